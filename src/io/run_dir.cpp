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

// the marker's list of a finished run: "file <path inside the run> <bytes>" per regular file
std::string fileList(const fs::path& dir) {
  std::vector<std::pair<std::string, std::uintmax_t>> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string rel = fs::relative(it->path(), dir, ec).generic_string();
    if (rel == kRunMarker) continue;
    files.emplace_back(rel, it->file_size(ec));
  }
  std::sort(files.begin(), files.end());
  std::string s;
  for (const auto& [name, bytes] : files) s += "file " + name + " " + std::to_string(bytes) + "\n";
  return s;
}
}  // namespace

void markRunFolder(const fs::path& dir) {
  writeFileAtomic(dir / kRunMarker, std::string("rootsim run directory ") + kVersion + "\n" + fileList(dir));
}

fs::path normaliseOutDir(const std::string& text) { return checkOutputName(text, "--out"); }

std::string whyNotWhole(const fs::path& dir) {
  std::ifstream in(dir / kRunMarker);
  if (!in) return dir.string() + ": no " + std::string(kRunMarker);
  std::string line;
  int listed = 0;
  while (std::getline(in, line)) {
    if (line.rfind("file ", 0) != 0) continue;
    const auto sp = line.rfind(' ');
    const std::string name = line.substr(5, sp - 5);
    std::uintmax_t bytes = 0;
    try {
      bytes = std::stoull(line.substr(sp + 1));
    } catch (const std::exception&) {
      return (dir / kRunMarker).string() + ": malformed line '" + printable(line) + "'";
    }
    std::error_code ec;
    const fs::path f = dir / name;
    if (!fs::is_regular_file(fs::symlink_status(f, ec))) return f.string() + " is missing";
    const std::uintmax_t have = fs::file_size(f, ec);
    if (ec || have != bytes)
      return f.string() + " holds " + std::to_string(have) + " bytes, not the " + std::to_string(bytes) + " its run wrote";
    ++listed;
  }
  if (listed == 0) return dir.string() + ": its marker lists no files (written by an older rootsim, or not finished)";
  return "";
}

RunDir::RunDir(const fs::path& dir, const RunDirOptions& opt, PartialRun partial)
    : final_(normaliseOutDir(dir.string())) {
  std::error_code ec;
  // held until the run is committed or failed: a second process on this run directory is refused
  lock_ = OutputLock(final_, "--out");
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
  // the marker lists every file and its size: a sweep counts a point complete only when they are whole
  writeFileAtomic(work_ / kRunMarker, std::string("rootsim run directory ") + kVersion + "\n" + fileList(work_));
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
