#pragma once
// runs the rootsim binary (ROOTSIM_BINARY, set by CMake) with arguments; exit code and all its output
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace rootsim::test {

struct Result {
  int code;
  std::string out;  // stdout + stderr
};

inline Result runBinary(const std::string& binary, const std::string& args) {
  const std::string cmd = binary + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}
inline Result run(const std::string& args) { return runBinary(ROOTSIM_BINARY, args); }

}  // namespace rootsim::test
