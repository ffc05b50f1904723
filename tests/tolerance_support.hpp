#pragma once
// The one tolerance helper of every test executable (physics, io, analysis, figure, render): a floating
// result compared with what it should be, the tolerance written at the check and relative to the wanted
// value.
//
//   ROOTSIM_CHECK_REL(what, got, want, tol)  passes when |got - want| <= tol * |want|, or, when want is 0,
//                                            |got| <= tol (an absolute tolerance in got's units)
//   ROOTSIM_CHECK_CLOSE(got, want, tol)      the same, named by the expression got
//
// With ROOTSIM_PRINT_RESIDUALS set in the environment every check prints its file:line and relative error.
//
// Why not a bare doctest::Approx(want): without .epsilon() it passes when
// |got - want| < 1.19e-5 * (1 + max(|got|, |want|)) (100 * FLT_EPSILON, relative and, through the 1,
// absolute too), so a length of 1e-4 m passes against 0 and the tolerance a test means is written nowhere.
// Every check that tolerance covered is tighter with one of these, relative to want (absolute at want 0):
//   kRoundoff       a double that only rounding separates from want (a unit conversion, a text round
//                   trip, a few operations): a thousand ulps, 2.2e-13
//   kFloatRoundoff  a value stored in single precision (a colour map's channel, a glTF float32
//                   accessor): four of its ulps, 4.8e-7
// The checks expand to doctest's INFO and CHECK where they are used: a test file includes doctest itself
// (a benchmark that shares physics_support.hpp must not, or it links doctest's test registry).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace rootsim::test {

inline constexpr double kRoundoff = 1e3 * std::numeric_limits<double>::epsilon();
inline constexpr double kFloatRoundoff = 4.0 * static_cast<double>(std::numeric_limits<float>::epsilon());

inline bool printResiduals() {
  static const bool on = std::getenv("ROOTSIM_PRINT_RESIDUALS") != nullptr;
  return on;
}

// relative error of got against want, measured against scale (want itself when scale == 0; 1, an
// absolute error, when both are 0)
inline double relError(double got, double want, double scale = 0.0) {
  const double ref = scale != 0.0 ? std::abs(scale) : std::abs(want);
  return std::abs(got - want) / (ref > 0 ? ref : 1.0);
}

inline void report(const std::string& what, double got, double want, double err) {
  if (printResiduals())
    std::printf("[residual] %-52s got % .9e want % .9e rel.err %.3e\n", what.c_str(), got, want, err);
}

// the same, the check's file name and line first
inline void reportAt(const char* file, int line, const std::string& what, double got, double want, double err) {
  if (!printResiduals()) return;
  const std::string f = file, name = f.substr(f.find_last_of('/') + 1);
  report(name + ":" + std::to_string(line) + " " + what, got, want, err);
}

}  // namespace rootsim::test

#define ROOTSIM_CHECK_REL(what, got, want, tol)                                              \
  do {                                                                                       \
    const double rs_got_ = (got), rs_want_ = (want);                                         \
    const double rs_err_ = ::rootsim::test::relError(rs_got_, rs_want_);                     \
    ::rootsim::test::reportAt(__FILE__, __LINE__, what, rs_got_, rs_want_, rs_err_);          \
    INFO(what << ": got " << rs_got_ << ", want " << rs_want_ << ", rel.err " << rs_err_);  \
    CHECK(rs_err_ <= (tol));                                                                 \
  } while (0)

#define ROOTSIM_CHECK_CLOSE(got, want, tol) ROOTSIM_CHECK_REL(#got, got, want, tol)
