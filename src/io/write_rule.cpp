// The write rule every command follows (write_rule.hpp; docs/outputs.md "What rootsim replaces")
#include "rootsim/write_rule.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <tinyxml2.h>
#include <zlib.h>

#include "rootsim/content_hash.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/run_dir.hpp"
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

// leftovers of an atomic write a kill interrupted: "<name>.tmp", "<name>.tmp<pid>-<thread>", and of one
// written atomically under a working name of its own ("table.csv.tmp<pid>-<host>.tmp"): every such suffix
std::string stripTemp(const std::string& name) {
  const auto t = name.rfind(".tmp");
  if (t == std::string::npos || t == 0) return name;
  for (std::size_t i = t + 4; i < name.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i])) && name[i] != '-') return name;
  return stripTemp(name.substr(0, t));
}

bool isLockFile(const std::string& name) { return name.size() > 14 && name[0] == '.' && endsWith(name, ".rootsim-lock"); }

// an entry another rootsim process changes while this one lists the folder: gone since the listing
// (renamed into place, removed), or a folder rootsim is creating under its working name (holding nothing
// but its marker, or nothing yet)
bool transientEntry(const fs::path& p) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!fs::exists(st)) return true;
  const std::string name = p.filename().string();
  if (!fs::is_directory(st) || stripTemp(name) == name) return false;
  for (const auto& e : fs::directory_iterator(p, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(".rootsim-", 0) != 0 || isLockFile(n)) return false;
  }
  return !ec;
}

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
      if (!transientEntry(e.path()) && !whyNotOurs(e.path(), runFolder()).empty()) return false;
    return !ec;
  }
  return false;
}

// a run directory inside a sweep folder: DIR, DIR.partial, DIR.incomplete, DIR.replaced of a run
bool isSweepEntry(const fs::path& dir, const std::string& name) {
  // table.csv.tmp<pid>-<host's number>: a shard's table being renamed into place
  if (name == ".rootsim-sweep" || stripTemp(name) == "table.csv" || isLockFile(name)) return true;
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
         base == "plants.json" || base == "growth.csv" || base == "growth.json" || base == "curves.csv";
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
  return base == ".rootsim-compare" || base == "compare.json" || base == "compare.csv" || base == "timelapse.csv" ||
         isFigureFile(base, "compare");
}

// what `fit` writes (docs/experiments.md): its files, the best fit's picture, the landscape, and runs/,
// the sweep folder of its evaluations; by group: groups/, keys.* and compare_NAME.*
bool isFitEntry(const fs::path& dir, const std::string& name) {
  if (isLockFile(name)) return true;
  const std::string base = stripTemp(name);
  if (base == ".rootsim-fit" || base == "fit.json" || base == "evaluations.csv" || base == "base.toml" ||
      base == "design.toml" || base == "best.toml" || isFigureFile(base, "compare") || isFigureFile(base, "landscape") ||
      isFigureFile(base, "keys"))
    return true;
  // a fit by group's compare picture of each group: compare_NAME.*
  if (base.rfind("compare_", 0) == 0 && base.find('.') != std::string::npos && isFigureFile(base, base.substr(0, base.rfind('.')).c_str()))
    return true;
  std::error_code ec;
  if (name == "groups") {
    // a fit by group (fit --groups): one fit folder per group, and their locks
    if (!fs::is_directory(fs::symlink_status(dir / name, ec))) return false;
    for (const auto& e : fs::directory_iterator(dir / name, ec)) {
      const std::string g = e.path().filename().string();
      if (isLockFile(g)) continue;
      if (transientEntry(e.path())) continue;
      std::error_code entry;  // an entry's own query: the listing's error stays the listing's
      if (e.is_symlink(entry) || !e.is_directory(entry) || !whyNotOurs(e.path(), fitFolder()).empty()) return false;
    }
    return !ec;
  }
  if (name != "runs") return false;
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

// the folder of rootsim's a file lies in (its marker beside it), or nullptr
const FolderSpec* ownFolderOf(const fs::path& file) {
  const fs::path dir = absoluteNormal(file).parent_path();
  for (const FolderSpec* spec : {&runFolder(), &framesFolder()}) {
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(dir / spec->marker, ec))) return spec;
  }
  return nullptr;
}

// a folder still being written: DIR.partial or inside one (its files are recorded when it is finished)
bool beingWritten(const fs::path& dir) {
  for (const auto& part : absoluteNormal(dir))
    if (endsWith(part.string(), ".partial")) return true;
  return false;
}

// files whose content varies legitimately between two identical runs: recorded without those fields
bool hasTimingFields(const std::string& rel) { return rel == "summary.json" || endsWith(rel, "/summary.json"); }

// summary.json without its wall time: the value of every "wall_time_s" key dropped
std::string withoutTiming(std::string text) {
  const std::string key = "\"wall_time_s\"";
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + key.size())) {
    std::size_t v = text.find(':', at + key.size());
    if (v == std::string::npos) break;
    std::size_t e = v + 1;
    while (e < text.size() && text[e] != ',' && text[e] != '}' && text[e] != '\n') ++e;
    text.erase(v + 1, e - v - 1);
  }
  return text;
}

// the size and hash a record line holds for the file as it is now ("" hash: unreadable)
std::pair<std::string, std::string> recordValues(const fs::path& file, const std::string& rel) {
  if (hasTimingFields(rel)) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return {"-", ""};
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return {"-", sha256Hex(withoutTiming(text))};
  }
  std::uintmax_t size = 0;
  std::string hash = sha256File(file, &size);
  return {std::to_string(size), hash};
}

std::string recordLine(const fs::path& dir, const std::string& rel) {
  const auto [size, hash] = recordValues(dir / rel, rel);
  if (hash.empty()) throw RunError("cannot read " + (dir / rel).string() + " to record it");
  return "file " + rel + " " + size + " " + hash + "\n";
}

struct Recorded {
  std::string size, hash;
};
// the marker's head line and its records by path
std::string readRecord(const fs::path& marker, std::map<std::string, Recorded>* files) {
  std::ifstream in(marker, std::ios::binary);
  std::string head, line;
  std::getline(in, head);
  while (std::getline(in, line)) {
    if (line.rfind("file ", 0) != 0) continue;
    const auto h = line.rfind(' ');
    if (h == std::string::npos || h < 5) continue;
    const auto z = line.rfind(' ', h - 1);
    if (z == std::string::npos || z < 5) continue;
    (*files)[line.substr(5, z - 5)] = Recorded{line.substr(z + 1, h - z - 1), line.substr(h + 1)};
  }
  return head;
}

// does the folder hold a marker of its own kind (a nested run or sweep folder)?
bool hasOwnMarker(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(".rootsim-", 0) == 0 && !endsWith(n, ".rootsim-lock") && e.is_regular_file(ec)) return true;
  }
  return false;
}

// the process's and the folder's lock around a read-modify-write of a marker, and around a check of a
// folder's files against it (shards share folders). A thread that holds a folder's lock already (a check
// reaching a folder it is recording) shares it: flock conflicts between two descriptors of one process
struct RecordLock {
  int fd = -1;
  fs::path key;
  std::unique_lock<std::recursive_mutex> g;
  explicit RecordLock(const fs::path& dir) : g(mutex()) {
    fs::path k = absoluteNormal(dir);
    std::vector<fs::path>& held = heldHere();
    if (std::find(held.begin(), held.end(), k) != held.end()) return;
    fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) ::flock(fd, LOCK_EX);
    key = std::move(k);
    held.push_back(key);
  }
  ~RecordLock() {
    if (key.empty()) return;
    if (fd >= 0) ::close(fd);
    std::vector<fs::path>& held = heldHere();
    held.erase(std::find(held.begin(), held.end(), key));
  }
  RecordLock(const RecordLock&) = delete;
  RecordLock& operator=(const RecordLock&) = delete;
  static std::recursive_mutex& mutex() {
    static std::recursive_mutex m;
    return m;
  }
  static std::vector<fs::path>& heldHere() {
    thread_local std::vector<fs::path> held;
    return held;
  }
};

// writes a marker through a temporary name of this process and thread, then one rename
void writeMarker(const fs::path& marker, const std::string& text) {
  std::ostringstream name;
  name << marker.filename().string() << ".tmp" << ::getpid() << "-" << std::hash<std::thread::id>{}(std::this_thread::get_id()) % 100000;
  const fs::path tmp = marker.parent_path() / name.str();
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw RunError("cannot write " + marker.string() + " (disk full?): " + std::strerror(errno));
    }
  }
  std::error_code ec;
  fs::rename(tmp, marker, ec);
  if (ec) throw RunError("cannot write " + marker.string() + ": " + ec.message());
}

// "" when every regular file below sub (a folder inside the finished folder dir, or dir itself for
// its top level) is recorded with its content; else the first that is not, and why
std::string whyNotAllRecorded(const fs::path& dir, const FolderSpec& spec, const std::map<std::string, Recorded>& rec,
                              const fs::path& sub) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(sub, ec)) {
    const fs::path p = e.path();
    const std::string name = p.filename().string();
    // an entry's own queries: an entry that vanished since the listing (renamed or removed by its
    // writer) is skipped, and its error is not the listing's
    std::error_code entry;
    const std::string rel = fs::relative(p, dir, entry).generic_string();
    const fs::file_status st = fs::symlink_status(p, entry);
    if (!fs::exists(st)) continue;
    if (rel == spec.marker || isLockFile(name) || stripTemp(name) != name) continue;
    // an unfinished file of a writer that was killed (movie.mp4.partial): a working name of rootsim's
    if (endsWith(name, ".partial") && sub == dir && fs::is_regular_file(st) && spec.owns(dir, name)) continue;
    if (fs::is_directory(st)) {
      if (hasOwnMarker(p)) continue;  // a nested folder of rootsim's: judged by its own marker (spec.owns)
      if (std::string why = whyNotAllRecorded(dir, spec, rec, p); !why.empty()) return why;
      continue;
    }
    if (!fs::is_regular_file(st))
      return dir.string() + " holds " + rel + ", " + kindOf(st) + " rootsim did not make; move it away or delete it";
    const auto it = rec.find(rel);
    if (it == rec.end())
      return dir.string() + " holds " + rel + ", which rootsim did not write (its " + spec.marker +
             " does not list it); move it away or delete it";
    const auto [size, hash] = recordValues(p, rel);
    if (hash.empty() || it->second.hash != hash || (it->second.size != "-" && it->second.size != size))
      return dir.string() + " holds " + rel + ", changed since rootsim wrote it (its content differs from the record in " +
             spec.marker + "); it is yours now: move it away or delete it";
  }
  if (ec) return "cannot list " + sub.string() + ": " + ec.message();
  return "";
}

// the single-file signature checks registered from outside rootsim_io (MP4: the renderer's libavformat)
std::map<OutputFormat, SignatureCheck>& signatureChecks() {
  static std::map<OutputFormat, SignatureCheck> m;
  return m;
}
std::mutex& signatureMutex() {
  static std::mutex m;
  return m;
}

std::string readAll(const fs::path& file, std::uintmax_t limit, bool* tooBig) {
  std::error_code ec;
  const std::uintmax_t n = fs::file_size(file, ec);
  *tooBig = !ec && n > limit;
  if (ec || *tooBig) return "";
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// "sha256:<64 hex>" after the signature text, or ""
std::string hashIn(const std::string& text) {
  const auto at = text.find(" sha256:");
  if (at == std::string::npos || text.size() < at + 8 + 64) return "";
  return text.substr(at + 8, 64);
}

// RSML: line 1 the XML declaration, line 2 the comment "<!-- rootsim-output ... sha256:H ... -->" (H: the
// SHA-256 of every byte after line 2), and the whole file parses as XML with an <rsml> root
std::string whyNotSignedRsml(const fs::path& file) {
  bool tooBig = false;
  const std::string text = readAll(file, std::uintmax_t(1) << 30, &tooBig);
  if (tooBig) return "larger than any RSML file rootsim writes";
  const auto l1 = text.find('\n');
  const auto l2 = l1 == std::string::npos ? l1 : text.find('\n', l1 + 1);
  if (l2 == std::string::npos || text.compare(0, 5, "<?xml") != 0) return "not an RSML file (no XML declaration on line 1)";
  const std::string line2 = text.substr(l1 + 1, l2 - l1 - 1);
  const std::string head = std::string("<!-- ") + kOutputSignature + " ";
  if (line2.compare(0, head.size(), head) != 0 || !endsWith(line2, "-->"))
    return "its line 2 is not rootsim's comment";
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement() ||
      std::string(doc.RootElement()->Name()) != "rsml")
    return "it does not parse as RSML (XML with an <rsml> root)";
  const std::string want = hashIn(line2);
  if (!want.empty() && sha256Hex(std::string_view(text).substr(l2 + 1)) != want) return "changed since rootsim wrote it";
  return "";
}

std::uint32_t le32(const std::string& s, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 3])) << 24;
}
std::uint32_t be32(const std::string& s, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[at])) << 24 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 1])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 2])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 3]));
}

// GLB: the 12-byte header ("glTF", version 2, the file's length), a JSON chunk that parses, whose
// asset.generator is rootsim's signature; asset.extras.rootsim_bin_sha256, when there, is the BIN chunk's hash
std::string whyNotSignedGlb(const fs::path& file) {
  bool tooBig = false;
  const std::string b = readAll(file, std::uintmax_t(4) << 30, &tooBig);
  if (b.size() < 20 || b.compare(0, 4, "glTF") != 0 || le32(b, 4) != 2 || le32(b, 8) != b.size())
    return "not a binary glTF 2.0 file (GLB header)";
  const std::uint32_t jsonLen = le32(b, 12);
  if (le32(b, 16) != 0x4E4F534Au || 20 + std::size_t(jsonLen) > b.size()) return "not a GLB file (no JSON chunk)";
  const nlohmann::json j = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + jsonLen, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return "its JSON chunk does not parse";
  const auto asset = j.find("asset");
  if (asset == j.end() || !asset->is_object() || !asset->contains("generator") || !(*asset)["generator"].is_string() ||
      (*asset)["generator"].get<std::string>().rfind(std::string(kOutputSignature) + " ", 0) != 0)
    return "its asset.generator is not rootsim's";
  const auto extras = asset->find("extras");
  if (extras != asset->end() && extras->is_object() && extras->contains("rootsim_bin_sha256")) {
    const std::size_t bin = 20 + jsonLen;
    if (bin + 8 > b.size() || le32(b, bin + 4) != 0x004E4942u || bin + 8 + std::size_t(le32(b, bin)) > b.size())
      return "its BIN chunk is missing or cut short";
    const auto& h = (*extras)["rootsim_bin_sha256"];
    if (!h.is_string() || sha256Hex(std::string_view(b).substr(bin + 8, le32(b, bin))) != h.get<std::string>())
      return "changed since rootsim wrote it";
  }
  return "";
}

// PNG: the 8-byte PNG signature, chunks whose CRCs (zlib's crc32) hold, IHDR first, IEND last, a tEXt
// "Software" chunk holding rootsim's signature; "sha256:H" in it is the hash of the IDAT chunks' data
std::string whyNotSignedPng(const fs::path& file) {
  bool tooBig = false;
  const std::string b = readAll(file, std::uintmax_t(2) << 30, &tooBig);
  static const std::string magic("\x89PNG\r\n\x1a\n", 8);
  if (b.size() < 8 || b.compare(0, 8, magic) != 0) return "not a PNG file";
  std::string software;
  Sha256 idat;
  bool first = true, end = false;
  for (std::size_t at = 8; !end;) {
    if (at + 12 > b.size()) return "not a PNG file (cut short)";
    const std::uint32_t len = be32(b, at);
    if (len > b.size() - at - 12) return "not a PNG file (a chunk runs past its end)";
    const std::string type = b.substr(at + 4, 4);
    const auto crc = static_cast<std::uint32_t>(
        ::crc32(0, reinterpret_cast<const Bytef*>(b.data() + at + 4), static_cast<uInt>(len + 4)));
    if (crc != be32(b, at + 8 + len)) return "not a PNG file (chunk " + printable(type) + " fails its CRC)";
    if (first && type != "IHDR") return "not a PNG file (no IHDR first)";
    first = false;
    if (type == "tEXt") {
      const std::string body = b.substr(at + 8, len);
      const auto nul = body.find('\0');
      if (nul != std::string::npos && body.compare(0, nul, "Software") == 0) software = body.substr(nul + 1);
    } else if (type == "IDAT") {
      idat.update(b.data() + at + 8, len);
    }
    end = type == "IEND";
    at += 12 + len;
  }
  if (software.rfind(std::string(kOutputSignature) + " ", 0) != 0) return "its tEXt Software chunk is not rootsim's";
  const std::string want = hashIn(software);
  if (!want.empty() && idat.hex() != want) return "changed since rootsim wrote it";
  return "";
}

const char* formatName(OutputFormat f) {
  switch (f) {
    case OutputFormat::Rsml: return "RSML";
    case OutputFormat::Glb: return "GLB";
    case OutputFormat::Png: return "PNG";
    case OutputFormat::Mp4: return "MP4";
    case OutputFormat::InFolder: return "run";
  }
  return "?";
}

// a process-wide table of the locks held, so that a path locked twice in one process shares one lock
struct HeldLock {
  int fd = -1;
  int count = 0;
  std::thread::id owner;  // the thread that holds it: another thread of this process is refused
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
  // "rootsim lock <pid>" per holder: those still alive (a shard that ended leaves its line behind)
  std::ifstream in(lockFile);
  std::string line, pids, last;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string a, b;
    long pid = 0;
    if (!(words >> a >> b >> pid) || pid <= 0) continue;
    last = std::to_string(pid);
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) continue;  // gone, or on another host
    if ((", " + pids + ",").find(" " + last + ",") == std::string::npos) pids += (pids.empty() ? "" : ", ") + last;
  }
  if (pids.empty()) pids = last;
  return pids.empty() ? std::string("unknown") : pids;
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
    // the marker's own working name (writeMarker renames it into place) is the folder's, whatever its kind
    if (spec.owns(dir, name) || stripTemp(name) == spec.marker || transientEntry(e.path())) continue;
    // a folder of rootsim's inside (a sweep's run, a plate's roots/NAME, a fit's runs/): its own reason
    std::error_code entry;  // an entry's own queries: the listing's error stays the listing's
    for (const FolderSpec* inner : {&runFolder(), &sweepFolder()})
      if (e.is_directory(entry) && !e.is_symlink(entry) &&
          fs::is_regular_file(fs::symlink_status(e.path() / inner->marker, entry)))
        if (std::string why = whyNotOurs(e.path(), *inner); !why.empty()) return why;
    if (name == "roots" && e.is_directory(entry))
      for (const auto& r : fs::directory_iterator(e.path(), entry)) {
        if (transientEntry(r.path())) continue;
        if (std::string why = whyNotOurs(r.path(), runFolder()); !why.empty()) return why;
      }
    return dir.string() + " holds " + name + ", which rootsim did not write; move it away or delete it";
  }
  if (ec) return "cannot list " + dir.string() + ": " + ec.message();
  // a finished folder: every file as its marker records it
  if (beingWritten(dir)) return "";
  // read under the folder's record lock: a file another process renames into place and records (a
  // shard's table.csv) is seen with its record, never renamed and not yet recorded
  const RecordLock lock(dir);
  std::map<std::string, Recorded> rec;
  readRecord(dir / spec.marker, &rec);
  return whyNotAllRecorded(dir, spec, rec, dir);
}

std::string recordOf(const fs::path& dir, const char* marker, bool nested) {
  std::vector<std::string> rels;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const fs::path p = it->path();
    const std::string name = p.filename().string();
    // an entry's own queries: one that vanished since the listing is skipped, not the end of the listing
    std::error_code entry;
    if (it->is_directory(entry) && !it->is_symlink(entry)) {
      if (!nested && hasOwnMarker(p)) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(entry) || it->is_symlink(entry)) continue;
    const std::string rel = fs::relative(p, dir, entry).generic_string();
    if (rel == marker || isLockFile(name) || stripTemp(name) != name) continue;
    rels.push_back(rel);
  }
  if (ec) throw RunError("cannot list " + dir.string() + ": " + ec.message());
  std::sort(rels.begin(), rels.end());
  std::string s;
  for (const std::string& rel : rels) s += recordLine(dir, rel);
  return s;
}

void recordFolder(const fs::path& dir, const FolderSpec& spec, bool nested) {
  const RecordLock lock(dir);
  const std::string head = std::string(spec.what) + " " + kVersion + "\n";
  writeMarker(dir / spec.marker, head + recordOf(dir, spec.marker, nested));
}

void recordFiles(const fs::path& dir, const FolderSpec& spec, const std::vector<std::string>& rels,
                 const std::function<void()>& put) {
  const RecordLock lock(dir);
  if (put) put();
  std::map<std::string, Recorded> rec;
  std::string head = readRecord(dir / spec.marker, &rec);
  if (head.empty()) head = std::string(spec.what) + " " + kVersion;
  std::map<std::string, std::string> lines;
  for (const auto& [rel, r] : rec) lines[rel] = "file " + rel + " " + r.size + " " + r.hash + "\n";
  std::error_code ec;
  for (const std::string& rel : rels) {
    if (fs::is_regular_file(fs::symlink_status(dir / rel, ec)))
      lines[rel] = recordLine(dir, rel);
    else
      lines.erase(rel);  // written, then removed again: no longer rootsim's to replace
  }
  std::string text = head + "\n";
  for (const auto& [rel, line] : lines) text += line;
  writeMarker(dir / spec.marker, text);
}

void recordWritten(const std::vector<fs::path>& files) {
  for (const fs::path& f : files) {
    std::error_code ec;
    if (f.empty() || !fs::is_regular_file(fs::symlink_status(f, ec))) continue;
    const fs::path dir = absoluteNormal(f).parent_path();
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string n = e.path().filename().string();
      std::error_code entry;
      if (n.rfind(".rootsim-", 0) != 0 || isLockFile(n) || stripTemp(n) != n || !e.is_regular_file(entry)) continue;
      // the folder's kind is the marker's own head line: kept as it is
      const std::string marker = n;
      const FolderSpec named{marker.c_str(), "rootsim folder", nullptr};
      recordFiles(dir, named, {f.filename().string()});
      break;
    }
  }
}

std::string whyNotRecorded(const fs::path& dir, const char* marker, const std::string& rel) {
  const RecordLock lock(dir);
  std::map<std::string, Recorded> rec;
  readRecord(dir / marker, &rec);
  const auto it = rec.find(rel);
  if (it == rec.end()) return "rootsim did not write it (" + (dir / marker).string() + " does not list it)";
  const auto [size, hash] = recordValues(dir / rel, rel);
  if (hash.empty() || it->second.hash != hash || (it->second.size != "-" && it->second.size != size))
    return "changed since rootsim wrote it (its content differs from the record in " + (dir / marker).string() + ")";
  return "";
}

void registerSignatureCheck(OutputFormat format, SignatureCheck check) {
  std::lock_guard<std::mutex> g(signatureMutex());
  signatureChecks()[format] = std::move(check);
}

std::string whyNotSigned(const fs::path& file, OutputFormat format) {
  switch (format) {
    case OutputFormat::Rsml: return whyNotSignedRsml(file);
    case OutputFormat::Glb: return whyNotSignedGlb(file);
    case OutputFormat::Png: return whyNotSignedPng(file);
    case OutputFormat::Mp4: break;
    case OutputFormat::InFolder: return "not inside a folder of rootsim's";
  }
  SignatureCheck check;
  {
    std::lock_guard<std::mutex> g(signatureMutex());
    const auto it = signatureChecks().find(format);
    if (it != signatureChecks().end()) check = it->second;
  }
  if (!check) return std::string("no ") + formatName(format) + " reader in this program to tell whether rootsim wrote it";
  return check(file);
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

void claimFile(const fs::path& file, const WriteRule& rule, const std::string& flag, OutputFormat format) {
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
    // inside a folder of rootsim's: its marker's record decides; elsewhere the file's own signature
    std::string why;
    if (const FolderSpec* spec = ownFolderOf(p)) {
      // an unfinished movie.mp4.partial in a run directory is rootsim's working file; the rest by record
      const fs::path folder = absoluteNormal(p).parent_path();
      if (!(*suffix && spec->owns(folder, p.filename().string())))
        why = whyNotRecorded(folder, spec->marker, p.filename().string());
    }
    else if (*suffix)
      why = "an interrupted output rootsim cannot vouch for (a movie is signed when it is finished)";
    else
      why = whyNotSigned(p, format);
    if (!why.empty())
      throw SceneError(flag + " " + file.string() + ": " + p.string() + " exists and was not written by rootsim as it is (" +
                       formatName(format) + ": " + why + "); rootsim never replaces files it did not write: move it away or delete it");
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

namespace {
// writes the folder's marker into `dir`: no permission is bad usage (exit 2); a full disk is a failed run
// (exit 1). Writing it also probes that the folder is writable now rather than at the end of a long run
void writeFirstMarker(const fs::path& dir, const FolderSpec& spec, const fs::path& named) {
  const fs::path marker = dir / spec.marker;
  const int fd = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOSPC || err == EDQUOT || err == EIO)
      throw RunError("cannot write into " + named.string() + ": " + std::strerror(err));
    throw SceneError("cannot write into " + named.string() + ": " + std::strerror(err));
  }
  const std::string text = std::string(spec.what) + " " + kVersion + "\n";
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int err = errno;
  ::close(fd);
  if (!ok) {
    std::error_code ec;
    fs::remove(marker, ec);
    throw RunError("cannot write into " + named.string() + ": " + std::strerror(err));
  }
}
}  // namespace

void createOwnFolder(const fs::path& dir, const FolderSpec& spec) {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(dir / spec.marker, ec))) return;
  const fs::path full = absoluteNormal(dir);
  fs::create_directories(full.parent_path(), ec);
  if (ec) throw SceneError("cannot create " + full.parent_path().string() + ": " + ec.message());
  // the folder appears with its marker or not at all: made under a working name with the marker inside,
  // then renamed into place without replacing anything. Another process creating the same folder at the
  // same moment (the shards of a job array) sees either no folder or rootsim's, never an empty one
  std::ostringstream name;
  name << full.filename().string() << ".tmp" << ::getpid() << "-"
       << std::hash<std::thread::id>{}(std::this_thread::get_id()) % 100000;
  const fs::path work = full.parent_path() / name.str();
  fs::remove_all(work, ec);  // this process and thread's own leftover
  if (::mkdir(work.c_str(), 0755) != 0) {
    const int err = errno;
    if (err == ENOSPC || err == EDQUOT || err == EIO) throw RunError("cannot create " + dir.string() + ": " + std::strerror(err));
    throw SceneError("cannot create " + dir.string() + ": " + std::strerror(err));
  }
  try {
    writeFirstMarker(work, spec, dir);
  } catch (...) {
    fs::remove_all(work, ec);
    throw;
  }
  if (::renameat2(AT_FDCWD, work.c_str(), AT_FDCWD, full.c_str(), RENAME_NOREPLACE) == 0) return;
  const int err = errno;
  fs::remove_all(work, ec);
  if (err == EEXIST || err == ENOTEMPTY) {
    // made by another process a moment ago: used if it is rootsim's
    if (fs::is_regular_file(fs::symlink_status(dir / spec.marker, ec))) return;
    throw SceneError(dir.string() + " appeared while rootsim was creating it and is not a " + spec.what +
                     " (no " + spec.marker + "); rootsim never writes into folders it did not write: choose another path");
  }
  if (err != EINVAL && err != ENOSYS)
    throw RunError("cannot create " + dir.string() + ": " + std::strerror(err));
  // a file system without an exclusive rename (some network file systems): made in place, marker first
  if (::mkdir(full.c_str(), 0755) != 0 && errno != EEXIST)
    throw SceneError("cannot create " + dir.string() + ": " + std::strerror(errno));
  if (fs::is_regular_file(fs::symlink_status(dir / spec.marker, ec))) return;
  try {
    writeFirstMarker(full, spec, dir);
  } catch (const SceneError&) {
    if (fs::is_regular_file(fs::symlink_status(dir / spec.marker, ec))) return;  // another shard's, a moment ago
    throw;
  }
}

fs::path lockFileOf(const fs::path& path) {
  const fs::path a = absoluteNormal(path);
  return a.parent_path() / ("." + a.filename().string() + ".rootsim-lock");
}

namespace {
std::string heldMessage(const std::string& flag, const fs::path& path, const std::string& pid, bool thread) {
  return flag + " " + path.string() + ": being written by another rootsim " + (thread ? "thread of this process" : "process") +
         " (PID " + pid + "); wait for it to finish, or stop it";
}
}  // namespace

OutputLock::OutputLock(const fs::path& path, const std::string& flag, LockMode mode) {
  const fs::path file = lockFileOf(path);
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw SceneError(flag + " " + path.string() + ": cannot create " + file.parent_path().string() + ": " + ec.message());
  const std::string key = file.string();
  std::lock_guard<std::mutex> g(lockMutex());
  auto& held = heldLocks();
  if (auto it = held.find(key); it != held.end()) {
    // the same thread again shares its lock; another thread (Python threads writing one `out`) is refused
    if (it->second.owner != std::this_thread::get_id())
      throw SceneError(heldMessage(flag, path, std::to_string(::getpid()), true));
    ++it->second.count;
    key_ = key;
    return;
  }
  // open, lock, and check that the file locked is still the one at the path: the last holder removes it
  // when it releases, so a lock taken on a removed file is retried on the new one
  const int how = mode == LockMode::Shared ? LOCK_SH : LOCK_EX;
  for (int attempt = 0; attempt < 50; ++attempt) {
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0)
      throw SceneError(flag + " " + path.string() + ": cannot create its lock " + file.string() + ": " + std::strerror(errno));
    if (::flock(fd, how | LOCK_NB) != 0) {
      const int err = errno;
      struct stat a {}, b {};
      const bool moved = ::fstat(fd, &a) == 0 && (::stat(file.c_str(), &b) != 0 || a.st_ino != b.st_ino || a.st_dev != b.st_dev);
      ::close(fd);
      if (err == EWOULDBLOCK && moved) continue;  // its last holder was removing it: take the new one
      if (err == EWOULDBLOCK) {
        // a shared holder releasing checks with an exclusive try whether it is the last: wait that out
        if (mode == LockMode::Shared && attempt < 20) {
          ::usleep(5000);
          continue;
        }
        throw SceneError(heldMessage(flag, path, holderOf(file), false));
      }
      throw SceneError(flag + " " + path.string() + ": cannot lock " + file.string() + ": " + std::strerror(err));
    }
    struct stat a {}, b {};
    if (::fstat(fd, &a) == 0 && ::stat(file.c_str(), &b) == 0 && a.st_ino == b.st_ino && a.st_dev == b.st_dev) {
      // the PID is for messages only: a lock whose file cannot hold it still locks. Shared holders (the
      // shards of a sweep) each add theirs; messages name those still alive
      const std::string text = "rootsim lock " + std::to_string(::getpid()) + "\n";
      if (mode == LockMode::Exclusive) {
        if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
        }
      } else if (::lseek(fd, 0, SEEK_END) < 0 || ::write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
      }
      held[key] = HeldLock{fd, 1, std::this_thread::get_id()};
      key_ = key;
      return;
    }
    ::close(fd);
  }
  throw SceneError(flag + " " + path.string() + ": cannot take the lock " + file.string() + " (it keeps changing)");
}

OutputLock lockOutput(const fs::path& path, const std::string& flag, LockMode mode) { return OutputLock(path, flag, mode); }

std::string whyUnfinished(const fs::path& dir) {
  fs::path base = absoluteNormal(dir);
  const bool isPartial = endsWith(base.filename().string(), ".partial");
  if (isPartial) base = base.parent_path() / base.stem();
  fs::path partial = base;
  partial += ".partial";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(partial, ec))) return "";
  bool held = false;
  if (const int fd = ::open(lockFileOf(base).c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW); fd >= 0) {
    held = ::flock(fd, LOCK_SH | LOCK_NB) != 0;
    ::close(fd);
  }
  if (held) return partial.string() + " is being written by PID " + holderOf(lockFileOf(base)) + "; wait for it to finish";
  if (isPartial || !fs::exists(fs::symlink_status(base, ec)))
    return partial.string() + " is an interrupted run (no process is writing it): continue it with `rootsim run SCENE --out " +
           base.string() + " --resume`, or read a finished run";
  return "";
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
    // removed only by its last holder: an exclusive try tells (a shared holder of another process keeps
    // it, so an exclusive locker can never take a fresh file beside it); a process waiting on the
    // removed file sees it is gone and retries
    if (::flock(it->second.fd, LOCK_EX | LOCK_NB) == 0) ::unlink(key_.c_str());
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
  lock_ = lockOutput(final_, flag);
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

void StagedFolder::commit() {
  recordFolder(work_, *spec_);  // every file as written: --force later replaces only what is still so
  replaceFolder(work_, final_, *spec_);
}

}  // namespace rootsim
