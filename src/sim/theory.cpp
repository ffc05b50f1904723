#include "rootsim/theory.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace rootsim {

Theory theoryFor(const Model& m) {
  constexpr double pi = std::numbers::pi;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double R = m.rod.radius, Lgz = m.growth.zoneLength, eps0 = m.growth.rate;
  const double beta = m.tropism.beta, alpha = m.env.plane.alpha;
  const double vtip = eps0 * Lgz;
  Theory t{};
  t.effectiveGain = beta * Lgz / R;
  // Eq. 7: T0 = (pi/2) (1/eps0) (beta Lgz / R)^(-3/5)
  t.T0 = t.effectiveGain > 0 ? 0.5 * pi / eps0 * std::pow(t.effectiveGain, -0.6) : nan;
  // Eq. 8: max kappa = T0 (eps0 / R) beta sin(alpha)
  t.maxKappa = t.T0 * eps0 / R * beta * std::sin(alpha);
  // Eqs. 9-11: lambda / 2 = T0 v_tip, 2 A = T0 v_tip tan(alpha)
  t.wavelength = 2.0 * t.T0 * vtip;
  t.amplitude = 0.5 * t.T0 * vtip * std::tan(alpha);
  // Eq. 12: sin(alpha_s->w) = sqrt(2/3) (2 dxi / pi) g^(-2/5), dxi = pi / 8
  const double s12 = std::sqrt(2.0 / 3.0) * 0.25 * std::pow(t.effectiveGain, -0.4);
  t.alphaStraightToWave = s12 <= 1.0 ? std::asin(s12) : nan;
  // Eq. 13: sin^2(a) / cos(a) = 4 / (C pi^2) g^(1/5), C = 0.5; with c = cos a: (1 - c^2) / c = q
  const double q = 4.0 / (0.5 * pi * pi) * std::pow(t.effectiveGain, 0.2);
  const double c = 0.5 * (-q + std::sqrt(q * q + 4.0));
  t.alphaWaveToCoil = std::acos(c);
  // Eq. 5: omega = tau eps0 Lgz with tau = (R tau) / R
  t.omega = m.tropism.rTau / R * eps0 * Lgz;
  t.omegaT0 = t.omega * t.T0;
  const double a14 = t.omegaT0 * std::tan(alpha), a15 = std::tan(alpha);
  t.skewSmall = std::abs(a14) <= 1.0 ? std::asin(a14) : nan;
  t.skewLarge = a15 <= 1.0 ? std::asin(a15) : nan;
  return t;
}

}  // namespace rootsim
