#pragma once
// The constant description of a simulation, built from a scene (docs/model.md, Experiment and
// parameters). SI units inside.
#include <optional>
#include <string>

#include "rootsim/initial.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

enum class Sensing { Local, Apical };

// how the gravitropic set-point angle goes from its initial to its final value with the organ's age
// (docs/plate.md, Set-point drift): linearly, reaching it at the drift time; or exponentially, the drift
// time its time constant
enum class SetPointDrift { Linear, Exponential };

struct GrowthParams {
  bool enabled = true;
  double zoneLength = 1e-3;        // Lgz [m]
  double rate = 0.2 / units::hour;  // relative growth rate in the zone, eps0 [1/s]
  int steps = 3000;                // growth steps
  double stepTime = 0.05 * units::hour;  // growth step [s]
  double splitFactor = 2.0;        // an element longer than splitFactor * h is split in two
};

struct TropismParams {
  double beta = 0.1;               // gravitropic gain
  double gamma = 0.1;              // proprioceptive gain
  Sensing sensing = Sensing::Local;
  double rTau = 0.0;               // intrinsic twist R tau (dimensionless)
  double cnGain = 0.0;             // circumnutation gain lambda_cn
  double cnPeriod = 1.0 * units::hour;  // circumnutation period [s]
  // gravitropic set-point angle phi_s (docs/plate.md, Lateral roots): the organ grows towards
  // g_s = cos(phi_s) g + sin(phi_s) h, h the horizontal direction of its apex's tangent; 0: towards g
  // (the primary root's law). A lateral root's; a plate seedling's set_point_deg, not a scene key.
  // phi_s drifts with the organ's age from setPoint towards setPointFinal (setPointAt, growth.hpp);
  // none, or equal to setPoint: no drift
  double setPoint = 0.0;                   // [rad]
  std::optional<double> setPointFinal;     // [rad]
  SetPointDrift setPointDrift = SetPointDrift::Exponential;
  double setPointDriftTime = 24.0 * units::hour;  // linear: time to reach setPointFinal; exponential:
                                                  // the time constant [s] (> 0)
};

struct AnalysisParams {
  double skewThresholdDeg = 5.0;   // |<theta>| above this is "skewing" [deg]
  double coilTurnDeg = 180.0;      // planar tangent turning through more than this is "coiling" [deg]
  double waveMinAmplitude = 0.5;   // hysteresis of the lateral turning points, in R: a swing smaller than
                                   // this is not a peak (so a root whose lateral peak-to-peak stays below it is "straight")
  double skewMinWaves = 2.0;       // a skew is judged only over at least this many full waves
                                   // (docs/model.md, Observables)
};

struct Model {
  std::string name;                // scene name (file stem)
  RodParams rod;
  Environment env;                 // plane, adhesion, base, loads
  InitialShape initial;            // L0, target element length h, perturbation, seed
  GrowthParams growth;
  TropismParams tropism;
  SolverOptions solver;
  AnalysisParams analysis;
};

// The defaults: the paper's parameters (docs/model.md, Experiment and parameters) and rootsim's numerical
// choices. They are written once, as the member initialisers of the parameter structs (this header, rod.hpp,
// environment.hpp, relax.hpp, initial.hpp; what a run writes: io's output_params.hpp); defaultModel() is the way to read them, and the scene
// schema takes every key's default from it.
Model defaultModel();

// fills in what follows from the other parameters, once, when a model is built (the model is constant
// afterwards): the solver's length scale Lref is the growth zone for a growing root (its equilibrium
// tolerance must not loosen as the root grows), the rod itself otherwise
void completeModel(Model& m);

}  // namespace rootsim
