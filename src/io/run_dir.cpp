#include "rootsim/run_dir.hpp"

#include <array>
#include <cerrno>
#include <cstring>

#include "rootsim/errors.hpp"
#include "rootsim/version.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
// every name a run (and `run --movie`) writes into its directory; anything else in it is the user's
constexpr std::array<const char*, 17> kRunEntries = {
    "modes.csv",      "modes.vtp",      "trajectory.bin",
    kRunMarker,       "scene.toml",     "timeseries.csv", "shape.csv",    "summary.json",
    "result.csv",     "trajectory.csv", "trajectory.pvd", "vtk",          "movie.mp4",
    "final_top.png",  "ERROR.txt",      "checkpoint.bin", "movie.mp4.partial"};

bool isRunEntry(const std::string& name) {
  for (const char* e : kRunEntries)
    if (name == e) return true;
  // leftovers of an atomic write interrupted by a kill: "<run entry>.tmp"
  const auto tmp = name.rfind(".tmp");
  if (tmp != std::string::npos && tmp + 4 == name.size()) return isRunEntry(name.substr(0, tmp));
  return false;
}

// is `inner` the same path as `outer` or inside it (both made absolute and normal)?
bool contains(const fs::path& outer, const fs::path& inner) {
  std::error_code ec;
  const fs::path o = fs::weakly_canonical(fs::absolute(outer, ec), ec);
  const fs::path i = fs::weakly_canonical(fs::absolute(inner, ec), ec);
  auto oi = o.begin(), ii = i.begin();
  for (; oi != o.end(); ++oi, ++ii) {
    if (oi->empty()) continue;  // trailing separator
    if (ii == i.end() || *oi != *ii) return false;
  }
  return true;
}

// removes a run directory we are allowed to remove; "" or why not
std::string removeRun(const fs::path& dir) {
  if (std::string why = whyNotReplaceable(dir); !why.empty()) return why;
  std::error_code ec;
  fs::remove_all(dir, ec);
  return ec ? "cannot remove " + dir.string() + ": " + ec.message() : "";
}

fs::path sibling(const fs::path& dir, const char* suffix) {
  fs::path p = dir;
  p += suffix;
  return p;
}
}  // namespace

fs::path normaliseOutDir(const std::string& text) {
  if (text.empty()) throw SceneError("--out: empty output directory name");
  fs::path p = fs::path(text).lexically_normal();
  // "out/" normalises to "out/" (an empty last component): drop it
  if (!p.empty() && p.filename().empty()) p = p.parent_path();
  const std::string s = p.string();
  if (s.empty() || s == "." || s == ".." || p == p.root_path() || p.filename() == "..")
    throw SceneError("--out " + text + ": not a run directory name (give a new folder, e.g. runs/my_run)");
  return p;
}

std::string whyNotReplaceable(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec)))
    return dir.string() + " exists and is not a directory";
  if (!fs::is_regular_file(fs::symlink_status(dir / kRunMarker, ec)))
    return dir.string() + " exists and is not a rootsim run directory (no " + std::string(kRunMarker) +
           "); rootsim never replaces folders it did not write: choose another --out";
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!isRunEntry(name))
      return dir.string() + " holds " + name + ", which no rootsim run writes; move it away or choose another --out";
  }
  if (ec) return "cannot list " + dir.string() + ": " + ec.message();
  return "";
}

RunDir::RunDir(const fs::path& dir, const RunDirOptions& opt, PartialRun partial)
    : final_(normaliseOutDir(dir.string())) {
  std::error_code ec;
  for (const auto& p : opt.protect)
    if (!p.empty() && contains(final_, p))
      throw SceneError("--out " + dir.string() + ": contains " + p.string() +
                       "; a run directory must be a folder of its own (e.g. runs/my_run)");
  work_ = sibling(final_, ".partial");
  // an earlier complete run: replaced only with --force, and only if it is one (a resumed run was
  // started with that permission)
  if (fs::exists(fs::symlink_status(final_, ec))) {
    if (std::string why = whyNotReplaceable(final_); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
    if (!opt.force && partial != PartialRun::Continue)
      throw SceneError("--out " + dir.string() + ": holds an earlier run; pass --force to replace it");
  }
  if (partial == PartialRun::Continue) {
    if (std::string why = whyNotReplaceable(work_); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
    return;
  }
  // an interrupted run (killed): discarded only with --force
  if (fs::exists(fs::symlink_status(work_, ec))) {
    if (std::string why = whyNotReplaceable(work_); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
    if (!opt.force && partial != PartialRun::Discard)
      throw SceneError("--out " + dir.string() + ": " + work_.string() +
                       " holds an interrupted run; pass --resume to continue it from its last checkpoint, or "
                       "--force to discard it and start again");
    if (std::string why = removeRun(work_); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
  }
  fs::create_directories(work_, ec);
  if (ec) throw SceneError("--out " + dir.string() + ": cannot create " + work_.string() + ": " + ec.message());
  // the marker first: from now on this folder is recognisably ours; writing it also probes that the
  // folder is writable now rather than at the end of a long run
  std::ofstream m(work_ / kRunMarker, std::ios::binary);
  m << "rootsim run directory " << kVersion << "\n";
  m.close();
  if (!m) {
    fs::remove(work_ / kRunMarker, ec);
    fs::remove(work_, ec);
    throw SceneError("--out " + dir.string() + ": cannot write into " + work_.string());
  }
}

RunDir::~RunDir() = default;

void RunDir::write(const std::string& name, const std::string& content) { writeFileAtomic(work_ / name, content); }

void RunDir::commit() {
  std::error_code ec;
  // an earlier run at DIR (checked replaceable when we started; checked again): moved aside, replaced,
  // then removed, so a failure in between never leaves neither
  fs::path old;
  if (fs::exists(fs::symlink_status(final_, ec))) {
    if (std::string why = whyNotReplaceable(final_); !why.empty()) throw RunError("cannot replace: " + why);
    old = sibling(final_, ".replaced");
    if (fs::exists(fs::symlink_status(old, ec))) {
      if (std::string why = removeRun(old); !why.empty()) throw RunError("cannot replace " + final_.string() + ": " + why);
    }
    fs::rename(final_, old, ec);
    if (ec) throw RunError("cannot move " + final_.string() + " aside: " + ec.message());
  }
  fs::rename(work_, final_, ec);
  if (ec) {
    const std::string msg = "cannot rename " + work_.string() + " to " + final_.string() + ": " + ec.message();
    if (!old.empty()) fs::rename(old, final_, ec);
    throw RunError(msg);
  }
  if (!old.empty()) removeRun(old);
  // a failed attempt of an earlier run is obsolete once this one is complete
  const fs::path inc = sibling(final_, ".incomplete");
  if (fs::exists(fs::symlink_status(inc, ec))) removeRun(inc);
  done_ = true;
}

void RunDir::fail(const std::string& error) {
  std::error_code ec;
  try {
    write("ERROR.txt", error + "\n");
  } catch (...) {
  }
  const fs::path inc = sibling(final_, ".incomplete");
  // an older DIR.incomplete is replaced only if it is ours; otherwise the failed run stays DIR.partial
  if (fs::exists(fs::symlink_status(inc, ec)) && !removeRun(inc).empty()) {
    done_ = true;
    return;
  }
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

AtomicFile::AtomicFile(fs::path path, std::uintmax_t bytes) : path_(std::move(path)) {
  tmp_ = path_;
  tmp_ += ".tmp";
  std::error_code ec;
  // a kill after the file was closed (renamed) and before the run was committed: continue it
  if (!fs::exists(tmp_, ec) && fs::is_regular_file(path_, ec)) fs::rename(path_, tmp_, ec);
  const std::uintmax_t have = fs::is_regular_file(tmp_, ec) ? fs::file_size(tmp_, ec) : 0;
  if (ec || !fs::is_regular_file(tmp_) || have < bytes)
    throw SceneError(tmp_.string() + ": missing or shorter (" + std::to_string(have) + " bytes) than the checkpoint says (" +
                     std::to_string(bytes) + " bytes); rerun with --force to discard the interrupted run");
  fs::resize_file(tmp_, bytes, ec);
  if (ec) throw RunError("cannot truncate " + tmp_.string() + ": " + ec.message());
  out_.open(tmp_, std::ios::binary | std::ios::app);
  if (!out_) throw RunError("cannot open " + tmp_.string() + " for appending: " + std::strerror(errno));
}

std::uintmax_t AtomicFile::size() const {
  std::error_code ec;
  const std::uintmax_t n = fs::file_size(tmp_, ec);
  if (ec) throw RunError("cannot read the size of " + tmp_.string() + ": " + ec.message());
  return n;
}

AtomicFile::~AtomicFile() {
  if (!closed_) {
    out_.close();
    std::error_code ec;
    fs::remove(tmp_, ec);
  }
}

void AtomicFile::flush() {
  out_.flush();
  if (!out_) {
    const int err = errno;
    throw RunError("write error on " + path_.string() + " (disk full?): " + std::strerror(err));
  }
}

void AtomicFile::close() {
  out_.flush();
  if (!out_) throw RunError("write error on " + path_.string() + " (disk full?): " + std::strerror(errno));
  out_.close();
  if (!out_) throw RunError("write error on " + path_.string() + " (disk full?): " + std::strerror(errno));
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) throw RunError("cannot rename " + tmp_.string() + " to " + path_.string() + ": " + ec.message());
  closed_ = true;
}

}  // namespace rootsim
