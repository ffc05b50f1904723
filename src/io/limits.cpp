#include "rootsim/limits.hpp"

#include <cmath>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"

namespace rootsim {

namespace {
// a count as text: "1000000", or "1e+30" beyond what a long holds
std::string countText(double n) {
  if (std::isfinite(n) && n >= 0 && n < 9e15) return std::to_string(static_cast<long long>(std::ceil(n)));
  return numberText(n);
}
}  // namespace

std::string rangeText(const NumberRange& r) {
  std::string s = "in " + std::string(r.loOpen ? "(" : "[") + numberText(r.lo) + ", " + numberText(r.hi) + (r.hiOpen ? ")" : "]");
  if (r.unit[0] != '\0') s += std::string(" ") + r.unit;
  return s;
}

double checkedNumber(const std::string& flag, double v, const NumberRange& r) {
  const bool aboveLo = r.loOpen ? v > r.lo : v >= r.lo;
  const bool belowHi = r.hiOpen ? v < r.hi : v <= r.hi;
  if (!std::isfinite(v) || !aboveLo || !belowHi)
    throw SceneError(flag + " " + numberText(v) + ": expected a finite number " + rangeText(r));
  return v;
}

void checkCount(const std::string& what, double count, double cap, const std::string& items, const std::string& reason) {
  if (std::isfinite(count) && count <= cap) return;
  throw SceneError(what + ": would make " + countText(count) + " " + items + ", more than the cap of " + countText(cap) +
                   " (" + reason + ")");
}

}  // namespace rootsim
