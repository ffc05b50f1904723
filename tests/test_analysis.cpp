// observables (src/sim/analysis.cpp): writhe, twist, linking number; wavelength, amplitude and pattern of
// synthetic shapes with known answers
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/analysis.hpp"
#include "rootsim/simulation.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using rootsim::test::coarse;

namespace {
constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

// a model whose whole rod counts as mature (no growth zone), on a plate tilted by 40 degrees
Model plateModel() {
  Model m;
  m.growth.enabled = false;
  m.env.plane.alpha = 40 * deg;
  return m;
}

// a rod lying on the plate along the curve p -> (lateral u(p), downhill w(p)) [m], p in [0, 1], n elements
RodState onPlate(const Model& m, int n, const std::function<void(double, double&, double&)>& curve) {
  RodState s;
  s.resize(n);
  const Plane& pl = m.env.plane;
  for (int i = 0; i <= n; ++i) {
    double u = 0, w = 0;
    curve(static_cast<double>(i) / n, u, w);
    s.x.col(i) = m.rod.radius * pl.normal() + u * pl.lateral() + w * pl.downhill();
  }
  s.S[0] = 0;
  for (int i = 0; i < n; ++i) {
    s.l0[i] = (s.x.col(i + 1) - s.x.col(i)).norm();
    s.S[i + 1] = s.S[i] + s.l0[i];
  }
  return s;
}

// a sine of `waves` wavelengths lam [m] and half excursion a [m] along downhill, its axis tilted by
// `tilt` [rad] toward +lateral: u = a sin(2 pi w / lam) + w tan(tilt)
RodState sine(const Model& m, double waves, double lam, double a, double tilt = 0, int perWave = 80) {
  const double L = waves * lam;
  return onPlate(m, static_cast<int>(std::lround(waves * perWave)), [&](double p, double& u, double& w) {
    w = p * L;
    u = a * std::sin(2 * pi * w / lam) + w * std::tan(tilt);
  });
}
}  // namespace

TEST_CASE("a sine of 10 waves: lambda is its wavelength, A its peak-to-peak excursion, and it waves") {
  const Model m = plateModel();
  const double lam = 2e-3, a = 0.25e-3;
  const ShapeAnalysis r = analyseShape(m, sine(m, 10, lam, a));
  INFO("lambda " << r.wavelength << " A " << r.amplitude << " peaks " << r.peaks << " skew " << r.skew / deg);
  CHECK(r.peaks == 20);
  ROOTSIM_CHECK_CLOSE(r.waves, 9.5, kRoundoff);
  CHECK(r.wavelength == doctest::Approx(lam).epsilon(1e-3));
  // the turning points are nodes: within half a node spacing of the crest, cos(pi / 80) of 2a
  CHECK(r.amplitude == doctest::Approx(2 * a).epsilon(1e-3));
  CHECK(r.amplitudeHalf == doctest::Approx(a).epsilon(1e-3));
  CHECK(std::abs(r.skew) < 0.1 * deg);
  CHECK(r.skewJudged);
  CHECK(r.pattern == "waving");
}

TEST_CASE("a sine of 1.5 waves ending to one side waves: too few waves to judge a skew") {
  const Model m = plateModel();
  const double lam = 2e-3, a = 0.25e-3;
  // 1.5 waves of a sine tilted by 8 degrees: the base-to-end direction is off by 13 degrees
  const ShapeAnalysis r = analyseShape(m, sine(m, 1.5, lam, a, 8 * deg));
  INFO("peaks " << r.peaks << " skew " << r.skew / deg << " lambda " << r.wavelength);
  CHECK(r.peaks == 3);
  CHECK_FALSE(r.skewJudged);
  CHECK(std::abs(r.skew) > m.analysis.skewThresholdDeg * deg);  // the measured angle would say skewing
  CHECK(r.pattern == "waving");
  CHECK(r.wavelength == doctest::Approx(lam).epsilon(0.01));
  // the untilted 1.5 waves: lambda and A exactly as for the long sine
  const ShapeAnalysis s = analyseShape(m, sine(m, 1.5, lam, a));
  CHECK(s.pattern == "waving");
  CHECK(s.wavelength == doctest::Approx(lam).epsilon(1e-3));
  CHECK(s.amplitude == doctest::Approx(2 * a).epsilon(1e-3));
}

TEST_CASE("a tilted sine of 6 waves skews by its tilt, and the mirror image the other way") {
  const Model m = plateModel();
  const double lam = 2e-3, a = 0.25e-3, tilt = 15 * deg;
  const ShapeAnalysis r = analyseShape(m, sine(m, 6, lam, a, tilt));
  const ShapeAnalysis q = analyseShape(m, sine(m, 6, lam, a, -tilt));
  INFO("skew " << r.skew / deg << " / " << q.skew / deg << " peaks " << r.peaks);
  CHECK(r.skewJudged);
  CHECK(r.pattern == "skewing");
  CHECK(q.pattern == "skewing");
  // the root leans toward +lateral: counter-clockwise from downhill seen from above (docs/model.md, Frames
  // and signs)
  CHECK(r.skew == doctest::Approx(tilt).epsilon(0.01));
  CHECK(q.skew == doctest::Approx(-tilt).epsilon(0.01));
  // same-side peaks stay one wavelength apart along downhill
  CHECK(r.wavelength == doctest::Approx(lam).epsilon(0.01));
  // and a tilt below the threshold still waves
  CHECK(analyseShape(m, sine(m, 6, lam, a, 3 * deg)).pattern == "waving");
}

TEST_CASE("a loop coils, a straight line is straight, a tilted line skews, ripples below the hysteresis are not waves") {
  const Model m = plateModel();
  SUBCASE("a circle: the tangent turns through 2 pi") {
    const double r0 = 0.9e-3;
    const ShapeAnalysis r = analyseShape(m, onPlate(m, 200, [&](double p, double& u, double& w) {
      u = r0 * (1 - std::cos(2 * pi * p));
      w = r0 * std::sin(2 * pi * p);
    }));
    INFO("theta " << r.thetaMin / deg << " .. " << r.thetaMax / deg << " max kappa " << r.maxKappa);
    CHECK(r.pattern == "coiling");
    CHECK(r.thetaMax - r.thetaMin == doctest::Approx(2 * pi).epsilon(0.02));
    CHECK(r.maxKappa == doctest::Approx(1 / r0).epsilon(0.01));
  }
  SUBCASE("a straight line along downhill") {
    const ShapeAnalysis r = analyseShape(m, onPlate(m, 100, [](double p, double& u, double& w) {
      u = 0;
      w = 10e-3 * p;
    }));
    CHECK(r.pattern == "straight");
    CHECK(r.peaks == 0);
    CHECK(r.amplitude == 0);
    CHECK(r.wavelength == 0);
  }
  SUBCASE("a straight line tilted by 20 degrees: no waves, so its direction is the skew") {
    const ShapeAnalysis r = analyseShape(m, onPlate(m, 100, [](double p, double& u, double& w) {
      w = 10e-3 * p;
      u = -w * std::tan(20 * deg);
    }));
    CHECK(r.pattern == "skewing");
    CHECK(r.skewJudged);
    CHECK(r.skew == doctest::Approx(-20 * deg).epsilon(1e-9));
  }
  SUBCASE("ripples of 0.4 R peak-to-peak (hysteresis 0.5 R) on a line are straight; on a sine they add no peaks") {
    const double rip = 0.2 * m.rod.radius;
    const ShapeAnalysis r = analyseShape(m, onPlate(m, 400, [&](double p, double& u, double& w) {
      w = 10e-3 * p;
      u = rip * std::sin(2 * pi * 60 * p);
    }));
    CHECK(r.pattern == "straight");
    CHECK(r.peaks == 0);
    const double lam = 2e-3, a = 0.25e-3;
    const ShapeAnalysis s = analyseShape(m, onPlate(m, 2000, [&](double p, double& u, double& w) {
      w = 5 * lam * p;
      u = a * std::sin(2 * pi * w / lam) + rip * std::sin(2 * pi * 150 * p);
    }));
    INFO("peaks " << s.peaks);
    CHECK(s.peaks == 10);
    CHECK(s.pattern == "waving");
    CHECK(s.wavelength == doctest::Approx(lam).epsilon(0.02));
  }
}

TEST_CASE("a larger end swing leaves out a first or last swing below it, and the inner swings keep the hysteresis") {
  // u = a sin(2 pi w / lam + 7 pi / 6) + a / 2: from 0 the root departs by a / 2 to a shallow trough, then
  // swings 2a between crests and troughs; it ends 0.1476 lam past its last crest, having come back by
  // a (1 - cos(0.927)) = 0.4 a. With a = 0.25 mm and the hysteresis 0.5 R = 0.05 mm both partial swings
  // (0.125 mm and 0.1 mm) make peaks; an end swing of 0.2 mm leaves them out
  const Model m = plateModel();
  const double lam = 2e-3, a = 0.25e-3, end = 4.8143 * lam;
  const RodState s = onPlate(m, 2000, [&](double p, double& u, double& w) {
    w = p * end;
    u = a * std::sin(2 * pi * w / lam + 7 * pi / 6) + 0.5 * a;
  });
  const int last = static_cast<int>(s.x.cols()) - 1;
  const Plane& pl = m.env.plane;
  const ShapeAnalysis plain = analyseCentreline(s.x, last, pl, m.analysis, m.rod.radius);
  const ShapeAnalysis ends = analyseCentreline(s.x, last, pl, m.analysis, m.rod.radius, 0.0, 0.2e-3);
  const ShapeAnalysis raised = analyseCentreline(s.x, last, pl, m.analysis, m.rod.radius, 0.2e-3);
  INFO("peaks " << plain.peaks << " / " << ends.peaks << " / " << raised.peaks);
  // troughs at w = lam (k + 1/6), crests at lam (k - 1/3): the shallow trough at lam / 6 first, the crest at
  // 4.667 lam last, 10 peaks in all
  REQUIRE(plain.peaks == 10);
  auto wOf = [&](int node) { return s.x.col(node).dot(pl.downhill()); };
  CHECK(wOf(plain.peakNodes.front()) == doctest::Approx(lam / 6).epsilon(0.01));
  CHECK(wOf(plain.peakNodes.back()) == doctest::Approx(lam * (5 - 1.0 / 3)).epsilon(0.01));
  // the end swing drops exactly the two end peaks; the others are the same nodes
  REQUIRE(ends.peaks == 8);
  CHECK(ends.peakNodes == std::vector<int>(plain.peakNodes.begin() + 1, plain.peakNodes.end() - 1));
  CHECK(ends.hysteresis == plain.hysteresis);
  // the inner swings (2a) are clear of 0.2 mm: the raised hysteresis finds the same peaks and values
  CHECK(raised.peakNodes == ends.peakNodes);
  CHECK(ends.wavelength == raised.wavelength);
  CHECK(ends.amplitude == raised.amplitude);
  CHECK(ends.skew == raised.skew);
  CHECK(ends.amplitude == doctest::Approx(2 * a).epsilon(1e-3));
  ROOTSIM_CHECK_CLOSE(ends.waves, plain.waves - 1.0, kRoundoff);
  // an end swing below the hysteresis changes nothing
  const ShapeAnalysis below = analyseCentreline(s.x, last, pl, m.analysis, m.rod.radius, 0.0, 0.01e-3);
  CHECK(below.peakNodes == plain.peakNodes);
  CHECK(below.amplitude == plain.amplitude);
}

TEST_CASE("a planar curve has zero writhe") {
  Eigen::Matrix3Xd p(3, 60);
  for (int i = 0; i < 60; ++i) p.col(i) = Vec3(std::cos(0.2 * i) * (1 + 0.01 * i), std::sin(0.2 * i), 0.0);
  CHECK(std::abs(writheOpen(p, 0, 59)) < 1e-12);
  CHECK(std::abs(writheClosed(p)) < 1e-12);
}

TEST_CASE("Calugareanu: Lk = Tw + Wr for a closed ribbon on a trefoil-like curve") {
  // closed curve: a (2,3) torus knot; ribbon: the Frenet-free frame u = normalised (p - axis point)
  // rotated by k full turns; Lk from the Gauss linking integral of the centreline and the ribbon edge
  const int N = 600;
  Eigen::Matrix3Xd c(3, N), e(3, N);
  std::vector<Vec3> u(N), t(N);
  auto curve = [](double s) {
    const double r = 2 + std::cos(3 * s);
    return Vec3(r * std::cos(2 * s), r * std::sin(2 * s), std::sin(3 * s));
  };
  for (int i = 0; i < N; ++i) c.col(i) = curve(2 * pi * i / N);
  for (int i = 0; i < N; ++i) t[i] = (c.col((i + 1) % N) - c.col((i + N - 1) % N)).normalized();
  const int k = 2;
  for (int i = 0; i < N; ++i) {
    const double s = 2 * pi * i / N;
    Vec3 radial = Vec3(c(0, i), c(1, i), 0).normalized();
    Vec3 a = (radial - radial.dot(t[i]) * t[i]).normalized();
    Vec3 b = t[i].cross(a);
    u[i] = std::cos(k * s) * a + std::sin(k * s) * b;
    e.col(i) = c.col(i) + 0.01 * u[i];
  }
  // twist: (1/2pi) sum of the rotation of u about t between neighbours
  double tw = 0;
  for (int i = 0; i < N; ++i) {
    const int j = (i + 1) % N;
    // parallel-transport u_i to j's normal plane, then the signed angle to u_j about t_j
    Vec3 ui = u[i] - u[i].dot(t[j]) * t[j];
    ui.normalize();
    tw += std::atan2(ui.cross(u[j]).dot(t[j]), ui.dot(u[j]));
  }
  tw /= 2 * pi;
  const double wr = writheClosed(c);
  const double lk = linkingNumber(c, e);
  INFO("Tw " << tw << " Wr " << wr << " Lk " << lk);
  CHECK(std::abs(lk - std::round(lk)) < 1e-6);
  CHECK(std::abs(tw + wr - lk) < 0.01);
  CHECK(std::abs(wr) > 0.5);  // a knotted curve writhes
}

TEST_CASE("a helix writhes, and its mirror image writhes the opposite way") {
  Eigen::Matrix3Xd p(3, 200);
  for (int i = 0; i < 200; ++i) {
    const double s = 0.1 * i;
    p.col(i) = Vec3(std::cos(s), std::sin(s), 0.3 * s);  // right-handed
  }
  const double wr = writheOpen(p, 0, 199);
  CHECK(std::abs(wr) > 0.1);
  Eigen::Matrix3Xd q = p;
  q.row(2) *= -1.0;  // mirror: left-handed
  CHECK(writheOpen(q, 0, 199) == doctest::Approx(-wr).epsilon(1e-12));
}

TEST_CASE("a straight rod twisted once has Tw = 1 and Wr = 0") {
  Model m = coarse(90, 0.0, 0);
  m.growth.zoneLength = 2e-3;  // the whole 1.1 mm rod is in the zone
  m.env.plane.enabled = false;
  Simulation sim(m);
  RodState s = sim.state();
  const int n = s.elements();
  const double L = s.restLength();
  // directors turned about d3 by 2 pi s / L (element centres)
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * pi * (s.S[i] + 0.5 * s.l0[i]) / L;
    Mat3 Q = s.Q[i];
    const Vec3 d1 = std::cos(phi) * Vec3(Q.row(0)) + std::sin(phi) * Vec3(Q.row(1));
    const Vec3 d2 = -std::sin(phi) * Vec3(Q.row(0)) + std::cos(phi) * Vec3(Q.row(1));
    s.Q[i].row(0) = d1.transpose();
    s.Q[i].row(1) = d2.transpose();
  }
  RodStrains k;
  k.resize(n);
  computeStrains(m.rod, s, k);
  const ZoneObservables z = observeZone(m, s, k);
  // the Voronoi domains cover [l/2, L - l/2]: Tw = (n - 1) / n of a turn, exactly 1 as n grows
  CHECK(z.Tw == doctest::Approx(static_cast<double>(n - 1) / n).epsilon(1e-9));
  CHECK(std::abs(z.Wr) < 1e-9);
}

// --- growth-zone integrals over exactly the last Lgz of rest arc length (docs/model.md, Observables) ---
namespace {
// a rod through the nodes x (3 x n+1), rest lengths the chords (no stretch), directors d3 = chord, d1 the
// unit part of d1ref(i) normal to it, d2 = d3 x d1; kappa0 = 0
RodState rodThrough(const Eigen::Matrix3Xd& x, const std::function<Vec3(int)>& d1ref) {
  const int n = static_cast<int>(x.cols()) - 1;
  RodState s;
  s.resize(n);
  s.x = x;
  s.S[0] = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 t = (x.col(i + 1) - x.col(i)).normalized();
    Vec3 d1 = d1ref(i);
    d1 = (d1 - d1.dot(t) * t).normalized();
    s.Q[static_cast<size_t>(i)].row(0) = d1.transpose();
    s.Q[static_cast<size_t>(i)].row(1) = t.cross(d1).transpose();
    s.Q[static_cast<size_t>(i)].row(2) = t.transpose();
    s.l0[i] = (x.col(i + 1) - x.col(i)).norm();
    s.S[i + 1] = s.S[i] + s.l0[i];
  }
  s.v.setZero();
  s.w.setZero();
  s.kappa0.setZero();
  s.anchor = s.x;
  s.anchored.assign(static_cast<size_t>(n + 1), 0);
  return s;
}

ZoneObservables observe(const Model& m, const RodState& s) {
  RodStrains k;
  k.resize(s.elements());
  computeStrains(m.rod, s, k);
  return observeZone(m, s, k);
}

// the default (physical) model with a growth zone of 0.93 mm: 18.6 of the default 0.05 mm elements of the
// 1.1 mm root, so the zone starts inside element 3
Model zoneModel() {
  Model m;
  m.growth.zoneLength = 0.93e-3;
  return m;
}
}  // namespace

TEST_CASE("growth zone starting inside an element: a straight rod twisted uniformly has Tw = its twist / 2pi") {
  const Model m = zoneModel();
  const int n = 22;
  const double h = m.initial.length / n, tau = 2 * pi / 1e-3;  // one turn per mm
  const Plane& pl = m.env.plane;
  Eigen::Matrix3Xd x(3, n + 1);
  for (int i = 0; i <= n; ++i) x.col(i) = m.rod.radius * pl.normal() + i * h * pl.downhill();
  // d1 turned about d3 by tau * (the element centre's arc length)
  const RodState s = rodThrough(x, [&](int i) {
    const double phi = tau * (i + 0.5) * h;
    return Vec3(std::cos(phi) * pl.lateral() + std::sin(phi) * pl.normal());
  });
  const double L = s.restLength(), S0 = L - m.growth.zoneLength;
  REQUIRE(std::abs(std::remainder(S0, h)) > 0.2 * h);  // the boundary lies well inside an element
  const ZoneObservables z = observe(m, s);
  // the material frame turns at tau between element centres; the last element's frame holds to the tip, so
  // the zone's twist is tau * (centre of the last element - S0)
  const double span = (L - 0.5 * h) - S0;
  CHECK(z.Tw == doctest::Approx(tau * span / (2 * pi)).epsilon(1e-9));
  CHECK(z.Et == doctest::Approx(m.rod.bendStiffness().z() * tau * tau * span).epsilon(1e-9));
  CHECK(std::abs(z.Eb) < 1e-12 * z.Et);
  CHECK(std::abs(z.Wr) < 1e-12);
}

TEST_CASE("growth zone starting inside an element: a uniformly bent planar rod has Eb = B1 kappa^2 span and Wr = 0") {
  const Model m = zoneModel();
  const int n = 22;
  const double r = 1e-3;                            // radius of the arc [m]
  const double dphi = (m.initial.length / n) / r;   // angle per element
  const Plane& pl = m.env.plane;
  Eigen::Matrix3Xd x(3, n + 1);
  for (int i = 0; i <= n; ++i)
    x.col(i) = m.rod.radius * pl.normal() + r * std::sin(i * dphi) * pl.downhill() +
               r * (1 - std::cos(i * dphi)) * pl.lateral();
  const RodState s = rodThrough(x, [&](int) { return Vec3(pl.lateral()); });
  const double h = s.l0[0];  // the chord
  const double L = s.restLength(), S0 = L - m.growth.zoneLength;
  REQUIRE(std::abs(std::remainder(S0, h)) > 0.2 * h);
  const ZoneObservables z = observe(m, s);
  // neighbouring elements turn by dphi over the Voronoi length h: kappa = dphi / h, about d2 (the normal)
  const double kap = dphi / h, span = (L - 0.5 * h) - S0;
  CHECK(z.Eb == doctest::Approx(m.rod.bendStiffness().x() * kap * kap * span).epsilon(1e-9));
  CHECK(std::abs(z.Et) < 1e-12 * z.Eb);
  CHECK(std::abs(z.Tw) < 1e-12);
  // the plate is tilted, so coplanar segment pairs give solid angles of asin(+-1 - rounding): each pair is
  // exact only to sqrt(machine epsilon) ~ 1.5e-8 (in an axis plane they are exact, "a planar curve ...")
  CHECK(std::abs(z.Wr) < 1e-6);
}

TEST_CASE("the growth-zone observables change continuously as the start of the zone crosses an element") {
  // a twisted helix (radius 0.1 mm, one turn per mm of arc, d1 turning 0.5 turn/mm against the axis
  // projection): all four observables are non-zero; its elements have unequal lengths
  Model m;
  const int n = 22;
  const double a = 0.1e-3, w = 2 * pi / 1e-3, c = std::sqrt(1.0 - std::pow(a * w, 2));
  Eigen::Matrix3Xd x(3, n + 1);
  double S = 0;
  for (int i = 0; i <= n; ++i) {
    x.col(i) = Vec3(a * std::cos(w * S), a * std::sin(w * S), c * S);
    S += m.initial.length / n * (1.0 + 0.3 * std::sin(i));
  }
  const RodState s = rodThrough(x, [&](int i) {
    const double phi = pi / 1e-3 * 1e-4 * i;
    return Vec3(std::cos(phi), std::sin(phi), 0.0);
  });
  const double L = s.restLength();
  const int e = 7;  // the zone's start crosses element e, from node e to node e + 1
  std::vector<ZoneObservables> z;
  for (int q = 0; q <= 10; ++q) {
    m.growth.zoneLength = L - (s.S[e] + 0.1 * q * s.l0[e]);
    z.push_back(observe(m, s));
  }
  auto check = [&](const std::string& what, double ZoneObservables::*f) {
    double total = 0, maxStep = 0;
    for (size_t q = 1; q < z.size(); ++q) {
      const double d = z[q].*f - z[q - 1].*f;
      total += d;
      maxStep = std::max(maxStep, std::abs(d));
    }
    INFO(what << ": change across the element " << total << ", largest of 10 sub-steps " << maxStep);
    CHECK(std::abs(total) > 1e-3 * std::abs(z[0].*f));  // the element counts: the observable does move
    // no jump: no sub-step carries more than twice its share (whole-element counting puts all of it in one)
    CHECK(maxStep <= 0.2 * std::abs(total));
  };
  check("Eb", &ZoneObservables::Eb);
  check("Et", &ZoneObservables::Et);
  check("Tw", &ZoneObservables::Tw);
  check("Wr", &ZoneObservables::Wr);
}

// Fig. 2E's Wr at t = 0 (docs/model.md, Observables): a straight rod in a general orientation has
// collinear segments only up to rounding; each pair's solid angle must be 0, not the angle between two
// normals of rounding-noise length
TEST_CASE("a straight or planar rod in a general orientation has zero writhe, rounding noise aside") {
  const Vec3 dir = Vec3(0.3, -0.5, 0.81).normalized();
  Eigen::Matrix3Xd p(3, 23);
  for (int i = 0; i < 23; ++i) p.col(i) = Vec3(1e-3, 2e-3, -0.5e-3) + (0.05e-3 * i) * dir;
  CHECK(std::abs(writheOpen(p, 0, 22)) < 1e-9);
  // a planar arc in a tilted plane
  const Vec3 e1 = Vec3(1, 0.2, -0.3).normalized(), e2 = e1.cross(dir).normalized();
  for (int i = 0; i < 23; ++i)
    p.col(i) = Vec3(1e-3, 2e-3, -0.5e-3) + 1e-3 * (std::cos(0.1 * i) * e1 + std::sin(0.1 * i) * e2);
  CHECK(std::abs(writheOpen(p, 0, 22)) < 1e-9);
  // the first record of a run on a plate tilted by 40 degrees: the initial straight rod
  for (double alpha : {40.0, 73.0}) {
    INFO("alpha " << alpha);
    const Model m = coarse(alpha, 0.2, 0);
    Simulation sim(m);
    const RodState& s = sim.state();
    RodStrains k;
    k.resize(s.elements());
    computeStrains(m.rod, s, k);
    CHECK(std::abs(observeZone(m, s, k).Wr) < 1e-9);
  }
}
