#pragma once
// Reference solution of the inextensible, unshearable Euler elastica: a cantilever clamped at s = 0
// along +xi, dead load P at the tip along -eta. With theta the tangent angle,
//   B theta'' = P cos(theta),  theta(0) = 0,  theta'(L) = 0,
// solved by shooting on theta'(0) (bisection) with classical RK4.
#include <cmath>
#include <utility>

namespace rootsim::test {

struct ElasticaTip { double xi, eta, theta; };  // tip position / L and tip angle

// load = P L^2 / B; returns the tip of the unit-length rod
inline ElasticaTip elasticaTip(double load, int steps = 4000) {
  auto integrate = [&](double k0) {
    // state (theta, theta', xi, eta) over s in [0, 1]
    double y[4] = {0.0, k0, 0.0, 0.0};
    const double h = 1.0 / steps;
    auto f = [&](const double* a, double* d) {
      d[0] = a[1];
      d[1] = load * std::cos(a[0]);
      d[2] = std::cos(a[0]);
      d[3] = std::sin(a[0]);
    };
    for (int i = 0; i < steps; ++i) {
      double k1[4], k2[4], k3[4], k4[4], t[4];
      f(y, k1);
      for (int j = 0; j < 4; ++j) t[j] = y[j] + 0.5 * h * k1[j];
      f(t, k2);
      for (int j = 0; j < 4; ++j) t[j] = y[j] + 0.5 * h * k2[j];
      f(t, k3);
      for (int j = 0; j < 4; ++j) t[j] = y[j] + h * k3[j];
      f(t, k4);
      for (int j = 0; j < 4; ++j) y[j] += h / 6.0 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    return ElasticaTip{y[2], y[3], y[0]};
  };
  auto endSlope = [&](double k0) {
    // theta'(1) = k0 + load * int cos(theta) = k0 + load * xi(1)
    const ElasticaTip t = integrate(k0);
    return k0 + load * t.xi;
  };
  double lo = -load, hi = 0.0;  // |theta'(0)| <= P L / B
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (endSlope(mid) > 0.0) hi = mid; else lo = mid;
  }
  return integrate(0.5 * (lo + hi));
}

}  // namespace rootsim::test
