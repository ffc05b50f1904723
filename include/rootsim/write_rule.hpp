#pragma once
// The one rule for every command that writes files (docs/outputs.md, "What rootsim replaces"). Every
// output path goes through it before any work is done:
//  - a path that does not exist is written;
//  - a path that exists is replaced only if rootsim wrote it AND --force is given. rootsim wrote it
//    when it is a folder holding rootsim's marker of that kind and nothing but what rootsim writes
//    there, or a file carrying rootsim's signature (PNG, MP4: kOutputSignature), or a file rootsim
//    writes inside a folder of its own (movie.mp4 in a run directory);
//  - anything else at the path (a user's file, a device, a FIFO, a symbolic link, a folder holding a
//    file rootsim did not write) is refused with SceneError (exit 2);
//  - an output is never an input, never holds one, and is never inside one (a run directory being
//    read receives only the files listed for it: render's movie.mp4 and final_top.png);
//  - a path is locked while a process writes it (OutputLock), so a second process is refused.
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rootsim/signature.hpp"

namespace rootsim {

// a kind of folder rootsim writes: its marker file and the entries it may hold
struct FolderSpec {
  const char* marker;  // file written first into every such folder; its first line names the kind
  const char* what;    // "run directory", "sweep folder", ... for messages
  std::function<bool(const std::filesystem::path& dir, const std::string& name)> owns;  // is the entry rootsim's?
};
// a run directory (run, sweep points, figure runs): marker .rootsim-run, the files a run writes
const FolderSpec& runFolder();
// a sweep folder: marker .rootsim-sweep, run directories (checked), table.csv, locks
const FolderSpec& sweepFolder();
// a folder of PNG frames: marker .rootsim-frames, frame_NNNNN.png
const FolderSpec& framesFolder();
// the folder of `analyze`: marker .rootsim-analysis, analysis.csv, analysis.json
const FolderSpec& analysisFolder();
// the folder of `compare`: marker .rootsim-compare, compare.json, compare.csv, compare.{pdf,svg,png}
const FolderSpec& compareFolder();
// the folder of `fit`: marker .rootsim-fit, fit.json, evaluations.csv, base.toml, design.toml, best.toml,
// compare.* and landscape.* pictures, and runs/ (a sweep folder: its evaluations' run directories)
const FolderSpec& fitFolder();
// a ParaView folder (export --paraview): marker .rootsim-paraview, step_NNNNNN.vtp, root.pvd, plate.vtp,
// open_in_paraview.py (docs/paraview.md)
const FolderSpec& paraviewFolder();

// what a command reads: never replaced nor held by an output; a folder whose content is read (a run
// directory) is also never written into, except for the names it receives
struct WriteInput {
  std::filesystem::path path;
  std::vector<std::string> receives;  // file names the command may write inside it (a folder)
  bool contentRead = true;            // false: only the path itself must survive (the working folder)
};

// the permissions of one command
struct WriteRule {
  bool force = false;               // --force: replace what rootsim wrote earlier
  std::vector<WriteInput> inputs;   // the scene or sweep file, the run directories read, the working folder
};

// the working folder, as an input (no output may be it or hold it)
WriteInput workingFolder();

// "" when dir is a folder of this kind that rootsim wrote and that holds nothing foreign, else why not
std::string whyNotOurs(const std::filesystem::path& dir, const FolderSpec& spec);

// the name checks shared by every output: not empty, not ".", "..", "/" or a name ending in "..", not
// one of rootsim's working names (.partial, .incomplete, .replaced, .tmp, .rootsim-lock endings), short
// enough for its working siblings (255 bytes per name); throws SceneError("FLAG PATH: ...")
std::filesystem::path checkOutputName(const std::string& text, const std::string& flag);

// an output file (a movie, a picture): its folder exists; if the file exists it is a regular file that
// rootsim wrote, and rule.force is set; it is not an input nor inside one (but for a name the input
// receives). Throws SceneError naming the flag and the path.
void claimFile(const std::filesystem::path& file, const WriteRule& rule, const std::string& flag);

// an output folder of this kind: new, or rootsim's of this kind with nothing foreign in it (and then
// replaced only with rule.force when `replaces`); not an input, not holding one, not inside one.
// Returns whether it exists. Throws SceneError.
bool claimFolder(const std::filesystem::path& dir, const FolderSpec& spec, const WriteRule& rule,
                 const std::string& flag, bool replaces);

// creates dir (and its parents) and writes spec's marker into it when it has none; throws SceneError
// when the folder cannot be created or written (permissions), RunError on a full disk
void createOwnFolder(const std::filesystem::path& dir, const FolderSpec& spec);

// does the file carry rootsim's signature (kOutputSignature in its bytes: PNG tEXt, MP4 comment)?
bool carriesSignature(const std::filesystem::path& file);

// An advisory lock on an output path, held while this process writes it: flock() on the hidden file
// ".<name>.rootsim-lock" beside it, so it dies with the process (a killed holder never blocks) and is
// removed when released. A second process is refused with SceneError naming the holder's PID. Locks
// of one path taken again in the same process (a run locking its directory, then its movie) share it.
class OutputLock {
 public:
  OutputLock() = default;
  // creates the path's parent folder if needed; throws SceneError when another process holds the lock
  OutputLock(const std::filesystem::path& path, const std::string& flag);
  ~OutputLock();
  OutputLock(OutputLock&& o) noexcept;
  OutputLock& operator=(OutputLock&& o) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  void release();

 private:
  std::string key_;  // the lock file's absolute path; empty: nothing held
};

// the lock file of an output path
std::filesystem::path lockFileOf(const std::filesystem::path& path);

// A folder written whole or not at all (PNG frames): files go into DIR.partial (with the marker);
// commit() renames it to DIR, replacing an earlier DIR of rootsim's (claimFolder checked it); a
// failure leaves DIR.partial, which its name marks as incomplete.
class StagedFolder {
 public:
  StagedFolder(const std::filesystem::path& dir, const FolderSpec& spec, const WriteRule& rule, const std::string& flag);
  const std::filesystem::path& work() const { return work_; }
  const std::filesystem::path& final() const { return final_; }
  void commit();

 private:
  const FolderSpec* spec_;
  std::filesystem::path final_, work_;
  OutputLock lock_;
};

// replaces `final` by `work` (both folders of spec): the old one is moved aside to FINAL.replaced,
// the new one renamed, then the old removed (made writable first: it is rootsim's); throws RunError
void replaceFolder(const std::filesystem::path& work, const std::filesystem::path& final, const FolderSpec& spec);

}  // namespace rootsim
