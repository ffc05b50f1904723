#pragma once
// Numbers several analysis files use, defined once (the library is compiled in unity batches: a file's
// own copy would be a second definition in its batch)
#include <limits>

namespace rootsim {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

namespace app {

// a traced point's position uncertainty when its file gives no pixel size: one pixel of a 20 px/mm plate
// scan [mm] (compare's sigma, the growth match's)
inline constexpr double kDefaultSigmaMm = 0.05;
// the step at which compare, fit and render --trace resample a trace for its distances: a run's
// element [mm]
inline constexpr double kDistanceStepMm = 0.05;

}  // namespace app
}  // namespace rootsim
