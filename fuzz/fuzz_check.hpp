#pragma once
// shared by the fuzz harnesses: what every input must end in. A harness returns normally for an input
// that was accepted or refused with a proper error; anything else aborts (libFuzzer and the replay
// driver report it as a crash): an exception other than SceneError, an empty or multi-line message,
// a signal, a hang (libFuzzer -timeout) or unbounded memory (-rss_limit_mb / -malloc_limit_mb).
#include <cstdio>
#include <cstdlib>
#include <string>

namespace rootsim::fuzz {

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz: %s\n", what.c_str());
  std::abort();
}

// a user-facing error: one non-empty line (the CLI prints it as "rootsim: error: <message>")
inline void checkMessage(const char* msg) {
  const std::string m = msg;
  if (m.empty()) fail("error with an empty message");
  for (unsigned char c : m)
    if (c == '\n' || c == '\r' || (c < 0x20 && c != '\t') || c == 0x7f)
      fail("error message is not one printable line: " + m);
}

}  // namespace rootsim::fuzz
