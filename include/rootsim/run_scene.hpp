#pragma once
// One scene -> one run directory (what `rootsim run` does without a movie; sweeps and figures use it).
#include <functional>
#include <string>

#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"

namespace rootsim {

// runs one parsed scene into a run directory (what `rootsim run` does, without a movie); returns wall
// time; throws SceneError (bad output path, before anything runs) or the run's error. progress is called
// after every growth step (with the first root's record); when it throws RunInterrupted the run stops
// there and DIR.partial stays. A scene of one root runs as a plate of one seedling, its files at the run
// directory's top; a plate's (docs/plate.md, Outputs) in a folder roots/NAME per root, each a run
// directory of that root alone, and the plate's files beside them. Both checkpoint and resume alike.
double runSceneToDir(const Scene& scene, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress);

}  // namespace rootsim
