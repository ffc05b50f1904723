#pragma once
// The one rule for every command that writes files (docs/outputs.md, "What rootsim replaces"). Every
// output path goes through it before any work is done:
//  - a path that does not exist is written;
//  - a path that exists is replaced only if rootsim wrote it AND --force is given. rootsim wrote a
//    folder when it holds rootsim's marker of that kind, and every file in it is one the marker
//    records with the content rootsim wrote (size and SHA-256: recordFiles); it wrote a single file
//    (RSML, GLB, PNG, MP4) when the file carries rootsim's signature in its format's metadata place
//    and that place parses as the format (whyNotSigned);
//  - anything else at the path (a user's file, a device, a FIFO, a symbolic link, a file edited after
//    rootsim wrote it, a file put beside rootsim's) is refused with SceneError (exit 2), naming it;
//  - an output is never an input, never holds one, and is never inside one (a run directory being
//    read receives only the files listed for it: render's movie.mp4 and final_top.png);
//  - a path is locked while a process writes it (lockOutput), so a second process, or a second thread
//    of this process, is refused naming the holder's PID.
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
// (a fit by group, fit --groups: fit.json and groups/NAME, a fit folder per group)
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

// "" when dir is a folder of this kind that rootsim wrote and that holds nothing foreign, else why not:
// every regular file in it (but the marker, lock files and interrupted temporaries) must be recorded in
// its marker with the size and SHA-256 it has now. A folder still being written (DIR.partial, or inside
// one) is judged by its file names alone: its files are recorded when it is finished.
std::string whyNotOurs(const std::filesystem::path& dir, const FolderSpec& spec);

// The marker's record. Line 1 names the kind ("rootsim <what> <version>"); then one line per file
// rootsim wrote there: "file <path inside the folder> <bytes> <sha256>". A file whose content varies
// legitimately between identical runs (summary.json's wall_time_s) is recorded without those fields:
// "file summary.json - <sha256 of the file without them>".
// records the files rels (paths inside dir) as they are now, keeping the other lines; under the folder's
// record lock, after running put (which may move a file into place) when given. Throws RunError.
void recordFiles(const std::filesystem::path& dir, const FolderSpec& spec, const std::vector<std::string>& rels,
                 const std::function<void()>& put = {});
// records every regular file below dir (but those in folders with a marker of their own, unless nested
// is set), replacing the record. Throws RunError.
void recordFolder(const std::filesystem::path& dir, const FolderSpec& spec, bool nested = false);
// records each of files (written just now) in the marker of the rootsim folder it lies in; a file
// elsewhere (a user's path) carries its own signature and is left as it is. Throws RunError.
void recordWritten(const std::vector<std::filesystem::path>& files);
// the record's lines "file <rel> <bytes> <sha256>" of every regular file below dir (see recordFolder)
std::string recordOf(const std::filesystem::path& dir, const char* marker, bool nested);
// "" when file (a path inside dir) is recorded in dir's marker with its present content, else why not
std::string whyNotRecorded(const std::filesystem::path& dir, const char* marker, const std::string& rel);

// the formats of single-file outputs: each carries rootsim's signature in its own metadata place
// (InFolder: a file rootsim writes only inside a folder of its own, whose record alone decides)
enum class OutputFormat { Rsml, Glb, Png, Mp4, InFolder };
// "" when file is a file of this format that rootsim wrote (its signature in the metadata place, that
// place parsing as the format, and, where the signature holds a content hash, the content matching
// it), else why not. MP4 is checked by the checker the renderer registers (no checker: not rootsim's).
std::string whyNotSigned(const std::filesystem::path& file, OutputFormat format);
using SignatureCheck = std::function<std::string(const std::filesystem::path&)>;
void registerSignatureCheck(OutputFormat format, SignatureCheck check);

// the name checks shared by every output: not empty, not ".", "..", "/" or a name ending in "..", not
// one of rootsim's working names (.partial, .incomplete, .replaced, .tmp, .rootsim-lock endings), short
// enough for its working siblings (255 bytes per name); throws SceneError("FLAG PATH: ...")
std::filesystem::path checkOutputName(const std::string& text, const std::string& flag);

// an output file (a movie, a picture): its folder exists; if the file exists it is a regular file that
// rootsim wrote, and rule.force is set; it is not an input nor inside one (but for a name the input
// receives). Throws SceneError naming the flag and the path.
// A file inside a folder of rootsim's (a run's final_top.png) is rootsim's when that folder's marker
// records it; elsewhere when it carries format's signature (whyNotSigned).
void claimFile(const std::filesystem::path& file, const WriteRule& rule, const std::string& flag, OutputFormat format);

// an output folder of this kind: new, or rootsim's of this kind with nothing foreign in it (and then
// replaced only with rule.force when `replaces`); not an input, not holding one, not inside one.
// Returns whether it exists. Throws SceneError.
bool claimFolder(const std::filesystem::path& dir, const FolderSpec& spec, const WriteRule& rule,
                 const std::string& flag, bool replaces);

// creates dir (and its parents) and writes spec's marker into it when it has none; throws SceneError
// when the folder cannot be created or written (permissions), RunError on a full disk
void createOwnFolder(const std::filesystem::path& dir, const FolderSpec& spec);

// An advisory lock on an output path, held while this process writes it: flock() on the hidden file
// ".<name>.rootsim-lock" beside it, so it dies with the process (a killed holder never blocks); the
// last holder removes it. A second process, or another thread of this one, is refused with SceneError
// naming the holder's PID. The same thread taking a path again (a run locking its directory, then
// resuming) shares the lock. Shared locks (the shards of one sweep folder) coexist with each other,
// never with an exclusive one.
enum class LockMode { Exclusive, Shared };
class OutputLock;
// the one way every command locks its output, before any work: creates the path's parent folder if
// needed; throws SceneError when another writer holds the lock
OutputLock lockOutput(const std::filesystem::path& path, const std::string& flag, LockMode mode = LockMode::Exclusive);

class OutputLock {
 public:
  OutputLock() = default;  // holds nothing
  ~OutputLock();
  OutputLock(OutputLock&& o) noexcept;
  OutputLock& operator=(OutputLock&& o) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  void release();

 private:
  friend OutputLock lockOutput(const std::filesystem::path& path, const std::string& flag, LockMode mode);
  OutputLock(const std::filesystem::path& path, const std::string& flag, LockMode mode);
  std::string key_;  // the lock file's absolute path; empty: nothing held
};

// the lock file of an output path
std::filesystem::path lockFileOf(const std::filesystem::path& path);

// "" when the run directory dir is neither being written nor an interrupted run, else why: "DIR.partial
// is being written by PID N" (dir or dir.partial, while its writer holds the lock), or that dir is an
// interrupted run to resume. Every command that reads a run directory asks first.
std::string whyUnfinished(const std::filesystem::path& dir);

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
