#include "rootsim/run_dir.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "rootsim/errors.hpp"
#include "rootsim/version.hpp"
#include "rootsim/write_rule.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
fs::path sibling(const fs::path& dir, const char* suffix) {
  fs::path p = dir;
  p += suffix;
  return p;
}

// removes a run directory we are allowed to remove; "" or why not
std::string removeRun(const fs::path& dir) {
  if (std::string why = whyNotOurs(dir, runFolder()); !why.empty()) return why;
  std::error_code ec;
  fs::remove_all(dir, ec);
  return ec ? "cannot remove " + dir.string() + ": " + ec.message() : "";
}

}  // namespace

void markRunFolder(const fs::path& dir) { recordFolder(dir, runFolder()); }

fs::path normaliseOutDir(const std::string& text) { return checkOutputName(text, "--out"); }

std::string whyNotWhole(const fs::path& dir) {
  std::ifstream in(dir / kRunMarker);
  if (!in) return dir.string() + ": no " + std::string(kRunMarker);
  std::string line;
  int listed = 0;
  while (std::getline(in, line)) {
    if (line.rfind("file ", 0) != 0) continue;
    // "file <path> <bytes or -> <sha256>"
    const auto h = line.rfind(' ');
    const auto z = h == std::string::npos || h < 6 ? std::string::npos : line.rfind(' ', h - 1);
    if (z == std::string::npos || z < 5) return (dir / kRunMarker).string() + ": malformed line '" + printable(line) + "'";
    const std::string name = line.substr(5, z - 5);
    std::error_code ec;
    const fs::path f = dir / name;
    if (!fs::is_regular_file(fs::symlink_status(f, ec))) return f.string() + " is missing";
    if (std::string why = whyNotRecorded(dir, kRunMarker, name); !why.empty()) return f.string() + ": " + why;
    ++listed;
  }
  if (listed == 0) return dir.string() + ": its marker lists no files (written by an older rootsim, or not finished)";
  // a plate's roots/NAME: run directories of their own, each whole by its own marker
  std::error_code ec;
  if (fs::is_directory(fs::symlink_status(dir / "roots", ec)))
    for (const auto& e : fs::directory_iterator(dir / "roots", ec))
      if (std::string why = whyNotWhole(e.path()); !why.empty()) return why;
  return "";
}

RunDir::RunDir(const fs::path& dir, const RunDirOptions& opt, PartialRun partial)
    : final_(normaliseOutDir(dir.string())) {
  std::error_code ec;
  // held until the run is committed or failed: a second process on this run directory is refused
  lock_ = lockOutput(final_, "--out");
  WriteRule rule;
  rule.force = opt.force;
  for (const auto& p : opt.protect) rule.inputs.push_back(WriteInput{p, {}, false});
  claimFolder(final_, runFolder(), rule, "--out", false);
  work_ = sibling(final_, ".partial");
  // an earlier complete run: replaced only with --force (a resumed run was started with that permission)
  if (fs::exists(fs::symlink_status(final_, ec)) && !opt.force && partial != PartialRun::Continue)
    throw SceneError("--out " + dir.string() + ": holds an earlier run; pass --force to replace it");
  // a failed run: kept (its ERROR.txt says why) unless --force
  const fs::path inc = sibling(final_, ".incomplete");
  if (fs::exists(fs::symlink_status(inc, ec))) {
    if (std::string why = whyNotOurs(inc, runFolder()); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
    if (!opt.force)
      throw SceneError("--out " + dir.string() + ": " + inc.string() +
                       " holds a failed run (its ERROR.txt says why); pass --force to replace it, or choose another --out");
  }
  if (partial == PartialRun::Continue) {
    if (std::string why = whyNotOurs(work_, runFolder()); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
    return;
  }
  // an interrupted run (killed): discarded only with --force
  if (fs::exists(fs::symlink_status(work_, ec))) {
    if (std::string why = whyNotOurs(work_, runFolder()); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
    if (!opt.force && partial != PartialRun::Discard)
      throw SceneError("--out " + dir.string() + ": " + work_.string() +
                       " holds an interrupted run; pass --resume to continue it from its last checkpoint, or "
                       "--force to discard it and start again");
    if (std::string why = removeRun(work_); !why.empty()) throw SceneError("--out " + dir.string() + ": " + why);
  }
  createOwnFolder(work_, runFolder());
}

RunDir::~RunDir() = default;

void RunDir::write(const std::string& name, const std::string& content) { writeFileAtomic(work_ / name, content); }

void RunDir::commit() {
  // the marker records every file, its size and its hash: a sweep counts a point complete only when they
  // are whole, and --force later replaces only what is still as recorded
  markRunFolder(work_);
  // an earlier run at DIR (checked replaceable when we started) is moved aside, replaced, then removed
  replaceFolder(work_, final_, runFolder());
  // a failed attempt of an earlier run is obsolete once this one is complete (--force was given)
  std::error_code ec;
  const fs::path inc = sibling(final_, ".incomplete");
  if (fs::exists(fs::symlink_status(inc, ec))) removeRun(inc);
  done_ = true;
  lock_.release();
}

void RunDir::fail(const std::string& error) {
  std::error_code ec;
  try {
    write("ERROR.txt", error + "\n");
    markRunFolder(work_);  // what the failed run wrote is rootsim's: --force may replace it
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
  lock_.release();
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
