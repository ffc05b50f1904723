#include "rootsim/model.hpp"

namespace rootsim {

Model defaultModel() {
  Model m;
  completeModel(m);
  return m;
}

void completeModel(Model& m) { m.solver.lengthScale = m.growth.enabled ? m.growth.zoneLength : 0.0; }

}  // namespace rootsim
