// The cases of the figure panels: a number's short text, a case's run directory, its model and scene info.
#include "figure_cases.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace rootsim::fig {


std::string dirOf(const Ctx& c, const Case& k) {
  return std::string(c.opt.quick ? "quick" : "full") + "_a" + significantText(k.alpha) + "_b" + significantText(k.beta) + "_g" +
         significantText(k.gamma) + "_t" + significantText(k.rTau) + (k.free ? "_free" : "") + (k.apical ? "_apical" : "") + "_L" +
         significantText(k.lengthMm);
}

Model modelOf(const Ctx& c, const Case& k) {
  Model m = defaultModel();
  m.name = kFigureSceneName;
  m.env.plane.alpha = k.alpha * units::deg;
  m.tropism.beta = k.beta;
  m.tropism.gamma = k.gamma;
  m.tropism.rTau = k.rTau;
  m.tropism.sensing = k.apical ? Sensing::Apical : Sensing::Local;
  if (k.free) {
    m.env.plane.enabled = false;
    m.env.adhesion = false;
  }
  m.initial.elementLength = c.h() * units::mm;
  m.growth.stepTime = c.dt() * units::hour;
  // from the initial 1.1 mm at v_tip = 0.2 mm/h (the default growth zone and rate)
  m.growth.steps = static_cast<int>(std::lround((k.lengthMm - 1.1) / (0.2 * c.dt())));
  completeModel(m);
  return m;
}

OutputParams outputOf(const Ctx& c) {
  OutputParams o;
  o.vtk = false;
  o.everySteps = std::max(1, static_cast<int>(std::lround(0.5 / c.dt())));  // every half hour
  return o;
}

SceneInfo infoOf(const Ctx& c, const Case& k) { return sceneInfoOf(modelOf(c, k)); }

}  // namespace rootsim::fig
