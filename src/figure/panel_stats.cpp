// The statistics of the panels' claims: tolerance checks, medians, counts, zero crossings, spacings.
#include "panel_stats.hpp"

#include <algorithm>
#include <cmath>

namespace rootsim::fig {

bool within(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string countWithin(const std::vector<double>& v, double lo, double hi) {
  int k = 0, n = 0;
  for (double x : v)
    if (std::isfinite(x)) { ++n; k += within(x, lo, hi); }
  return std::to_string(k) + " of " + std::to_string(n) + " runs within";
}

std::vector<double> zeroCrossings(const std::vector<double>& t, const std::vector<double>& y, double t0) {
  std::vector<double> z;
  for (size_t i = 1; i < t.size(); ++i)
    if (t[i - 1] >= t0 && y[i - 1] * y[i] < 0) z.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-y[i - 1]) / (y[i] - y[i - 1]));
  return z;
}

double meanSpacing(const std::vector<double>& z) {
  return z.size() >= 2 ? (z.back() - z.front()) / static_cast<double>(z.size() - 1) : NAN;
}

}  // namespace rootsim::fig
