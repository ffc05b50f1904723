#pragma once
// The two kinds of failure a user sees (SPEC.md): bad input exits 2, a failed run exits 1.
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

}  // namespace rootsim
