#pragma once
// Scene and sweep helpers shared by the io tests: the message a scene text or a sweep file is refused
// with ("(no error)" when accepted)
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/sweep.hpp"

namespace rootsim::test {

// the error of a scene text named scenes/t.toml with these --set overrides
inline std::string errorOf(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parseScene(text, "scenes/t.toml", sets);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// the error of a sweep file
inline std::string sweepError(const std::string& file) {
  try {
    loadSweep(file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace rootsim::test
