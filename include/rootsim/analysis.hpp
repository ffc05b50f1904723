#pragma once
// Observables (MODEL.md section 8).
#include <string>

#include "rootsim/model.hpp"

namespace rootsim {

// planar tip angle theta_tip (MODEL.md section 3) [rad], in (-pi, pi]; without a plate (free organ)
// the angle of the tip from gravity in the vertical plane of motion, about +x (starts at -alpha)
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

// growth-zone observables of a relaxed state (strains must belong to it)
struct ZoneObservables {
  double Eb = 0, Et = 0;   // bending and twisting energies of the zone (no factor 1/2) [J]
  double Wr = 0, Tw = 0;   // writhe of the zone centreline, twist (1/2pi) int kappa3 ds
};
ZoneObservables observeZone(const Model& m, const RodState& s, const RodStrains& k);

// the final shape on the plate
struct ShapeAnalysis {
  std::string pattern;        // straight | waving | coiling | skewing
  double wavelength = 0;      // mean distance between neighbouring lateral peaks along downhill [m] (0: none)
  double amplitude = 0;       // half the mean lateral peak-to-peak distance [m]
  int peaks = 0;              // lateral extrema used
  double skew = 0;            // mean planar angle of the mature shape [rad]
  double maxKappa = 0;        // max curvature of the shape projected on the plane [1/m]
  double thetaMin = 0, thetaMax = 0;  // range of the unwrapped planar tangent angle [rad]
};
ShapeAnalysis analyseShape(const Model& m, const RodState& s);

}  // namespace rootsim
