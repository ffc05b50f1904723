#include "rootsim/run_dir.hpp"

#include <cstring>

#include "rootsim/errors.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
// a directory that an earlier run wrote (and that may therefore be replaced)
bool looksLikeRun(const fs::path& d) {
  std::error_code ec;
  if (!fs::is_directory(d, ec)) return false;
  if (fs::is_empty(d, ec)) return true;
  return fs::exists(d / "scene.toml", ec);
}
}  // namespace

RunDir::RunDir(const fs::path& dir) : final_(dir) {
  std::error_code ec;
  if (final_.empty()) throw SceneError("--out: empty output directory name");
  if (fs::exists(final_, ec) && !looksLikeRun(final_))
    throw SceneError("--out " + final_.string() +
                     ": exists and is not a rootsim run directory (no scene.toml); choose another folder");
  work_ = final_;
  work_ += ".partial";
  fs::remove_all(work_, ec);
  fs::create_directories(work_, ec);
  if (ec) throw SceneError("--out " + final_.string() + ": cannot create " + work_.string() + ": " + ec.message());
  // probe that the folder is writable now rather than at the end of a long run
  const fs::path probe = work_ / ".probe";
  std::ofstream p(probe);
  if (!p) throw SceneError("--out " + final_.string() + ": cannot write into " + work_.string());
  p.close();
  fs::remove(probe, ec);
}

RunDir::~RunDir() = default;

void RunDir::write(const std::string& name, const std::string& content) { writeFileAtomic(work_ / name, content); }

void RunDir::commit() {
  std::error_code ec;
  if (fs::exists(final_, ec)) {
    fs::remove_all(final_, ec);
    if (ec) throw RunError("cannot replace " + final_.string() + ": " + ec.message());
  }
  fs::rename(work_, final_, ec);
  if (ec) throw RunError("cannot rename " + work_.string() + " to " + final_.string() + ": " + ec.message());
  done_ = true;
}

void RunDir::fail(const std::string& error) {
  std::error_code ec;
  try {
    write("ERROR.txt", error + "\n");
  } catch (...) {
  }
  fs::path inc = final_;
  inc += ".incomplete";
  fs::remove_all(inc, ec);
  fs::rename(work_, inc, ec);
  done_ = true;
}

void writeFileAtomic(const fs::path& path, const std::string& content) {
  AtomicFile f(path);
  f.stream() << content;
  f.close();
}

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)) {
  tmp_ = path_;
  tmp_ += ".tmp";
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw RunError("cannot open " + tmp_.string() + " for writing: " + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (!closed_) {
    out_.close();
    std::error_code ec;
    fs::remove(tmp_, ec);
  }
}

void AtomicFile::close() {
  out_.flush();
  if (!out_) throw RunError("write error on " + tmp_.string());
  out_.close();
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) throw RunError("cannot rename " + tmp_.string() + " to " + path_.string() + ": " + ec.message());
  closed_ = true;
}

}  // namespace rootsim
