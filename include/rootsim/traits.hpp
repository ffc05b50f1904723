#pragma once
// Phenotyping traits of a root's centreline on the plate (docs/experiments.md): what a root lab measures on
// a scanned plate (length, base-to-tip skew angle, tortuosity, the insertion angle of a lateral) and the
// observables of a run (pattern, lambda, A, lateral peaks, skew over whole waves, max kappa: analysis.hpp)
// computed by the very code that measures runs. Plain geometry: no file formats here.
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/analysis.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/model.hpp"

namespace rootsim {

// the polyline p (3 x n, any unit) resampled at equal arc-length steps of about ds (the last step ends
// exactly on the last point; the first and the last point are kept). Consecutive repeated points are
// dropped first. Throws std::invalid_argument when ds <= 0 or the polyline has no length.
Eigen::Matrix3Xd resampleByArcLength(const Eigen::Matrix3Xd& p, double ds);

// arc length of a polyline (same unit as p)
double polylineLength(const Eigen::Matrix3Xd& p);

// plate coordinates [mm] (lateral, downhill, height; docs/model.md, Frames and signs) to lab positions [m]
// on the plate `frame` (the inverse of PlateFrame::coords)
Eigen::Matrix3Xd plateMmToLab(const Eigen::Matrix3Xd& plateMm, const PlateFrame& frame);

// the position noise of a traced polyline (docs/experiments.md, "Noise"): each interior point against the
// cubic through its two neighbours on either side (Lagrange, in the frame of the chord from the second
// neighbour before to the second after, so a curve's own bend and its change cancel), the offset across
// the chord, divided by the prediction's standard factor sqrt(1 + sum w^2); sigma is the RMS of those residuals clipped at 3 sigma (iterated from a median
// start, corrected for the clipping; a point outside the clip also removes the residuals of the
// neighbours whose cubic it enters) so a tracer's snapping steps do not inflate it. Only the plate's
// (lateral, downhill) plane.
struct TraceNoise {
  double sigma = std::numeric_limits<double>::quiet_NaN();  // one point's position noise per coordinate [unit
                                                            // of p]; NaN: fewer than 9 distinct points
  double spacing = 0;  // median distance between consecutive distinct points [unit of p]
  int residuals = 0;   // residuals inside the clip
  std::vector<int> outliers;  // the distinct points outside the clip (snaps), in order
};
TraceNoise estimateTraceNoise(const Eigen::Matrix3Xd& p);

// a traced polyline smoothed (docs/experiments.md, "Noise"): local quadratic regression of the points
// against their arc length (LOESS: tricube weights over a half-width b, grown locally where fewer than 4
// points lie within it), b = 2.5 ... 30 median point spacings (at most a sixth of the length) chosen by
// generalised cross-validation, GCV(b) = n RSS / (n - 1.4 tr H)^2 (Kim & Gu 2004); twice, the second time against the arc
// length of the first pass's curve. Evaluated at arc-length steps of about ds (ds <= 0: at the points'
// own arc lengths; the ends are kept). Fewer than 7 distinct points are not smoothed (points: the
// polyline, resampled at ds when ds > 0; halfWidth 0).
struct TraceSmoothing {
  Eigen::Matrix3Xd points;  // the smoothed curve [unit of p]
  double halfWidth = 0;     // b, where the weights reach 0 [unit of p] (0: not smoothed)
  double leverage = 1;      // the mean hat-matrix diagonal tr H / n of the last pass (1: not smoothed): a
                            // smoothed value's white noise is at most sigma sqrt(H_ii) (LOESS with weights
                            // <= 1: sum_j L_ij^2 <= L_ii)
};
TraceSmoothing smoothTrace(const Eigen::Matrix3Xd& p, double ds);

// the excursion a traced root's peak needs (docs/experiments.md, "Noise: a phenotype or the tracing"): the
// tracing limit. A tracer's error has two parts. One is white: jitter and rounding, sigma per point, a
// smoothed value's sigma_s = sigma sqrt(tr H / n) (TraceSmoothing::leverage), so an excursion between two
// smoothed values sqrt(2) sigma_s, passed at kNoisePeakK of it rarely. The other is correlated over
// millimetres and survives any smoothing that keeps a wave: the tracer puts the centreline anywhere
// across the root's image, it drifts there and snaps to the edges, so two placements differ by up to one
// root diameter 2R. An excursion within 2R + kNoisePeakK sqrt(2) sigma_s can be the tracing alone; a peak
// counts only beyond it. sigma_s unknown (NaN: too few points): 2R alone.
inline constexpr double kNoisePeakK = 3.0;
inline constexpr double kPlacementDiameters = 1.0;  // the placement's range, in root diameters
double tracingLimitMm(double smoothedSigmaMm, double radiusMm);

struct RootTraits {
  double lengthMm = 0;          // arc length of the trace [mm]
  double chordMm = 0;           // straight base-to-tip distance [mm]
  double tortuosity = 0;        // length / chord (1 for a straight root; inf for a closed loop)
  double skewDeg = 0;           // base-to-tip direction from downhill, sign as theta (counter-clockwise
                                // seen from the plate's normal, i.e. towards -lateral is negative) [deg]
  int matureLast = 0;           // last point of the mature part used by the shape analysis (resampled)
  double dsMm = 0;              // the resampling step of the shape analysis [mm]; 0: the trace's own points
  ShapeAnalysis shape;          // the run observables of the mature part (SI units as analysis.hpp)
  double noiseMm = std::numeric_limits<double>::quiet_NaN();  // the points' position noise sigma
                                // (estimateTraceNoise) [mm]; NaN: fewer than 9 distinct points
  double smoothingMm = 0;       // half-width of the smoothing windows [mm]; 0: measured as it is
  double noiseThresholdMm = 0;  // a trace's tracing limit (tracingLimitMm), the excursion a peak needs
                                // [mm]; 0: none (a run's nodes: the hysteresis of R alone)
  // the field's traits on the measured curve (smoothed for a trace): Grabov et al. 2005
  double curveLengthMm = 0;     // arc length of the measured curve [mm]
  double straightness = 0;      // its chord / its length (1: straight)
  double hgi = 0;               // horizontal growth index: tip's lateral displacement from the base / length,
                                // signed as the skew angle (towards +lateral positive)
  double vgi = 0;               // vertical growth index: tip's downhill displacement from the base / length
  double bowMm = 0;             // the mature part's bow: the largest distance of its curve from the chord
                                // between its ends [mm]
  double bendDeg = 0;           // its turning angle: the direction of its last third (the chord across
                                // it) less that of its first third, sign as theta [deg]
  double thetaTipDeg = 0;       // planar tip angle of the measured curve's last segment, sign as theta [deg]
  std::string wavesNote;        // why lambda (or lambda and A) are not measured; "" when both are
  Eigen::Matrix3Xd curveMm;     // the curve the shape analysis measured (plate coordinates [mm])
};

// the traits of one root given in plate coordinates [mm] (columns: lateral, downhill, height), base first.
// The shape analysis runs on the trace resampled at dsMm (a run's element length: curvature and peaks are
// read at the resolution runs have; dsMm <= 0: on the trace's own points) and on its mature part: the whole trace but the last excludeTipMm of
// arc length (a run's growth zone). radiusMm sets the peaks' hysteresis (set.waveMinAmplitude * R).
// Throws std::invalid_argument for fewer than two distinct points.
// The points are measured as they are (a run's nodes: no noise); noiseMm is still estimated and reported.
RootTraits rootTraits(const Eigen::Matrix3Xd& plateMm, double dsMm, double excludeTipMm, double radiusMm,
                      const AnalysisParams& set);
// the same for a traced root (docs/experiments.md, "Noise"): its noise sigma estimated, the shape analysis
// run on the smoothed curve (smoothTrace of the points less the noise's outliers, evaluated every dsMm, or at the trace's own points for dsMm <= 0)
// with the peaks' hysteresis raised to the tracing limit (tracingLimitMm of the smoothed curve's sigma and
// radiusMm); peaks beyond it are a wave only as a wave train (3 successive half-waves within 2x of each
// other), else the root is measured as not waving and wavesNote says which rule it failed. A root then
// "straight" with at most one excursion above the limit, its bow beyond it and its turning beyond the skew
// threshold and 2 atan(3 limit / L) is "curved" (one bend). The length,
// chord, tortuosity and base-to-tip skew stay the trace's own. Throws std::invalid_argument for fewer than
// two distinct points.
RootTraits traceTraits(const Eigen::Matrix3Xd& plateMm, double dsMm, double excludeTipMm, double radiusMm,
                       const AnalysisParams& set);

// a run's root measured as the trace `as` was (its traits: the rule every comparison of a run with a
// trace follows, docs/experiments.md "Fit"): the nodes smoothed by smoothTrace's LOESS at the trace's own
// half-width as.smoothingMm (one pass against the nodes' arc length: a run has no noise to choose a width
// from or to run ahead of its arc length), evaluated every as.dsMm (as.dsMm <= 0: at the nodes), then the
// shape analysis of rootTraits: the peaks' hysteresis of R (a run has no tracing noise to hide its inner
// swings), except at the two ends of the wave train, which take the trace's tracing limit
// as.noiseThresholdMm (analyseCentreline's endSwing): a first peak the root leaves its base towards by
// less than the limit, or a last one it comes back from by less, is no peak of the run, as it is none of
// the trace. A smoothing that flattens a traced wave's peaks flattens the run's alike. as.smoothingMm 0 (a
// trace measured as it is): rootTraits at as.dsMm with those ends. Throws std::invalid_argument for fewer
// than two distinct points.
RootTraits rootTraitsAs(const Eigen::Matrix3Xd& plateMm, const RootTraits& as, double excludeTipMm, double radiusMm,
                        const AnalysisParams& set);

// the insertion angle of a lateral on its parent [deg], in [0, 180]: the angle between the lateral's
// direction over its first spanMm of arc length (base to the point there) and the parent's tangent at the
// parent point nearest the lateral's base, taken over spanMm of the parent on either side (towards the
// parent's tip). Both in plate coordinates [mm]. NaN when the parent has no length.
double insertionAngleDeg(const Eigen::Matrix3Xd& parentMm, const Eigen::Matrix3Xd& lateralMm, double spanMm);

}  // namespace rootsim
