#pragma once
// The two kinds of failure a user sees (docs/cli.md): bad input exits 2, a failed run exits 1.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rootsim {

// bad scene, bad flag, unreadable or unwritable path: the message names the file and line or the flag
// and key, what was expected and what was found; the CLI prints it and exits 2
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// a run that started but failed (I/O during the run, rendering, encoding); exits 1
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// a run stopped on purpose between growth steps (Ctrl-C in Python, a cancelled sweep): not a failure, so
// the run directory is left as DIR.partial/ (like a killed run), without ERROR.txt
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// text from a file or the command line (a key, a value) as it may appear inside a one-line message:
// newline, tab and other control characters escaped (as \n, \t, \x01)
inline std::string printable(const std::string& s) {
  std::string o;
  for (unsigned char c : s) {
    if (c == '\n') o += "\\n";
    else if (c == '\t') o += "\\t";
    else if (c < 0x20 || c == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      o += b;
    } else o += static_cast<char>(c);
  }
  return o;
}

}  // namespace rootsim
