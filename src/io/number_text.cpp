#include "rootsim/number_text.hpp"

#include <charconv>

namespace rootsim {

std::string numberText(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string shortestNumber(double x) {
  std::string s = numberText(x);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // "n": inf, nan
  return s;
}

std::string decimalNumber(double x) {
  // fixed notation: up to ~330 characters for the largest doubles, 1100 for the smallest subnormals
  char buf[1200];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed);
  return std::string(buf, r.ptr);
}

}  // namespace rootsim
