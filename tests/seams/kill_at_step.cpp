// The run seams of the test binary rootsim_killable (run_seams.hpp): ROOTSIM_TEST_KILL="C:K" writes a
// checkpoint after growth step C and ends the process after step K (K >= C) with _Exit(137), as a kill
// would: nothing flushed, nothing renamed. Without the variable the binary behaves as rootsim.
#include <cstdio>
#include <cstdlib>

#include "rootsim/run_seams.hpp"

namespace rootsim {

StepSeams stepSeams() {
  int checkpointAt = -1, killAt = -1;
  const char* e = std::getenv("ROOTSIM_TEST_KILL");
  if (!e || std::sscanf(e, "%d:%d", &checkpointAt, &killAt) != 2) return {};
  StepSeams s;
  s.checkpointAfter = [checkpointAt](int step) { return step == checkpointAt; };
  s.afterStep = [killAt](int step) {
    if (step == killAt) std::_Exit(137);
  };
  return s;
}

}  // namespace rootsim
