// the scene of a model built in code (sceneOf, src/io/scene.cpp): the schema's getters read the model
// back into scene values, so model -> scene -> model is exact and the text is the one a scene file with
// the same values resolves to (what `rootsim run` writes as scene.toml)
#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "run_rootsim.hpp"

using namespace rootsim;

namespace {

// every field of the model the schema maps (and the derived length scale, the name, the obstacles),
// doubles bitwise: an empty result means the same model
std::string differences(const Model& a, const Model& b) {
  std::ostringstream os;
  auto num = [&](const char* what, double x, double y) {
    if (std::bit_cast<std::uint64_t>(x) != std::bit_cast<std::uint64_t>(y)) os << what << ": " << x << " vs " << y << "\n";
  };
  auto same = [&](const char* what, bool equal) {
    if (!equal) os << what << " differs\n";
  };
  auto vec = [&](const char* what, const Vec3& x, const Vec3& y) {
    for (int i = 0; i < 3; ++i) num(what, x[i], y[i]);
  };
  same("name", a.name == b.name);
  num("rod.radius", a.rod.radius, b.rod.radius);
  num("rod.youngs", a.rod.youngs, b.rod.youngs);
  num("rod.density", a.rod.density, b.rod.density);
  num("initial.length", a.initial.length, b.initial.length);
  num("initial.elementLength", a.initial.elementLength, b.initial.elementLength);
  num("initial.perturbation", a.initial.perturbation, b.initial.perturbation);
  same("initial.seed", a.initial.seed == b.initial.seed);
  same("growth.enabled", a.growth.enabled == b.growth.enabled);
  num("growth.zoneLength", a.growth.zoneLength, b.growth.zoneLength);
  num("growth.rate", a.growth.rate, b.growth.rate);
  same("growth.steps", a.growth.steps == b.growth.steps);
  num("growth.stepTime", a.growth.stepTime, b.growth.stepTime);
  num("growth.splitFactor", a.growth.splitFactor, b.growth.splitFactor);
  num("tropism.beta", a.tropism.beta, b.tropism.beta);
  num("tropism.gamma", a.tropism.gamma, b.tropism.gamma);
  same("tropism.sensing", a.tropism.sensing == b.tropism.sensing);
  num("tropism.rTau", a.tropism.rTau, b.tropism.rTau);
  num("tropism.cnGain", a.tropism.cnGain, b.tropism.cnGain);
  num("tropism.cnPeriod", a.tropism.cnPeriod, b.tropism.cnPeriod);
  same("env.plane.enabled", a.env.plane.enabled == b.env.plane.enabled);
  num("env.plane.alpha", a.env.plane.alpha, b.env.plane.alpha);
  num("env.plane.k", a.env.plane.k, b.env.plane.k);
  num("env.plane.c", a.env.plane.c, b.env.plane.c);
  same("env.adhesion", a.env.adhesion == b.env.adhesion);
  num("env.kAdhesion", a.env.kAdhesion, b.env.kAdhesion);
  same("env.selfContact.enabled", a.env.selfContact.enabled == b.env.selfContact.enabled);
  num("env.selfContact.k", a.env.selfContact.k, b.env.selfContact.k);
  same("env.friction.enabled", a.env.friction.enabled == b.env.friction.enabled);
  num("env.friction.muStatic", a.env.friction.muStatic, b.env.friction.muStatic);
  num("env.friction.muKinetic", a.env.friction.muKinetic, b.env.friction.muKinetic);
  num("env.friction.axialRatio", a.env.friction.axialRatio, b.env.friction.axialRatio);
  num("env.friction.slipWeakening", a.env.friction.slipWeakening, b.env.friction.slipWeakening);
  vec("env.tipForce", a.env.tipForce, b.env.tipForce);
  vec("env.tipTorque", a.env.tipTorque, b.env.tipTorque);
  same("env.base", a.env.base == b.env.base);
  vec("env.gravity", a.env.gravity, b.env.gravity);
  same("env.obstacles.size", a.env.obstacles.size() == b.env.obstacles.size());
  same("solver.kind", a.solver.kind == b.solver.kind);
  num("solver.window", a.solver.window, b.solver.window);
  same("solver.newtonMaxIterations", a.solver.newtonMaxIterations == b.solver.newtonMaxIterations);
  same("solver.mass", a.solver.mass == b.solver.mass);
  same("solver.damping", a.solver.damping == b.solver.damping);
  num("solver.viscousRate", a.solver.viscousRate, b.solver.viscousRate);
  num("solver.forceTol", a.solver.forceTol, b.solver.forceTol);
  num("solver.speedTol", a.solver.speedTol, b.solver.speedTol);
  same("solver.maxSubsteps", a.solver.maxSubsteps == b.solver.maxSubsteps);
  num("solver.lengthScale", a.solver.lengthScale, b.solver.lengthScale);
  same("solver.stabilityCheck", a.solver.stabilityCheck == b.solver.stabilityCheck);
  num("analysis.skewThresholdDeg", a.analysis.skewThresholdDeg, b.analysis.skewThresholdDeg);
  num("analysis.coilTurnDeg", a.analysis.coilTurnDeg, b.analysis.coilTurnDeg);
  num("analysis.waveMinAmplitude", a.analysis.waveMinAmplitude, b.analysis.waveMinAmplitude);
  num("analysis.skewMinWaves", a.analysis.skewMinWaves, b.analysis.skewMinWaves);
  same("output.everySteps", a.output.everySteps == b.output.everySteps);
  same("output.trajectory", a.output.trajectory == b.output.trajectory);
  same("output.vtk", a.output.vtk == b.output.vtk);
  return os.str();
}

// a model set in code and the --set overrides that say the same
struct Variant {
  const char* what;
  std::function<void(Model&)> set;
  std::vector<std::string> sets;
};

const std::vector<Variant>& variants() {
  using units::deg;
  using units::hour;
  using units::mm;
  static const std::vector<Variant> v = {
      {"default", [](Model&) {}, {}},
      {"alpha 65, beta 0.2, gamma 0.05",
       [](Model& m) {
         m.env.plane.alpha = 65 * deg;
         m.tropism.beta = 0.2;
         m.tropism.gamma = 0.05;
       },
       {"plane.alpha_deg=65", "tropism.beta=0.2", "tropism.gamma=0.05"}},
      // 7.5 * deg / deg is not 7.5: the getter still reads 7.5 (the figure's alpha = 7.5 runs)
      {"alpha 7.5", [](Model& m) { m.env.plane.alpha = 7.5 * deg; }, {"plane.alpha_deg=7.5"}},
      {"twist and apical sensing",
       [](Model& m) {
         m.env.plane.alpha = 37.5 * deg;
         m.tropism.rTau = -0.35;
         m.tropism.sensing = Sensing::Apical;
       },
       {"plane.alpha_deg=37.5", "tropism.twist_r_tau=-0.35", "tropism.sensing=apical"}},
      {"free organ, coarse quick run",
       [](Model& m) {
         m.env.plane.enabled = false;
         m.env.adhesion = false;
         m.env.plane.alpha = 40 * deg;
         m.initial.elementLength = 0.1 * mm;
         m.growth.stepTime = 0.1 * hour;
         m.growth.steps = 445;
         m.output.vtk = false;
         m.output.everySteps = 5;
       },
       {"plane.enabled=false", "adhesion.enabled=false", "plane.alpha_deg=40", "root.element_length_mm=0.1",
        "growth.step_h=0.1", "growth.steps=445", "output.vtk=false", "output.every_steps=5"}},
      {"self-contact off, dynamic solver with viscous damping",
       [](Model& m) {
         m.env.selfContact.enabled = false;
         m.solver.kind = SolverKind::Dynamic;
         m.solver.damping = Damping::Viscous;
         m.solver.viscousRate = 3e4;
         m.solver.mass = MassModel::Physical;
         m.solver.forceTol = 3e-5;
         m.solver.maxSubsteps = 123456;
       },
       {"self_contact.enabled=false", "solver.kind=dynamic", "solver.damping=viscous", "solver.damping_per_s=3e4",
        "solver.mass=physical", "solver.force_tol=3e-5", "solver.max_substeps=123456"}},
      {"friction, circumnutation, growth zone and rate, radius, window",
       [](Model& m) {
         m.env.friction.enabled = true;
         m.env.friction.muStatic = 0.4;
         m.env.friction.muKinetic = 0.3;
         m.env.friction.slipWeakening = 0.07 * mm;
         m.tropism.cnGain = 0.3;
         m.tropism.cnPeriod = 1.7 * hour;
         m.growth.zoneLength = 1.3 * mm;
         m.growth.rate = 0.35 / hour;
         m.rod.radius = 0.13 * mm;
         m.rod.youngs = 7.3 * units::mpa;
         m.solver.window = 2.5 * mm;
         m.initial.seed = 42;
         m.initial.perturbation = 3e-6;
       },
       {"friction.enabled=true", "friction.mu_static=0.4", "friction.mu_kinetic=0.3", "friction.slip_weakening_mm=0.07",
        "tropism.circumnutation_gain=0.3", "tropism.circumnutation_period_h=1.7", "growth.growth_zone_mm=1.3",
        "growth.rate_per_h=0.35", "root.radius_mm=0.13", "root.youngs_modulus_mpa=7.3", "solver.window_mm=2.5",
        "solver.seed=42", "solver.perturbation=3e-6"}},
      {"mechanics only: loads, free base, gravity",
       [](Model& m) {
         m.growth.enabled = false;
         m.env.plane.enabled = false;
         m.env.tipForce = Vec3(1e-6, 0, -2.5e-6);
         m.env.tipTorque = Vec3(0, 3e-9, 0);
         m.env.gravity = Vec3(0, 0, -9.81);
         m.analysis.coilTurnDeg = 270;
       },
       {"growth.enabled=false", "plane.enabled=false", "load.tip_force_n=[1e-6, 0, -2.5e-6]",
        "load.tip_torque_nm=[0, 3e-9, 0]", "load.gravity=true", "analysis.coil_turn_deg=270"}},
  };
  return v;
}

Model modelOf(const Variant& v) {
  Model m = defaultModel();
  m.name = "variant";
  v.set(m);
  completeModel(m);
  return m;
}

}  // namespace

TEST_CASE("sceneOf: model -> scene -> model is exact, and the text is the scene file's") {
  for (const Variant& v : variants()) {
    INFO(v.what);
    const Model m = modelOf(v);
    const Scene typed = sceneOf(m);
    // the scene holds the model given
    CHECK(differences(typed.model, m) == "");
    // its text loads back to the same model
    const Scene loaded = parseScene(typed.resolvedToml, "runs/variant.toml");
    CHECK(differences(loaded.model, m) == "");
    // and it is the text the same settings given as overrides resolve to
    const Scene fromSets = parseScene("", "scenes/variant.toml", v.sets);
    CHECK(differences(fromSets.model, m) == "");
    CHECK(typed.resolvedToml == fromSets.resolvedToml);
  }
}

TEST_CASE("sceneOf: the text is the scene.toml `rootsim run` writes") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "rootsim_test_scene_of";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    std::ofstream(dir / "variant.toml") << "";
  }
  for (const Variant& v : variants()) {
    INFO(v.what);
    Model m = modelOf(v);
    m.growth.steps = 0;  // the scene file is written before anything runs; no need to grow
    m.output.vtk = false;
    std::string args = "run " + (dir / "variant.toml").string() + " --out " + (dir / "run").string() + " --force --quiet";
    for (const std::string& s : v.sets) args += " --set '" + s + "'";
    args += " --set growth.steps=0 --set output.vtk=false";  // later overrides win
    const auto r = test::run(args);
    REQUIRE_MESSAGE(r.code == 0, r.out);
    std::ifstream in(dir / "run" / "scene.toml");
    std::stringstream written;
    written << in.rdbuf();
    CHECK(sceneOf(m).resolvedToml == written.str());
  }
  fs::remove_all(dir);
}

TEST_CASE("sceneOf: a model out of a key's range is refused, naming the key") {
  Model m = defaultModel();
  m.name = "bad";
  m.tropism.beta = -1;
  CHECK_THROWS_WITH_AS(sceneOf(m), doctest::Contains("model bad: tropism.beta must be in [0, 100] (got -1)"),
                       SceneError);
  m = defaultModel();
  m.name = "bad";
  m.initial.elementLength = 0.6 * units::mm;  // more than half the initial length
  CHECK_THROWS_WITH_AS(sceneOf(m), doctest::Contains("model bad: root.element_length_mm must be at most half"),
                       SceneError);
}
