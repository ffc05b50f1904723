#pragma once
// The statistics of the panels' claims: the referee's tolerances, medians and counts within them, zero
// crossings of a time series and the spacing of successive values.
#include <string>
#include <vector>

namespace rootsim::fig {

// the referee's tolerances: a scaling law holds when measured / predicted is within +-25 %;
// a ratio of two measured quantities that the paper says is 1 holds within 0.75 ... 1.33 (symmetric in log)
inline constexpr double kScaleLo = 0.75, kScaleHi = 1.25, kRatioLo = 0.75, kRatioHi = 1.33;
inline constexpr const char* kScaleTol = "±25 % (0.75 … 1.25)";
inline constexpr const char* kRatioTol = "0.75 … 1.33";
// v is finite and in [lo, hi]
bool within(double v, double lo, double hi);

// median of the finite values (NaN if none)
double median(std::vector<double> v);
// "k of n runs within": of the finite values, how many are in [lo, hi]
std::string countWithin(const std::vector<double>& v, double lo, double hi);

// times where y crosses zero, interpolated linearly, after time t0 [h]
std::vector<double> zeroCrossings(const std::vector<double>& t, const std::vector<double>& y, double t0);
// mean spacing of successive values (NaN if fewer than 2)
double meanSpacing(const std::vector<double>& z);

}  // namespace rootsim::fig
