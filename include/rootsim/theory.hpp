#pragma once
// Scaling laws of the paper (docs/model.md, Theory), printed beside every measurement.
#include "rootsim/model.hpp"

namespace rootsim {

struct Theory {
  double effectiveGain;     // beta Lgz / R
  double T0;                // turning time, Eq. 7 [s]
  double maxKappa;          // max curvature of the final shape, Eq. 8 [1/m]
  double wavelength;        // lambda = 2 T0 v_tip, Eq. 9 [m]
  double amplitude;         // A = T0 v_tip tan(alpha) / 2, Eq. 10 [m]; compared with the measured
                            // peak-to-peak A (docs/model.md, Observables)
  double alphaStraightToWave;  // Eq. 12 [rad] (NaN if no solution)
  double alphaWaveToCoil;      // Eq. 13 [rad]
  double omega;             // apex twist rate tau eps0 Lgz, Eq. 5 [rad/s]
  double omegaT0;           // omega T0
  double skewSmall;         // asin(omega T0 tan alpha), Eq. 14, for omega T0 << 1 [rad] (NaN if > 1)
  double skewLarge;         // asin(tan alpha), Eq. 15, for omega T0 >> 1 [rad] (NaN if > 1)
};

Theory theoryFor(const Model& m);

}  // namespace rootsim
