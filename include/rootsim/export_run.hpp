#pragma once
// `rootsim export RUN_DIR` (docs/cli.md, docs/rsml.md): a saved run's root in other programs' formats.
// One command, one output flag per format; every output goes through the write rule.
#include <filesystem>
#include <string>
#include <vector>
#include "rootsim/limits.hpp"

namespace rootsim::app {

struct ExportOptions {
  static constexpr double kUnset = kUnsetFlag;  // a number flag not given (limits.hpp)
  std::string runDir;
  // outputs: at least one
  std::string rsml;       // --rsml FILE: RSML 1.0 (docs/rsml.md)
  std::string gltf;       // --gltf FILE.glb: glTF 2.0 (docs/gltf.md); every snapshot, animated, unless
                          // --at-h (a still) or --every-h (those snapshots, animated, in this one file)
  std::string paraview;   // --paraview DIR
  // which snapshots: the final one (default), the one nearest atH (ties to the earlier), or one every
  // everyH hours from the first (RSML then writes one file per time, glTF animates those snapshots in its
  // one file: docs/rsml.md, Choosing the time)
  double atH = kUnset;    // --at-h [h]
  double everyH = kUnset; // --every-h [h]
  bool force = false;     // replace outputs rootsim wrote earlier (never a file rootsim did not write)
  bool quiet = false;
};

// Bad flags, a missing or malformed run directory, an output the write rule refuses: SceneError (exit
// 2) before anything is written; a failed write RunError (exit 1). Returns 0. The paths written, in
// order (a series in time order), are appended to `written` when given.
int exportRunCommand(const ExportOptions& o, std::vector<std::filesystem::path>* written = nullptr);

}  // namespace rootsim::app
