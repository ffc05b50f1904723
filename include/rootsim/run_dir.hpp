#pragma once
// A run directory written atomically (SPEC.md): files go into DIR.partial/, each through a temporary
// file and a rename; commit() renames DIR.partial to DIR (replacing an older run there), fail() keeps
// what was written as DIR.incomplete/ with ERROR.txt. A killed run leaves only DIR.partial/.
#include <filesystem>
#include <fstream>
#include <string>

namespace rootsim {

class RunDir {
 public:
  // throws SceneError (exit 2) when DIR cannot be created or holds something that is not a run
  explicit RunDir(const std::filesystem::path& dir);
  ~RunDir();
  RunDir(const RunDir&) = delete;
  RunDir& operator=(const RunDir&) = delete;

  // where files are being written now
  const std::filesystem::path& work() const { return work_; }
  const std::filesystem::path& final() const { return final_; }
  // writes name atomically inside the working directory; throws RunError on I/O failure
  void write(const std::string& name, const std::string& content);
  void commit();
  void fail(const std::string& error);

 private:
  std::filesystem::path final_, work_;
  bool done_ = false;
};

// writes path atomically (temp file in the same folder, then rename); throws RunError
void writeFileAtomic(const std::filesystem::path& path, const std::string& content);

// streams a large file to path.tmp and renames it on close(); throws RunError
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  std::ofstream& stream() { return out_; }
  void close();

 private:
  std::filesystem::path path_, tmp_;
  std::ofstream out_;
  bool closed_ = false;
};

}  // namespace rootsim
