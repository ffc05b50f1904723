#pragma once
// Observables (docs/model.md, Observables).
#include <string>
#include <vector>

#include "rootsim/model.hpp"

namespace rootsim {

// planar tip angle theta_tip (docs/model.md, Frames and signs) [rad], in (-pi, pi]; without a plate (free
// organ) the angle of the tip from gravity in the vertical plane of motion, about +x (starts at -alpha)
double tipAngle(const Model& m, const RodState& s);
// signed planar angle of a lab direction against downhill, counter-clockwise seen from the normal [rad]
double planarAngle(const Plane& plane, const Vec3& t);

// writhe of the open polyline through columns [first, last] of p (exact Gauss double integral over
// segment pairs, Klenin & Langowski, Biopolymers 54, 307, 2000)
double writheOpen(const Eigen::Matrix3Xd& p, int first, int last);
// writhe of the closed polygon through all columns of p
double writheClosed(const Eigen::Matrix3Xd& p);
// Gauss linking number of two closed polygons
double linkingNumber(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b);

// rest arc length of Voronoi domain j (from the centre of element j to that of element j + 1) that lies
// in [Sfrom, Sto] [m]
double zoneShare(const RodState& s, int j, double Sfrom, double Sto);

// growth-zone observables of a relaxed state (strains must belong to it), integrated over exactly the last
// Lgz of rest arc length, the domain and element straddling the zone's start counted pro rata
// (docs/model.md, Observables)
struct ZoneObservables {
  double Eb = 0, Et = 0;   // bending and twisting energies of the zone (no factor 1/2) [J]:
                           //   int m.(dk1 d1 + dk2 d2) ds and int m.(dk3 d3) ds
  double Wr = 0, Tw = 0;   // writhe of the zone centreline (open-curve Gauss integral), twist
                           //   (1/2pi) int kappa3 ds [turns]
};
ZoneObservables observeZone(const Model& m, const RodState& s, const RodStrains& k);

// the final shape on the plate (docs/model.md, Observables). Waves are read from the turning points ("peaks")
// of the lateral displacement of the mature part along the rod, found with a hysteresis of
// analysis.wave_min_amplitude_r * R so numerical ripples are not peaks; consecutive peaks alternate sides.
struct ShapeAnalysis {
  std::string pattern;        // straight | waving | coiling | skewing (and a trace's curved: traits.hpp)
  double wavelength = 0;      // lambda: mean downhill distance between successive peaks on the same side
                              //   (a full wave) [m] (0: fewer than 3 peaks)
  double amplitude = 0;       // A: mean lateral distance between neighbouring (opposite) peaks, the
                              //   peak-to-peak excursion, as the paper's Fig. 3B caption measures it [m]
                              //   (0: fewer than 2 peaks)
  double amplitudeHalf = 0;   // A / 2, the half excursion (what the triangle argument of Eq. 10 calls A) [m]
  int peaks = 0;              // lateral turning points used
  double waves = 0;           // full waves between the first and the last peak, (peaks - 1) / 2
  double skew = 0;            // mean planar angle of the mature shape [rad]: over whole waves (first peak to
                              //   the last peak on its side) when there are at least 3 peaks, otherwise
                              //   the direction of the mature part as a whole
  bool skewJudged = false;    // true when the pattern could be "skewing": no waves at all (fewer than 2
                              //   peaks) or at least analysis.skew_min_waves full waves
  double maxKappa = 0;        // max curvature of the shape projected on the plane [1/m]
  double thetaMin = 0, thetaMax = 0;  // range of the unwrapped planar tangent angle [rad]
  std::vector<int> peakNodes; // the columns of the centreline at the peaks, in order along it
  double hysteresis = 0;      // the peaks' hysteresis used: the larger of analysis.wave_min_amplitude_r * R
                              //   and the noise threshold given to analyseCentreline [m]
};
// pattern rule, in order: coiling if the planar tangent turns through more than analysis.coil_turn_deg;
// with 2 or more peaks but fewer than analysis.skew_min_waves full waves: waving (a short root's mean
// angle is biased by its incomplete wave, so a skew is not judged); otherwise skewing if |skew| exceeds
// analysis.skew_threshold_deg; otherwise waving (2 or more peaks) or straight.
ShapeAnalysis analyseShape(const Model& m, const RodState& s);
// that pattern rule applied to a's peaks, waves, skew and tangent angles: sets a.skewJudged and a.pattern
void judgePattern(ShapeAnalysis& a, const AnalysisParams& set);
// the last node of the mature part: nodes whose rest arc length S lies below the growth zone's start
// (all of them, n, when the run does not grow)
int matureLastNode(const Model& m, const RodState& s);
// the same analysis of any centreline lying on the plate pl (a run's nodes, or a traced root put into the
// lab frame): columns of x [m], the mature part being columns 0 .. last; set: the thresholds, radius: the
// root's radius R [m]; noiseSwing: a traced root's noise threshold k * sigma [m] (0 for a run). The
// hysteresis is the larger of set.waveMinAmplitude * R and noiseSwing, so a peak counts only when the
// excursion to its opposite neighbour exceeds both. endSwing [m]: what the open side of the train's two
// end peaks needs, the departure from the first node before the first peak and the return after the last
// peak within the mature part (the larger of it and the hysteresis; 0: the hysteresis): a run compared
// with a trace takes the trace's noise threshold there, so that a start or an end of its wave train the
// trace's threshold cannot see is not a peak of the run either, while its inner swings keep the run's own
// hysteresis. analyseShape is analyseCentreline(s.x, matureLastNode(m, s), m.env.plane, m.analysis,
// m.rod.radius). Throws std::invalid_argument for fewer than two points.
ShapeAnalysis analyseCentreline(const Eigen::Matrix3Xd& x, int last, const Plane& pl, const AnalysisParams& set,
                                double radius, double noiseSwing = 0.0, double endSwing = 0.0);

}  // namespace rootsim
