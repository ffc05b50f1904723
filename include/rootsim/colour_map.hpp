#pragma once
// Colour along the tube (`--color-by`): a per-node scalar computed from a snapshot alone (the renderer
// never sees the simulation state), its range over a whole movie, and a perceptual colour map.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "rootsim/snapshot.hpp"

namespace rootsim {

enum class ColourField {
  None,       // plain ivory body
  Curvature,  // |kappa1, kappa2| per current length from neighbouring directors [1/mm]
  Twist,      // kappa3 per current length from neighbouring directors [rad/mm], signed
  Kappa1,     // bending component kappa1 (about d1) per current length [1/mm], signed
  Kappa2,     // bending component kappa2 (about d2) per current length [1/mm], signed
  Kappa0,     // |intrinsic bending curvature kappa0| per rest length, Snapshot::kappa0 [1/mm]
  Stretch,    // dilatation lambda_e = (R / radius)^2, from the element radius [-]
  Contact,    // plate contact force per node, Snapshot::plateForce [mN]
};

// "curvature" -> ColourField::Curvature ...; false for an unknown name
bool parseColourField(const std::string& name, ColourField& out);
// the names parseColourField accepts, comma separated (for error messages)
std::string colourFieldNames();
// colour bar title with its unit, e.g. "curvature [1/mm]" (UTF-8)
std::string colourFieldLabel(ColourField f);
// a signed field (twist, kappa1, kappa2): symmetric range about 0 and the diverging map; the others
// (magnitudes, stretch) use the sequential map
bool colourFieldSigned(ColourField f);

// the field at every node (n+1 values). Throws RenderError if the snapshot lacks what the field needs
// (kappa0 or plate force from an older trajectory, or a scene radius <= 0 for stretch).
Eigen::VectorXd nodeField(const Snapshot& s, const SceneInfo& info, ColourField f);

// one range for a whole movie, so a colour means the same value in every frame: [0, q99] for the
// magnitudes (curvature, kappa0, contact), [-q99, q99] of |x| for the signed fields (twist, kappa1,
// kappa2), [q1, q99] for stretch (q = quantile over every node of every snapshot, so one spike at the
// clamp does not wash the colours out)
std::array<double, 2> fieldRange(const std::vector<Snapshot>& snaps, const SceneInfo& info, ColourField f);

// viridis (van der Walt and Smith, matplotlib 2015), interpolated between its published 11 stops at
// 0, 0.1, ..., 1; t is clamped to [0, 1]; sRGB 0..1
std::array<float, 3> viridis(double t);

// Moreland's diverging "cool to warm" map (K. Moreland, Diverging Color Maps for Scientific
// Visualization, ISVC 2009): blue (t = 0) through neutral grey (t = 0.5) to red (t = 1), interpolated
// between its published 33 control points; lightness symmetric about the middle; t clamped; sRGB 0..1
std::array<float, 3> coolWarm(double t);

// the diverging map of the signed fields, built in CIELAB (D65) so it keeps off the hues of the ±d1
// stripes (pink, h* ≈ 355°; orange, h* ≈ 62°): blue (h* = 290°) for t < 0.5, green (h* = 150°) for
// t > 0.5, L* = 88 − 50·|2t − 1| and C* = 44·|2t − 1| (the most chroma both hues hold in sRGB at every
// lightness), so the neutral grey at 0.5 and the same lightness at ±x; t clamped; sRGB 0..1
std::array<float, 3> blueGreen(double t);

// the sequential map of the magnitudes: viridis over [0.1, 0.9] (its purple and yellow ends come within
// 35° of the stripes' hues)
std::array<float, 3> sequential(double t);

// the smallest CIELAB hue distance [deg] from sRGB colour c to the ±d1 stripes' colours of the renderer's
// material; 180 for a colour of chroma C* < 10 (a grey is told apart by its missing hue)
double stripeHueDistanceDeg(const std::array<float, 3>& c);

// the colour of field value v of f over range: blueGreen for a signed field (0 -> t = 0.5 when the
// range is symmetric), sequential otherwise; range must be increasing
std::array<float, 3> fieldColour(ColourField f, double v, const std::array<double, 2>& range);

}  // namespace rootsim
