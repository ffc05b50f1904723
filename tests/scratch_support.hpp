#pragma once
// A test's scratch folders: rootsim_<prefix>_<name>_<pid> in the temporary folder, emptied when made and
// removed when the test process ends (ctest runs hundreds of processes, each writing runs, frames and
// movies: left behind they fill a small disk within one suite). ROOTSIM_KEEP_SCRATCH=1 keeps them, to look
// at a failure's files.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <algorithm>
#include <vector>

namespace rootsim::test {

namespace detail {
struct ScratchFolders {
  std::vector<std::filesystem::path> made;
  ScratchFolders() = default;
  ScratchFolders(const ScratchFolders&) = delete;
  ScratchFolders& operator=(const ScratchFolders&) = delete;
  ~ScratchFolders() {
    const char* keep = std::getenv("ROOTSIM_KEEP_SCRATCH");
    if (keep && std::string(keep) == "1") return;
    for (const auto& d : made) {
      std::error_code ec;  // a folder a test removed itself, or cannot be removed, is left as it is
      std::filesystem::remove_all(d, ec);
    }
  }
};
inline ScratchFolders& scratchFolders() {
  static ScratchFolders folders;
  return folders;
}
}  // namespace detail

// an empty folder rootsim_<prefix>_<name>_<pid> in the temporary folder (emptied if it was there), removed
// when the process ends
inline std::filesystem::path scratchDir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("rootsim_" + prefix + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  auto& made = detail::scratchFolders().made;
  if (std::find(made.begin(), made.end(), d) == made.end()) made.push_back(d);
  return d;
}

}  // namespace rootsim::test
