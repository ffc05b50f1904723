#pragma once
// A run directory written atomically: files go into DIR.partial/, each through a temporary file and a
// rename; commit() renames DIR.partial to DIR, fail() keeps what was written as DIR.incomplete/ with
// ERROR.txt. A killed run leaves only DIR.partial/.
//
// The write rule (write_rule.hpp) decides what may be replaced: every run directory carries a marker
// file (kRunMarker) written first, recording every file with its size and SHA-256 when the run is
// committed (or failed), and an existing DIR, DIR.partial or DIR.incomplete is replaced only with
// --force and only when it holds that marker and nothing but the files it records, as recorded. Anything else is
// refused with a SceneError (exit 2) before the run starts. DIR is locked (OutputLock) from the
// constructor until commit() or fail(): a second process is refused naming the first one's PID.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "rootsim/write_rule.hpp"

namespace rootsim {

// the marker every run directory holds (its content: "rootsim run directory <version>")
inline constexpr const char* kRunMarker = ".rootsim-run";

// what may happen to an earlier run at the output path
struct RunDirOptions {
  // replace an earlier run directory (marker, nothing foreign) and discard an interrupted DIR.partial;
  // never touches a folder that is not a run directory
  bool force = false;
  // paths the output must not contain or be (the scene file, the working directory): replacing an
  // ancestor of them would delete them
  std::vector<std::filesystem::path> protect;
  // continue an interrupted run (DIR.partial) from its checkpoint (runSceneToDir); with force, a
  // checkpoint that cannot be used (corrupt, another scene) is discarded and the run starts again
  bool resume = false;
  // where a resumed run says what it did (continued from step K, or started again); may be empty
  std::function<void(const std::string&)> note;
};

// what the RunDir constructor does with an interrupted run DIR.partial
enum class PartialRun {
  Refuse,    // discard it with RunDirOptions::force, else refuse (SceneError)
  Continue,  // keep writing into it (resuming from its checkpoint)
  Discard    // remove it (a run directory, checked) and start again
};

// the --out path as the user meant it: "out/" -> "out", "./a/b/" -> "a/b"; throws SceneError for "",
// ".", "..", "/", paths ending in "..", rootsim's working names and names too long (checkOutputName)
std::filesystem::path normaliseOutDir(const std::string& text);

// "" when the finished run directory holds every file its marker lists, each with the content (size and
// SHA-256) the run wrote, and a plate's roots/NAME are whole too; else what is missing or changed
std::string whyNotWhole(const std::filesystem::path& dir);

// marks a finished run directory (RunDir::commit, a plate's roots/NAME): its marker records every file
// with its size and SHA-256 (recordFolder)
void markRunFolder(const std::filesystem::path& dir);

class RunDir {
 public:
  // validates the output path (see above) and creates DIR.partial; throws SceneError (exit 2)
  RunDir(const std::filesystem::path& dir, const RunDirOptions& opt, PartialRun partial = PartialRun::Refuse);
  ~RunDir();
  RunDir(const RunDir&) = delete;
  RunDir& operator=(const RunDir&) = delete;

  // where files are being written now
  const std::filesystem::path& work() const { return work_; }
  const std::filesystem::path& final() const { return final_; }
  // writes name atomically inside the working directory; throws RunError on I/O failure
  void write(const std::string& name, const std::string& content);
  // DIR.partial -> DIR (an earlier run there is moved aside first and removed only after the rename)
  void commit();
  // DIR.partial -> DIR.incomplete with ERROR.txt; never throws
  void fail(const std::string& error);

 private:
  std::filesystem::path final_, work_;
  OutputLock lock_;
  bool done_ = false;
};

// writes path atomically (temp file in the same folder, then rename); throws RunError
void writeFileAtomic(const std::filesystem::path& path, const std::string& content);

// streams a large file to path.tmp and renames it on close(); throws RunError
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  // continues a file a killed run was streaming (path.tmp, or path if it was already closed), cut back
  // to its first `bytes` bytes (where a checkpoint saw it); throws SceneError when it is missing or shorter
  AtomicFile(std::filesystem::path path, std::uintmax_t bytes);
  ~AtomicFile();
  std::ofstream& stream() { return out_; }
  // hands what was streamed to the system now; throws RunError naming the file when it cannot be written
  // (a full disk is noticed at the next flush, not at close() after the whole run)
  void flush();
  void close();
  // bytes handed to the system so far (call after flush())
  std::uintmax_t size() const;

 private:
  std::filesystem::path path_, tmp_;
  std::ofstream out_;
  bool closed_ = false;
};

}  // namespace rootsim
