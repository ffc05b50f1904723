#pragma once
// one tolerance helper for every physics test: checks |got - want| <= tol * |scale| and, when
// ROOTSIM_PRINT_RESIDUALS is set in the environment, prints the actual relative error
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace rootsim::test {

inline bool printResiduals() {
  static const bool on = std::getenv("ROOTSIM_PRINT_RESIDUALS") != nullptr;
  return on;
}

// relative error of got against want, measured against scale (want itself when scale == 0)
inline double relError(double got, double want, double scale = 0.0) {
  const double ref = scale != 0.0 ? std::abs(scale) : std::abs(want);
  return std::abs(got - want) / (ref > 0 ? ref : 1.0);
}

inline void report(const std::string& what, double got, double want, double err) {
  if (printResiduals())
    std::printf("[residual] %-52s got % .9e want % .9e rel.err %.3e\n", what.c_str(), got, want, err);
}

// observed convergence order from errors at resolutions n1 < n2
inline double order(double err1, double err2, double n1, double n2) {
  return std::log(err1 / err2) / std::log(n2 / n1);
}

}  // namespace rootsim::test

#define ROOTSIM_CHECK_REL(what, got, want, tol)                                              \
  do {                                                                                       \
    const double rs_got_ = (got), rs_want_ = (want);                                         \
    const double rs_err_ = ::rootsim::test::relError(rs_got_, rs_want_);                     \
    ::rootsim::test::report(what, rs_got_, rs_want_, rs_err_);                               \
    INFO(what << ": got " << rs_got_ << ", want " << rs_want_ << ", rel.err " << rs_err_);  \
    CHECK(rs_err_ <= (tol));                                                                 \
  } while (0)
