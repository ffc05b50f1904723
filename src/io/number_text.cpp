#include "rootsim/number_text.hpp"

#include <charconv>

namespace rootsim {

std::string shortestNumber(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // "n": inf, nan
  return s;
}

}  // namespace rootsim
