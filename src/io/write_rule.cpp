// The write rule every command follows (write_rule.hpp; docs/outputs.md "What rootsim replaces")
#include "rootsim/write_rule.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>

#include "rootsim/errors.hpp"
#include "rootsim/version.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// rootsim's working names: a folder or file being written, failed, moved aside, a lock
constexpr std::array<const char*, 5> kWorkingSuffixes = {".partial", ".incomplete", ".replaced", ".tmp",
                                                        ".rootsim-lock"};
// the longest name rootsim derives from an output name: ".<name>.rootsim-lock" and "<name>.incomplete"
constexpr std::size_t kNameMax = 255;
constexpr std::size_t kDerivedExtra = 14;  // "." + ".rootsim-lock"

// leftovers of an atomic write a kill interrupted: "<name>.tmp", "<name>.tmp<pid>-<thread>"
std::string stripTemp(const std::string& name) {
  const auto t = name.rfind(".tmp");
  if (t == std::string::npos || t == 0) return name;
  for (std::size_t i = t + 4; i < name.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i])) && name[i] != '-') return name;
  return name.substr(0, t);
}

bool isLockFile(const std::string& name) { return name.size() > 14 && name[0] == '.' && endsWith(name, ".rootsim-lock"); }

// every name a run (and `run --movie`, `render`, `modes`) writes into its directory
constexpr std::array<const char*, 17> kRunEntries = {
    "modes.csv",      "modes.vtp",      "trajectory.bin", ".rootsim-run",   "scene.toml",     "timeseries.csv",
    "shape.csv",      "summary.json",   "result.csv",     "trajectory.csv", "trajectory.pvd", "vtk",
    "movie.mp4",      "final_top.png",  "ERROR.txt",      "checkpoint.bin", "movie.mp4.partial"};

// and what a plate's run writes besides (docs/plate.md, Outputs): roots/ holds one run directory per root
constexpr std::array<const char*, 5> kPlateEntries = {"plate.csv", "plate_timeseries.csv", "plate.pvd", "plate_view.png",
                                                      "plate_scan.png"};

bool isRunEntry(const fs::path& dir, const std::string& name) {
  const std::string base = stripTemp(name);
  for (const char* e : kRunEntries)
    if (base == e) return true;
  for (const char* e : kPlateEntries)
    if (base == e) return true;
  if (name == "roots") {
    std::error_code ec;
    const fs::path roots = dir / name;
    if (!fs::is_directory(fs::symlink_status(roots, ec))) return false;
    for (const auto& e : fs::directory_iterator(roots, ec))
      if (!whyNotOurs(e.path(), runFolder()).empty()) return false;
    return !ec;
  }
  return false;
}

// a run directory inside a sweep folder: DIR, DIR.partial, DIR.incomplete, DIR.replaced of a run
bool isSweepEntry(const fs::path& dir, const std::string& name) {
  if (name == ".rootsim-sweep" || name == "table.csv" || isLockFile(name)) return true;
  // table.csv.<host>.<pid>: a shard's table being renamed into place
  if (name.rfind("table.csv.", 0) == 0) return true;
  std::error_code ec;
  const fs::path p = dir / name;
  if (!fs::is_directory(fs::symlink_status(p, ec))) return false;
  return whyNotOurs(p, runFolder()).empty();
}

bool isFrameEntry(const fs::path&, const std::string& name) {
  if (name == ".rootsim-frames") return true;
  const std::string base = stripTemp(name);
  // frame_NNNNN.png
  if (base.size() < 14 || base.rfind("frame_", 0) != 0 || !endsWith(base, ".png")) return false;
  for (std::size_t i = 6; i + 4 < base.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(base[i]))) return false;
  return true;
}

// what `analyze` writes into its folder (docs/experiments.md)
bool isAnalysisEntry(const fs::path&, const std::string& name) {
  const std::string base = stripTemp(name);
  return base == ".rootsim-analysis" || base == "analysis.csv" || base == "analysis.json" || base == "plants.csv" ||
         base == "plants.json" || base == "growth.csv" || base == "growth.json";
}

// what `export --paraview DIR` writes (docs/paraview.md): step_NNNNNN.vtp, root.pvd, plate.vtp, the script
bool isParaviewEntry(const fs::path&, const std::string& name) {
  const std::string base = stripTemp(name);
  if (base == ".rootsim-paraview" || base == "root.pvd" || base == "plate.vtp" || base == "open_in_paraview.py")
    return true;
  // step_NNNNNN.vtp
  if (base.size() < 10 || base.rfind("step_", 0) != 0 || !endsWith(base, ".vtp")) return false;
  for (std::size_t i = 5; i + 4 < base.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(base[i]))) return false;
  return true;
}

bool isFigureFile(const std::string& base, const char* stem) {
  for (const char* ext : {".pdf", ".svg", ".png"})
    if (base == std::string(stem) + ext) return true;
  return false;
}

// what `compare` writes (docs/experiments.md): compare.json, compare.csv, the picture
bool isCompareEntry(const fs::path&, const std::string& name) {
  const std::string base = stripTemp(name);
  return base == ".rootsim-compare" || base == "compare.json" || base == "compare.csv" || isFigureFile(base, "compare");
}

// what `fit` writes (docs/experiments.md): its files, the best fit's picture, the landscape, and runs/,
// the sweep folder of its evaluations
bool isFitEntry(const fs::path& dir, const std::string& name) {
  if (isLockFile(name)) return true;
  const std::string base = stripTemp(name);
  if (base == ".rootsim-fit" || base == "fit.json" || base == "evaluations.csv" || base == "base.toml" ||
      base == "design.toml" || base == "best.toml" || isFigureFile(base, "compare") || isFigureFile(base, "landscape"))
    return true;
  if (name != "runs") return false;
  std::error_code ec;
  return fs::is_directory(fs::symlink_status(dir / name, ec)) && whyNotOurs(dir / name, sweepFolder()).empty();
}

fs::path absoluteNormal(const fs::path& p) {
  std::error_code ec;
  fs::path a = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) a = fs::absolute(p).lexically_normal();
  // "a/b/" -> "a/b"
  if (!a.empty() && a.filename().empty()) a = a.parent_path();
  return a;
}

// is `inner` the same path as `outer` or inside it?
bool contains(const fs::path& outer, const fs::path& inner) {
  const fs::path o = absoluteNormal(outer), i = absoluteNormal(inner);
  auto oi = o.begin(), ii = i.begin();
  for (; oi != o.end(); ++oi, ++ii) {
    if (oi->empty()) continue;
    if (ii == i.end() || *oi != *ii) return false;
  }
  return true;
}

// what a path that exists is, for messages: "a symbolic link", "a FIFO", ...
std::string kindOf(fs::file_status st) {
  switch (st.type()) {
    case fs::file_type::symlink: return "a symbolic link";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::character:
    case fs::file_type::block: return "a device";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::directory: return "a folder";
    case fs::file_type::regular: return "a file";
    default: return "not a regular file";
  }
}

// the output must not be an input, hold one, or lie inside one (but for the names an input receives)
void checkNotInput(const fs::path& out, const WriteRule& rule, const std::string& flag) {
  for (const WriteInput& in : rule.inputs) {
    if (in.path.empty()) continue;
    if (contains(out, in.path))
      throw SceneError(flag + " " + out.string() + ": " +
                       (absoluteNormal(out) == absoluteNormal(in.path) ? "is " : "contains ") + in.path.string() +
                       ", which this command reads; write the output somewhere of its own");
    if (in.contentRead && contains(in.path, out)) {
      const bool direct = absoluteNormal(out).parent_path() == absoluteNormal(in.path);
      bool received = false;
      for (const std::string& r : in.receives) received = received || (direct && out.filename() == r);
      if (!received)
        throw SceneError(flag + " " + out.string() + ": inside " + in.path.string() +
                         ", which this command reads; write the output somewhere else");
    }
  }
}

// a file of rootsim's by its place: a name rootsim writes, in a folder of rootsim's
bool ownedByFolder(const fs::path& file) {
  const fs::path dir = absoluteNormal(file).parent_path();
  const std::string name = file.filename().string();
  for (const FolderSpec* spec : {&runFolder(), &framesFolder()}) {
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(dir / spec->marker, ec)) && spec->owns(dir, name)) return true;
  }
  return false;
}

// a process-wide table of the locks held, so that a path locked twice in one process shares one lock
struct HeldLock {
  int fd = -1;
  int count = 0;
};
std::mutex& lockMutex() {
  static std::mutex m;
  return m;
}
std::map<std::string, HeldLock>& heldLocks() {
  static std::map<std::string, HeldLock> m;
  return m;
}

std::string holderOf(const fs::path& lockFile) {
  std::ifstream in(lockFile);
  std::string word, pid;
  in >> word >> word >> pid;  // "rootsim lock <pid>"
  return pid.empty() ? std::string("unknown") : pid;
}

}  // namespace

const FolderSpec& runFolder() {
  static const FolderSpec s{".rootsim-run", "rootsim run directory", isRunEntry};
  return s;
}
const FolderSpec& sweepFolder() {
  static const FolderSpec s{".rootsim-sweep", "rootsim sweep folder", isSweepEntry};
  return s;
}
const FolderSpec& framesFolder() {
  static const FolderSpec s{".rootsim-frames", "rootsim frame folder", isFrameEntry};
  return s;
}

const FolderSpec& analysisFolder() {
  static const FolderSpec s{".rootsim-analysis", "rootsim analysis folder", isAnalysisEntry};
  return s;
}
const FolderSpec& compareFolder() {
  static const FolderSpec s{".rootsim-compare", "rootsim compare folder", isCompareEntry};
  return s;
}
const FolderSpec& fitFolder() {
  static const FolderSpec s{".rootsim-fit", "rootsim fit folder", isFitEntry};
  return s;
}
const FolderSpec& paraviewFolder() {
  static const FolderSpec s{".rootsim-paraview", "rootsim ParaView folder", isParaviewEntry};
  return s;
}

WriteInput workingFolder() { return WriteInput{fs::current_path(), {}, false}; }

std::string whyNotOurs(const fs::path& dir, const FolderSpec& spec) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(dir, ec);
  if (!fs::is_directory(st)) return dir.string() + " exists and is " + kindOf(st) + ", not a " + spec.what;
  if (!fs::is_regular_file(fs::symlink_status(dir / spec.marker, ec)))
    return dir.string() + " exists and is not a " + std::string(spec.what) + " (no " + spec.marker +
           "); rootsim never replaces or writes into folders it did not write: choose another path";
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!spec.owns(dir, name))
      return dir.string() + " holds " + name + ", which rootsim did not write; move it away or choose another path";
  }
  if (ec) return "cannot list " + dir.string() + ": " + ec.message();
  return "";
}

fs::path checkOutputName(const std::string& text, const std::string& flag) {
  if (text.empty()) throw SceneError(flag + ": empty path (give a file or folder name)");
  fs::path p = fs::path(text).lexically_normal();
  if (!p.empty() && p.filename().empty()) p = p.parent_path();
  const std::string s = p.string();
  if (s.empty() || s == "." || s == ".." || p == p.root_path() || p.filename() == "..")
    throw SceneError(flag + " " + text + ": not a name of its own (give a new file or folder, e.g. runs/my_run)");
  const std::string name = p.filename().string();
  if (name.size() + kDerivedExtra > kNameMax)
    throw SceneError(flag + " " + text.substr(0, 40) + "...: its last part is " + std::to_string(name.size()) +
                     " bytes; at most " + std::to_string(kNameMax - kDerivedExtra) +
                     " (rootsim adds up to 14 bytes for its working names, file systems allow 255)");
  for (const char* suffix : kWorkingSuffixes)
    if (endsWith(name, suffix))
      throw SceneError(flag + " " + text + ": names ending in " + suffix +
                       " are rootsim's working names (interrupted, failed or replaced outputs); choose another name");
  return p;
}

void claimFile(const fs::path& file, const WriteRule& rule, const std::string& flag) {
  checkOutputName(file.string(), flag);
  checkNotInput(file, rule, flag);
  std::error_code ec;
  const fs::path dir = fs::absolute(file, ec).parent_path();
  if (!fs::is_directory(dir, ec)) throw SceneError(flag + " " + file.string() + ": folder " + dir.string() + " not found");
  // the working names beside it must be free or rootsim's too (an MP4 is streamed into FILE.partial)
  for (const char* suffix : {"", ".partial"}) {
    fs::path p = file;
    p += suffix;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (!fs::exists(st)) continue;
    if (!fs::is_regular_file(st))
      throw SceneError(flag + " " + file.string() + ": " + p.string() + " exists and is " + kindOf(st) +
                       "; rootsim writes only regular files of its own (a link, device or FIFO is never written through)");
    if (!carriesSignature(p) && !ownedByFolder(p))
      throw SceneError(flag + " " + file.string() + ": " + p.string() +
                       " exists and was not written by rootsim; rootsim never replaces files it did not write: "
                       "choose another name or move it away");
    if (!rule.force)
      throw SceneError(flag + " " + file.string() + ": " + p.string() +
                       " exists (written by rootsim earlier); pass --force to replace it");
  }
}

bool claimFolder(const fs::path& dir, const FolderSpec& spec, const WriteRule& rule, const std::string& flag,
                 bool replaces) {
  checkOutputName(dir.string(), flag);
  checkNotInput(dir, rule, flag);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(dir, ec))) return false;
  if (std::string why = whyNotOurs(dir, spec); !why.empty()) throw SceneError(flag + " " + dir.string() + ": " + why);
  if (replaces && !rule.force)
    throw SceneError(flag + " " + dir.string() + ": holds earlier output of rootsim; pass --force to replace it");
  return true;
}

void createOwnFolder(const fs::path& dir, const FolderSpec& spec) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw SceneError("cannot create " + dir.string() + ": " + ec.message());
  const fs::path marker = dir / spec.marker;
  if (fs::is_regular_file(fs::symlink_status(marker, ec))) return;
  // the marker first: from now on the folder is recognisably rootsim's. Writing it also probes that
  // the folder is writable now rather than at the end of a long run: no permission is bad usage (exit
  // 2); a full disk is a failed run (exit 1)
  const int fd = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) {
    const int err = errno;
    if (err == EEXIST) return;  // another process (a shard) made it a moment ago
    if (err == ENOSPC || err == EDQUOT || err == EIO)
      throw RunError("cannot write into " + dir.string() + ": " + std::strerror(err));
    throw SceneError("cannot write into " + dir.string() + ": " + std::strerror(err));
  }
  const std::string text = std::string("rootsim ") + spec.what + " " + kVersion + "\n";
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int err = errno;
  ::close(fd);
  if (!ok) {
    fs::remove(marker, ec);
    throw RunError("cannot write into " + dir.string() + ": " + std::strerror(err));
  }
}

bool carriesSignature(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  const std::string sig = kOutputSignature;
  // streamed in blocks, each carrying the tail of the one before (a signature across a block edge)
  std::string buf(1 << 16, '\0'), carry;
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::string block = carry + buf.substr(0, static_cast<std::size_t>(in.gcount()));
    if (block.find(sig) != std::string::npos) return true;
    carry = block.size() >= sig.size() ? block.substr(block.size() - sig.size() + 1) : block;
  }
  return false;
}

fs::path lockFileOf(const fs::path& path) {
  const fs::path a = absoluteNormal(path);
  return a.parent_path() / ("." + a.filename().string() + ".rootsim-lock");
}

OutputLock::OutputLock(const fs::path& path, const std::string& flag) {
  const fs::path file = lockFileOf(path);
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw SceneError(flag + " " + path.string() + ": cannot create " + file.parent_path().string() + ": " + ec.message());
  const std::string key = file.string();
  std::lock_guard<std::mutex> g(lockMutex());
  auto& held = heldLocks();
  if (auto it = held.find(key); it != held.end()) {
    ++it->second.count;
    key_ = key;
    return;
  }
  // open, lock, and check that the file locked is still the one at the path: a holder removes it when
  // it releases, so a lock taken on a removed file is retried on the new one
  for (int attempt = 0; attempt < 50; ++attempt) {
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0)
      throw SceneError(flag + " " + path.string() + ": cannot create its lock " + file.string() + ": " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err == EWOULDBLOCK)
        throw SceneError(flag + " " + path.string() + ": being written by another rootsim process (PID " +
                         holderOf(file) + "); wait for it to finish, or stop it");
      throw SceneError(flag + " " + path.string() + ": cannot lock " + file.string() + ": " + std::strerror(err));
    }
    struct stat a {}, b {};
    if (::fstat(fd, &a) == 0 && ::stat(file.c_str(), &b) == 0 && a.st_ino == b.st_ino && a.st_dev == b.st_dev) {
      const std::string text = "rootsim lock " + std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
        // the PID is for messages only: a lock whose file cannot hold it still locks
      }
      held[key] = HeldLock{fd, 1};
      key_ = key;
      return;
    }
    ::close(fd);
  }
  throw SceneError(flag + " " + path.string() + ": cannot take the lock " + file.string() + " (it keeps changing)");
}

OutputLock::~OutputLock() { release(); }

OutputLock::OutputLock(OutputLock&& o) noexcept : key_(std::move(o.key_)) { o.key_.clear(); }

OutputLock& OutputLock::operator=(OutputLock&& o) noexcept {
  if (this != &o) {
    release();
    key_ = std::move(o.key_);
    o.key_.clear();
  }
  return *this;
}

void OutputLock::release() {
  if (key_.empty()) return;
  std::lock_guard<std::mutex> g(lockMutex());
  auto& held = heldLocks();
  auto it = held.find(key_);
  if (it != held.end() && --it->second.count == 0) {
    // removed while still held: a process waiting on this file then sees it is gone and retries
    ::unlink(key_.c_str());
    ::close(it->second.fd);
    held.erase(it);
  }
  key_.clear();
}

void replaceFolder(const fs::path& work, const fs::path& final, const FolderSpec& spec) {
  std::error_code ec;
  fs::path old;
  if (fs::exists(fs::symlink_status(final, ec))) {
    if (std::string why = whyNotOurs(final, spec); !why.empty()) throw RunError("cannot replace: " + why);
    old = final;
    old += ".replaced";
    if (fs::exists(fs::symlink_status(old, ec))) {
      if (std::string why = whyNotOurs(old, spec); !why.empty()) throw RunError("cannot replace " + final.string() + ": " + why);
      fs::remove_all(old, ec);
    }
    fs::rename(final, old, ec);
    if (ec) throw RunError("cannot move " + final.string() + " aside: " + ec.message());
  }
  fs::rename(work, final, ec);
  if (ec) {
    const std::string msg = "cannot rename " + work.string() + " to " + final.string() + ": " + ec.message();
    if (!old.empty()) fs::rename(old, final, ec);
    throw RunError(msg);
  }
  if (!old.empty()) {
    // rootsim's own earlier output, read-only or not: made writable, then removed
    for (auto it = fs::recursive_directory_iterator(old, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
      if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
    fs::permissions(old, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(old, ec);
    if (ec) throw RunError("wrote " + final.string() + " but cannot remove the earlier one moved to " + old.string() + ": " + ec.message());
  }
}

StagedFolder::StagedFolder(const fs::path& dir, const FolderSpec& spec, const WriteRule& rule, const std::string& flag)
    : spec_(&spec), final_(checkOutputName(dir.string(), flag)) {
  lock_ = OutputLock(final_, flag);
  claimFolder(final_, spec, rule, flag, true);
  work_ = final_;
  work_ += ".partial";
  std::error_code ec;
  if (fs::exists(fs::symlink_status(work_, ec))) {
    // an earlier attempt that did not finish: rootsim's, so it is discarded (nothing else at that name)
    if (std::string why = whyNotOurs(work_, spec); !why.empty()) throw SceneError(flag + " " + dir.string() + ": " + why);
    fs::remove_all(work_, ec);
    if (ec) throw SceneError(flag + " " + dir.string() + ": cannot remove the unfinished " + work_.string() + ": " + ec.message());
  }
  createOwnFolder(work_, spec);
}

void StagedFolder::commit() { replaceFolder(work_, final_, *spec_); }

}  // namespace rootsim
