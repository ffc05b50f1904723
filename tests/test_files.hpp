#pragma once
// file helpers shared by the tests that run the binary: a fresh scratch folder and a whole file's bytes
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rootsim::test {

// a case that cannot run here says why on stdout; ctest's SKIP_REGULAR_EXPRESSION (tests/CMakeLists.txt)
// then reports it as skipped, never as passed
inline void skipCase(const std::string& why) {
  std::printf("rootsim-test-skipped: %s\n", why.c_str());
  std::fflush(stdout);
}

// an empty folder rootsim_<prefix>_<name>_<pid> in the temporary folder (emptied if it was there)
inline std::filesystem::path scratchDir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("rootsim_" + prefix + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// the bytes of a file ("" when it cannot be read)
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace rootsim::test
