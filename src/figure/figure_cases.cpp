#include "figure_cases.hpp"

#include <sstream>

#include "rootsim/units.hpp"

namespace rootsim::fig {

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string dirOf(const Ctx& c, const Case& k) {
  return std::string(c.opt.quick ? "quick" : "full") + "_a" + num(k.alpha) + "_b" + num(k.beta) + "_g" +
         num(k.gamma) + "_t" + num(k.rTau) + (k.free ? "_free" : "") + (k.apical ? "_apical" : "") + "_L" +
         num(k.lengthMm);
}

std::vector<std::string> setsOf(const Ctx& c, const Case& k) {
  const int steps = static_cast<int>(std::lround((k.lengthMm - 1.1) / (0.2 * c.dt())));
  std::vector<std::string> s = {
      "plane.alpha_deg=" + num(k.alpha),     "tropism.beta=" + num(k.beta),
      "tropism.gamma=" + num(k.gamma),       "tropism.twist_r_tau=" + num(k.rTau),
      "root.element_length_mm=" + num(c.h()), "growth.step_h=" + num(c.dt()),
      "growth.steps=" + std::to_string(steps), "output.vtk=false",
      "output.every_steps=" + std::to_string(std::max(1, static_cast<int>(std::lround(0.5 / c.dt()))))};
  if (k.apical) s.push_back("tropism.sensing=apical");
  if (k.free) {
    s.push_back("plane.enabled=false");
    s.push_back("adhesion.enabled=false");
  }
  return s;
}

Model modelOf(const Case& k) {
  Model m;
  m.env.plane.alpha = k.alpha * units::deg;
  m.tropism.beta = k.beta;
  m.tropism.gamma = k.gamma;
  m.tropism.rTau = k.rTau;
  m.tropism.sensing = k.apical ? Sensing::Apical : Sensing::Local;
  return m;
}

SceneInfo infoOf(const Case& k) {
  SceneInfo si;
  si.alphaDeg = k.alpha;
  si.beta = k.beta;
  si.gamma = k.gamma;
  si.rTau = k.rTau;
  si.plate = !k.free;
  return si;
}

}  // namespace rootsim::fig
