#pragma once
// Phenotyping traits of a root's centreline on the plate (docs/experiments.md): what a root lab measures on
// a scanned plate (length, base-to-tip skew angle, tortuosity, the insertion angle of a lateral) and the
// observables of a run (pattern, lambda, A, lateral peaks, skew over whole waves, max kappa: analysis.hpp)
// computed by the very code that measures runs. Plain geometry: no file formats here.
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

struct RootTraits {
  double lengthMm = 0;          // arc length of the trace [mm]
  double chordMm = 0;           // straight base-to-tip distance [mm]
  double tortuosity = 0;        // length / chord (1 for a straight root; inf for a closed loop)
  double skewDeg = 0;           // base-to-tip direction from downhill, sign as theta (counter-clockwise
                                // seen from the plate's normal, i.e. towards -lateral is negative) [deg]
  int matureLast = 0;           // last point of the mature part used by the shape analysis (resampled)
  double dsMm = 0;              // the resampling step of the shape analysis [mm]; 0: the trace's own points
  ShapeAnalysis shape;          // the run observables of the mature part (SI units as analysis.hpp)
};

// the traits of one root given in plate coordinates [mm] (columns: lateral, downhill, height), base first.
// The shape analysis runs on the trace resampled at dsMm (a run's element length: curvature and peaks are
// read at the resolution runs have; dsMm <= 0: on the trace's own points) and on its mature part: the whole trace but the last excludeTipMm of
// arc length (a run's growth zone). radiusMm sets the peaks' hysteresis (set.waveMinAmplitude * R).
// Throws std::invalid_argument for fewer than two distinct points.
RootTraits rootTraits(const Eigen::Matrix3Xd& plateMm, double dsMm, double excludeTipMm, double radiusMm,
                      const AnalysisParams& set);

// the insertion angle of a lateral on its parent [deg], in [0, 180]: the angle between the lateral's
// direction over its first spanMm of arc length (base to the point there) and the parent's tangent at the
// parent point nearest the lateral's base, taken over spanMm of the parent on either side (towards the
// parent's tip). Both in plate coordinates [mm]. NaN when the parent has no length.
double insertionAngleDeg(const Eigen::Matrix3Xd& parentMm, const Eigen::Matrix3Xd& lateralMm, double spanMm);

}  // namespace rootsim
