#pragma once
// internal: how `render`, `montage` and `export` claim their outputs (what they read from a run directory:
// rootsim/run_snapshots.hpp)
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/movie.hpp"
#include "rootsim/run_snapshots.hpp"
#include "rootsim/write_rule.hpp"

namespace rootsim::app {

// the outputs of render and montage, checked by the write rule and locked until they are written
struct Outputs {
  std::vector<OutputLock> locks;
};
// the --mp4 file, the --final-png file and the --png-dir folder (each empty for none): none may be
// another or lie inside the frame folder; each is locked, then checked against rule (SceneError)
// (pngFlag: the flag that names png in messages)
Outputs claimOutputs(const std::string& mp4, const std::filesystem::path& png, const std::string& pngDir,
                     const WriteRule& rule, const char* pngFlag = "--final-png");

// stderr progress: one line per ~10 % of the frames; none when quiet
MovieProgress progressLines(bool quiet, const std::string& what);

}  // namespace rootsim::app
