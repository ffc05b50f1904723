#pragma once
// numbers as text, one module for every library (header only: the renderer links no rootsim_io).
// Numbers written to be read back (the CSV and JSON files, sweep run-folder names and table.csv grid
// columns, --set values, the resolved scene.toml) are the shortest text that parses to the same double,
// so 0.3 reads "0.3" and not "0.29999999999999999" as 17 significant digits print it; numbers for people
// (messages, labels, folder names of figure cases) are printf's %g or %f with a stated number of digits.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace rootsim {

// the shortest round-trip text of x as std::to_chars writes it ("2", "0.3", "1e-07", "nan"): the numbers
// of the CSV and JSON files
inline std::string numberText(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// shortest round-trip text of x (std::to_chars): "0.3", "35.7", "1e-07", "1e+300"; an integral value
// keeps a ".0" ("2.0", not "2") so that TOML reads it back as a float; "inf", "-inf", "nan" as TOML
// spells them
inline std::string shortestNumber(double x) {
  std::string s = numberText(x);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // "n": inf, nan
  return s;
}

// the shortest round-trip text of x without an exponent ("0.0000001", "35.7", "2"): for formats whose
// numbers are decimals (RSML's xs:decimal); x must be finite
inline std::string decimalNumber(double x) {
  // fixed notation: up to ~330 characters for the largest doubles, 1100 for the smallest subnormals
  char buf[1200];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed);
  return std::string(buf, r.ptr);
}

// x to `digits` significant digits as printf's %g writes it ("0.15", "1000", "1e+06", "inf"): a number
// for people, not to be read back
inline std::string significantText(double x, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// x with `decimals` digits after the point, as printf's %f writes it ("12.5", "3"); |x| below 1e40
inline std::string fixedText(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

// an axis or colour bar tick: 3 significant digits, a value within 1e-300 of 0 as "0"
inline std::string tickText(double x) { return std::abs(x) < 1e-300 ? "0" : significantText(x, 3); }

// a round scale-bar length: 1, 2 or 5 times a power of ten, at most `most` (> 0)
inline double niceLength(double most) {
  const double p = std::pow(10.0, std::floor(std::log10(most)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= most) return m * p;
  return p;
}

}  // namespace rootsim
