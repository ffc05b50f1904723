// The production run has no seams (run_seams.hpp). This file holds nothing else, so that a test binary's
// own stepSeams() replaces it at link time.
#include "rootsim/run_seams.hpp"

namespace rootsim {

StepSeams stepSeams() { return {}; }

}  // namespace rootsim
