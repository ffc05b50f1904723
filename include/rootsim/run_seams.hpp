#pragma once
// The seams of a run (docs/architecture.md, "Seams"): where a test binary changes when a run checkpoints
// and ends it as a kill would. RunOutputs::growthSteps (the step loop of a run of one root and of a plate) asks
// stepSeams() once per run. rootsim_io's definition
// (src/io/run_seams.cpp) has none; the test binary rootsim_killable links its own definition instead
// (tests/seams/kill_at_step.cpp), so the production binary holds no test code.
#include <functional>

namespace rootsim {

struct StepSeams {
  // true: write a checkpoint after this growth step (instead of by wall time, output.checkpoint_every_s)
  std::function<bool(int step)> checkpointAfter;
  // called after each growth step's outputs and checkpoint, before the progress callback
  std::function<void(int step)> afterStep;
};

StepSeams stepSeams();

}  // namespace rootsim
