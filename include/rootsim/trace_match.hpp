#pragma once
// A simulated root against a traced one (docs/experiments.md, "Compare" and "Fit"): shape distances
// between two centrelines in plate coordinates, the observables side by side with the uncertainty the
// trace's resolution gives each, the chi-square objective a fit minimises, and the curvature of that
// objective at its minimum (uncertainties, and the directions the observables cannot see). Plain
// geometry and linear algebra: no file formats here.
#include <functional>
#include <limits>
#include <utility>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/traits.hpp"

namespace rootsim {

// the root-mean-square distance [mm] between the points of a and b at equal fractions of their arc
// lengths from their first points (both in plate coordinates [mm], base first), sampled about every dsMm
// along the longer one: arc-length alignment that a noisy trace's extra length does not shift. It sees a
// wave's phase and a skew alike. Throws std::invalid_argument for a polyline without length or dsMm <= 0.
double arcLengthDistanceMm(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b, double dsMm);

// the discrete Frechet distance [mm] between the two polylines resampled every dsMm (the shortest leash
// that walks both, each only forwards: Eiter & Mannila 1994); O(n m) time and O(m) memory
double frechetDistanceMm(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b, double dsMm);

// one observable of the trace beside the simulated root's, with the trace's standard uncertainty
struct Observation {
  std::string name;   // the analysis.csv column: "skew_deg", "wavelength_mm", ...
  std::string unit;
  double trace = 0, sim = 0;
  double sigma = 0;   // standard uncertainty of the trace's value (same unit)
  bool used = false;  // part of the objective (else shown only: the trace does not define it)
  std::string why;    // how sigma was found, or why the observable is not used
  double residual() const { return used ? (sim - trace) / sigma : 0.0; }
};

// the observables of a traced root beside a simulated root's, both measured by rootTraits. sigmaPosMm:
// the standard uncertainty of one traced point's position (a scan's pixel: docs/experiments.md). Used in
// the objective: the skew over whole waves (or the base-to-tip skew when the trace has no whole wave),
// the tortuosity, and, when the trace waves, the wavelength and the peak-to-peak amplitude; each sigma
// from the resolution and the number of waves averaged. Shown only: max curvature and the tangent range.
std::vector<Observation> observeBoth(const RootTraits& trace, const RootTraits& sim, double sigmaPosMm);

// sum of the squared residuals of the used observables
double chiSquare(const std::vector<Observation>& obs);
// how many observables are used
int usedCount(const std::vector<Observation>& obs);

// the outputs a fit matches (docs/experiments.md, "Fit"): the trace's values with their uncertainty and
// the simulated root's values, one entry per output
struct FitComponents {
  std::vector<std::string> names;
  Eigen::VectorXd trace, sigma, sim;  // sigma: the square root of cov's diagonal
  Eigen::MatrixXd cov;                // the trace's values' covariance
  std::string covName = "the trace's uncertainty alone";  // what cov is, in the words of a goodness line
};
// the observables in the objective (Observation::used); a simulated root without the waves the trace
// has counts its wavelength and amplitude as 0
FitComponents observableComponents(const std::vector<Observation>& obs);
// the shape: the points at fractions k / samples (k = 1 .. samples) of each root's arc length, lateral
// and downhill [mm] (both polylines in plate coordinates with the seed, their first point, at the
// origin), with the trace's covariance traceCov (shapeTraceCovariance). Throws std::invalid_argument when
// traceCov is not 2 samples square.
FitComponents shapeComponents(const Eigen::Matrix3Xd& trace, const Eigen::Matrix3Xd& sim, const Eigen::MatrixXd& traceCov,
                              int samples);
// the covariance of the shape outputs of a polyline whose points each get an independent error of sigmaMm
// in their lateral and downhill position, propagated through the sampling itself: draws of clean plus
// noise, each aligned at its own first point and sampled at fractions of its own length (a fixed seed:
// the same polyline, the same covariance). It holds the seed's error, common to every sample, the
// length's error that moves samples along the root, and the smaller error of a sample between two points.
// Throws std::invalid_argument for sigmaMm <= 0, samples < 1 or draws < 2.
Eigen::MatrixXd shapeNoiseCovariance(const Eigen::Matrix3Xd& clean, double sigmaMm, int samples, int draws = 2000);
// the outputs of draws of clean with an independent error of sigmaMm on each point's lateral and downhill
// position, each draw aligned at its own first point (a fixed seed: the same polyline, the same draws): one
// row per draw. Throws std::invalid_argument for sigmaMm <= 0 or draws < 1.
Eigen::MatrixXd noiseDraws(const Eigen::Matrix3Xd& clean, double sigmaMm, int draws,
                           const std::function<Eigen::VectorXd(const Eigen::Matrix3Xd&)>& outputs);
// the indices of the points of p that do not repeat the point before them (a tracer's doubled click: one
// point, one error)
std::vector<int> distinctPoints(const Eigen::Matrix3Xd& p);
// the polyline with less of its points' noise: each point the mean of itself and its two neighbours,
// weights 1/4, 1/2, 1/4 (the end points as they are): a tenth of the noise in the differences between
// neighbours, whose squares lengthen a noisy polyline, while a wave 15 points long keeps 96 % of its
// amplitude
Eigen::Matrix3Xd denoised(const Eigen::Matrix3Xd& p);
// a traced root's: shapeNoiseCovariance of the trace with less of its own noise (each point averaged with
// its neighbours, 1/4 1/2 1/4; an estimate: the trace's true shape is unknown)
Eigen::MatrixXd shapeTraceCovariance(const Eigen::Matrix3Xd& trace, double sigmaMm, int samples, int draws = 2000);
// how much longer the points' noise of sigmaMm makes a traced polyline, on average [mm]: the mean length of
// draws of the trace with less of its own noise (as shapeTraceCovariance) given new noise, less that
// polyline's length. A trace's length less this is the root's (a point every 0.2 mm with 0.025 mm of noise
// adds about 0.3 mm to 20 mm: 1.5 h of a root growing 0.2 mm/h). Throws std::invalid_argument for sigmaMm <= 0.
double noiseLengtheningMm(const Eigen::Matrix3Xd& trace, double sigmaMm, int draws = 400);
// the strongest wave of a nearly straight root: the sinusoid of lateral offset against distance along the
// base-to-tip chord that takes the most of the offsets' variance (a least-squares fit of a line plus the
// sinusoid at each wavelength of a grid in 1/lambda, refined by a parabola through the best three), the tip's
// excludeTipMm (its growth zone, still bending) left out. It needs no peak above the noise: a wave of 2
// pixels on a trace with 0.6 px of noise, invisible to the peak count, is found from its whole length.
// lambdaMin, lambdaMax [mm]: the range searched (a trace's: 4 point spacings to the span; a run's the same
// as its trace's). NaN values when fewer than 8 points remain or the range is empty.
struct WaveFit {
  double wavelengthMm = std::numeric_limits<double>::quiet_NaN();
  double amplitudeMm = std::numeric_limits<double>::quiet_NaN();  // the sinusoid's half peak-to-peak
};
WaveFit strongestWave(const Eigen::Matrix3Xd& p, double excludeTipMm, double lambdaMin, double lambdaMax);
// the range strongestWave searches on a trace p: [4 median point spacings, the chord's span less excludeTipMm]
std::pair<double, double> waveRange(const Eigen::Matrix3Xd& p, double excludeTipMm);
// root traced as trace was: as many points as the trace has distinct ones, at equal arc length along root.
// shapeNoiseCovariance(tracedLike(run, trace), ...) is the covariance a trace of that run would have: the
// one a goodness of fit of the run tests against
Eigen::Matrix3Xd tracedLike(const Eigen::Matrix3Xd& root, const Eigen::Matrix3Xd& trace);

}  // namespace rootsim
