// The relaxation's scratch memory (relax.hpp).
#include "rootsim/relax.hpp"

namespace rootsim {

void RelaxWorkspace::resize(int n) {
  strains.resize(n);
  force.resize(3, n + 1);
  torque.resize(3, n);
  mass.resize(n + 1);
  inertia.resize(3, n);
  invMass.resize(n + 1);
  invInertia.resize(3, n);
  xStart.resize(3, n + 1);
  contact.resize(n);
}

}  // namespace rootsim
