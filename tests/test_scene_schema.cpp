// the scene key schema (src/io/scene_schema.cpp): every key's setter and getter of the model, its range
// and the relations buildParams checks; through it the scene of a model built in code (sceneOf,
// src/io/scene.cpp): the getters read the model back into scene values, so model -> scene -> model is
// exact and the text is the one a scene file with the same values resolves to (what `rootsim run`
// writes as scene.toml)
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "scratch_support.hpp"

#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "scene_schema.hpp"
#include "scene_support.hpp"
#include "test_support.hpp"

using namespace rootsim;

namespace {
using rootsim::test::errorOf;

namespace sd = rootsim::detail;

// a scene value bitwise (its origin aside)
bool sameValue(const sd::Value& a, const sd::Value& b) {
  auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  return a.type == b.type && bits(a.num) == bits(b.num) && a.b == b.b && a.str == b.str && bits(a.vec[0]) == bits(b.vec[0]) &&
         bits(a.vec[1]) == bits(b.vec[1]) && bits(a.vec[2]) == bits(b.vec[2]);
}
std::string shown(const sd::Value& v) {
  std::ostringstream os;
  os.precision(17);
  os << v.num << " " << v.b << " \"" << v.str << "\" [" << v.vec[0] << ", " << v.vec[1] << ", " << v.vec[2] << "]";
  return os.str();
}
// the keys where two value sets differ (bitwise), with both values
std::string differingKeys(const sd::Values& a, const sd::Values& b) {
  std::string out;
  for (const sd::KeySpec& k : sd::schema())
    if (!sameValue(a.at(k.full()), b.at(k.full())))
      out += k.full() + " (" + shown(a.at(k.full())) + " vs " + shown(b.at(k.full())) + ") ";
  return out;
}

// values of a key other than its default, in its range, in the order tried: another choice for
// strings, the other bool, a vector for vectors, twice, half, a tenth, then 0.3 of the default for
// numbers (doubling and halving keep a decimal default's shortest text, so the value reads back as given)
std::vector<sd::Value> otherValues(const sd::KeySpec& k) {
  const sd::Value def = sd::defaultValue(k);
  std::vector<sd::Value> out;
  auto with = [&](auto change) {
    sd::Value v = def;
    v.origin = "--set";
    change(v);
    if (sd::checkValue(k, v).empty() && !sameValue(v, def)) out.push_back(v);
  };
  switch (k.type) {
    case sd::KeyType::String:
      for (const std::string& c : k.choices) with([&](sd::Value& v) { v.str = c; });
      break;
    case sd::KeyType::Boolean:
      with([](sd::Value& v) { v.b = !v.b; });
      break;
    case sd::KeyType::Vector3:
      with([&](sd::Value& v) { v.vec = {def.vec[0] + 1.5e-6, def.vec[1] - 2.5e-6, def.vec[2] + 0.75e-6}; });
      break;
    case sd::KeyType::Vector2:
      with([&](sd::Value& v) { v.vec = {def.vec[0] + 1.5, def.vec[1] - 2.5, 0.0}; });
      break;
    case sd::KeyType::Integer:
      for (double x : {2 * def.num, def.num + 1, def.num - 1}) with([&](sd::Value& v) { v.num = x; });
      break;
    case sd::KeyType::Real:
      for (double x : {2 * def.num, 0.5 * def.num, 0.1 * def.num, 0.3, 0.5 * (k.lo + std::min(k.hi, 1.0))})
        with([&](sd::Value& v) { v.num = x; });
      break;
  }
  return out;
}

// two models with their outputs: every key of the schema (valuesOf, bitwise), and what the schema does
// not map: the name, the obstacles and the derived length scale. An empty result means the same model
std::string differences(const sd::SceneParams& pa, const sd::SceneParams& pb) {
  std::string out = differingKeys(sd::valuesOf(pa, "a"), sd::valuesOf(pb, "b"));
  const Model& a = pa.model;
  const Model& b = pb.model;
  if (a.name != b.name) out += "name ";
  if (a.env.obstacles.size() != b.env.obstacles.size()) out += "obstacles ";
  if (std::bit_cast<std::uint64_t>(a.solver.lengthScale) != std::bit_cast<std::uint64_t>(b.solver.lengthScale))
    out += "solver.lengthScale ";
  return out;
}

// a model set in code and the --set overrides that say the same
struct Variant {
  const char* what;
  std::function<void(Model&, OutputParams&)> set;
  std::vector<std::string> sets;
};

const std::vector<Variant>& variants() {
  using units::deg;
  using units::hour;
  using units::mm;
  static const std::vector<Variant> v = {
      {"default", [](Model&, OutputParams&) {}, {}},
      {"alpha 65, beta 0.2, gamma 0.05",
       [](Model& m, OutputParams&) {
         m.env.plane.alpha = 65 * deg;
         m.tropism.beta = 0.2;
         m.tropism.gamma = 0.05;
       },
       {"plane.alpha_deg=65", "tropism.beta=0.2", "tropism.gamma=0.05"}},
      // 7.5 * deg / deg is not 7.5: the getter still reads 7.5 (the figure's alpha = 7.5 runs)
      {"alpha 7.5", [](Model& m, OutputParams&) { m.env.plane.alpha = 7.5 * deg; }, {"plane.alpha_deg=7.5"}},
      {"twist and apical sensing",
       [](Model& m, OutputParams&) {
         m.env.plane.alpha = 37.5 * deg;
         m.tropism.rTau = -0.35;
         m.tropism.sensing = Sensing::Apical;
       },
       {"plane.alpha_deg=37.5", "tropism.twist_r_tau=-0.35", "tropism.sensing=apical"}},
      {"free organ, coarse quick run",
       [](Model& m, OutputParams& o) {
         m.env.plane.enabled = false;
         m.env.adhesion = false;
         m.env.plane.alpha = 40 * deg;
         m.initial.elementLength = 0.1 * mm;
         m.growth.stepTime = 0.1 * hour;
         m.growth.steps = 445;
         o.vtk = false;
         o.everySteps = 5;
       },
       {"plane.enabled=false", "adhesion.enabled=false", "plane.alpha_deg=40", "root.element_length_mm=0.1",
        "growth.step_h=0.1", "growth.steps=445", "output.vtk=false", "output.every_steps=5"}},
      {"self-contact off, dynamic solver with viscous damping",
       [](Model& m, OutputParams&) {
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
       [](Model& m, OutputParams&) {
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
       [](Model& m, OutputParams&) {
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

sd::SceneParams paramsOf(const Variant& v) {
  sd::SceneParams p{defaultModel(), OutputParams{}};
  p.model.name = "variant";
  v.set(p.model, p.output);
  completeModel(p.model);
  return p;
}

}  // namespace

TEST_CASE("sceneOf: model -> scene -> model is exact, and the text is the scene file's") {
  for (const Variant& v : variants()) {
    INFO(v.what);
    const sd::SceneParams m = paramsOf(v);
    const Scene typed = sceneOf(m.model, m.output);
    // the scene holds the model given
    CHECK(differences({typed.model, typed.output}, m) == "");
    // its text loads back to the same model
    const Scene loaded = parseScene(typed.resolvedToml, "runs/variant.toml");
    CHECK(differences({loaded.model, loaded.output}, m) == "");
    // and it is the text the same settings given as overrides resolve to
    const Scene fromSets = parseScene("", "scenes/variant.toml", v.sets);
    CHECK(differences({fromSets.model, fromSets.output}, m) == "");
    CHECK(typed.resolvedToml == fromSets.resolvedToml);
  }
}

TEST_CASE("sceneOf: the text is the scene.toml `rootsim run` writes") {
  namespace fs = std::filesystem;
  const fs::path dir = rootsim::test::scratchDir("test", "scene_of");
  {
    std::ofstream(dir / "variant.toml") << "";
  }
  for (const Variant& v : variants()) {
    INFO(v.what);
    sd::SceneParams m = paramsOf(v);
    m.model.growth.steps = 0;  // the scene file is written before anything runs; no need to grow
    m.output.vtk = false;
    std::string args = "run " + (dir / "variant.toml").string() + " --out " + (dir / "run").string() + " --force --quiet";
    for (const std::string& s : v.sets) args += " --set '" + s + "'";
    args += " --set growth.steps=0 --set output.vtk=false";  // later overrides win
    const auto r = test::run(args);
    REQUIRE_MESSAGE(r.code == 0, r.out);
    std::ifstream in(dir / "run" / "scene.toml");
    std::stringstream written;
    written << in.rdbuf();
    CHECK(sceneOf(m.model, m.output).resolvedToml == written.str());
  }
  fs::remove_all(dir);
}

TEST_CASE("sceneOf: a model out of a key's range is refused, naming the key") {
  Model m = defaultModel();
  m.name = "bad";
  m.tropism.beta = -1;
  CHECK_THROWS_WITH_AS(sceneOf(m, OutputParams{}), doctest::Contains("model bad: tropism.beta must be in [0, 100] (got -1)"),
                       SceneError);
  m = defaultModel();
  m.name = "bad";
  m.initial.elementLength = 0.6 * units::mm;  // more than half the initial length
  CHECK_THROWS_WITH_AS(sceneOf(m, OutputParams{}), doctest::Contains("model bad: root.element_length_mm must be at most half"),
                       SceneError);
}

TEST_CASE("every physical key has an upper bound named in the error and in the key docs") {
  // key, accepted range as the message gives it
  const std::pair<const char*, const char*> keys[] = {
      {"root.radius_mm", "in (0, 100]"},         {"root.youngs_modulus_mpa", "in (0, 1e+06]"},
      {"root.initial_length_mm", "in (0, 10000]"}, {"root.element_length_mm", "in (0, 1000]"},
      {"root.density_kg_per_m3", "in (0, 1e+05]"}, {"growth.rate_per_h", "in (0, 10]"},
      {"growth.step_h", "in (0, 10]"},           {"growth.growth_zone_mm", "in (0, 1000]"},
      {"tropism.beta", "in [0, 100]"},           {"tropism.gamma", "in [0, 100]"},
      {"tropism.twist_r_tau", "in [-10, 10]"},   {"tropism.circumnutation_gain", "in [0, 100]"},
      {"tropism.circumnutation_period_h", "in (0, 10000]"}, {"plane.k_n_per_m", "in [0, 1e+06]"},
      {"plane.damping_kg_per_s", "in [0, 1000]"}, {"adhesion.k_n_per_m", "in [0, 1e+06]"},
      {"solver.damping_per_s", "in (0, 1e+09]"}, {"analysis.wave_min_amplitude_r", "in [0.001, 1000]"},
  };
  const std::string resolved = parseScene("", "scenes/t.toml").resolvedToml;
  for (const auto& kr : keys) {
    const std::string key = kr.first, range = kr.second;
    CAPTURE(key);
    const std::string e = errorOf("", {key + "=1e300"});
    CHECK(e == "--set " + key + "=1e300: " + key + " must be " + range + " (got 1e+300)");
    // the key's line in the resolved scene (what `rootsim check` prints) ends with its range
    const std::string k = key.substr(key.find('.') + 1);
    const auto at = resolved.find("\n" + k + " = ");
    REQUIRE(at != std::string::npos);
    const std::string line = resolved.substr(at + 1, resolved.find('\n', at + 1) - at - 1);
    CHECK(line.size() > range.size());
    CHECK(line.substr(line.size() - range.size()) == range);
  }
  // negative twist is a direction, not a bound
  CHECK(errorOf("", {"tropism.twist_r_tau=-10"}) == "(no error)");
  // a bound in a file names file:line
  CHECK(errorOf("[root]\nradius_mm = 1e300\n") == "scenes/t.toml:2: root.radius_mm must be in (0, 100] (got 1e+300)");
}

TEST_CASE("the element cap refuses scenes that would grow without bound naming keys and cap") {
  // 1e4 mm in 0.05 mm elements: 200000 elements at the start (it grew to GBs)
  CHECK(errorOf("", {"root.initial_length_mm=1e4"}) ==
        "--set root.initial_length_mm: root.initial_length_mm = 10000: root.initial_length_mm / "
        "root.element_length_mm = 10000 mm / 0.05 mm = 200000 elements at the start; at most 20000 elements are allowed");
  // a 1e-12 mm element (it hung): the key the scene gave is named, with its line
  CHECK(errorOf("[root]\nelement_length_mm = 1e-12\n") ==
        "scenes/t.toml:2: root.element_length_mm = 1e-12: root.initial_length_mm / root.element_length_mm = 1.1 mm / "
        "1e-12 mm = 1100000000000 elements at the start; at most 20000 elements are allowed");
  // a huge mechanics rod (it ended in std::bad_alloc)
  const std::string c = errorOf("[growth]\nenabled = false\n[root]\ninitial_length_mm = 9000\nelement_length_mm = 0.01\n");
  CHECK(c.find("scenes/t.toml:4: root.initial_length_mm = 9000: ") == 0);
  CHECK(c.find("= 900000 elements at the start; at most 20000 elements are allowed") != std::string::npos);
  // growth: the final length counts (1.1 + 1e7 * 0.05 * 0.2 * 1 mm)
  CHECK(errorOf("", {"growth.steps=10000000"}) ==
        "--set growth.steps: growth.steps = 10000000: the root grows to 100001.1 mm (root.initial_length_mm + "
        "growth.steps * growth.step_h * growth.rate_per_h * growth.growth_zone_mm) = 2000022 elements of "
        "root.element_length_mm = 0.05 mm; at most 20000 elements are allowed");
  // the shipped fig2b grows to about 31 mm = 622 elements: far inside the cap
  CHECK(errorOf("[growth]\nsteps = 3000\n") == "(no error)");
  // just inside and just outside the cap
  CHECK(errorOf("[root]\ninitial_length_mm = 1000\nelement_length_mm = 0.05\n[growth]\nenabled = false\n") ==
        "(no error)");
  CHECK(errorOf("[root]\ninitial_length_mm = 1000\nelement_length_mm = 0.0499\n[growth]\nenabled = false\n") !=
        "(no error)");
}

// Relations between keys (buildParams) that the values chosen must satisfy: the tip loads and a free base
// apply to mechanics-only scenes, so those keys are varied from growth.enabled = false (in both the
// reference and the changed scene); friction.mu_kinetic may not exceed friction.mu_static, whose default
// is 0, so it is varied from mu_static = 0.6 (in both). Every other key's first in-range candidate (twice
// the default, or 0.3 where the default is 0) satisfies the relations; a candidate that breaks one is
// reported (MESSAGE) and the next one tried.
TEST_CASE("every scene key of the schema: a non-default value changes the model at that key alone and reads back bitwise through the scene text") {
  const std::vector<sd::KeySpec>& keys = sd::schema();
  REQUIRE(keys.size() > 50);
  sd::Values defaults;
  for (const sd::KeySpec& k : keys) defaults[k.full()] = sd::defaultValue(k);
  // the defaults are defaultModel()'s values
  CHECK(differingKeys(sd::valuesOf({defaultModel(), OutputParams{}}, "default"), defaults) == "");
  int checked = 0;
  for (const sd::KeySpec& k : keys) {
    const std::string key = k.full();
    CAPTURE(key);
    sd::Values base = defaults;
    if (key == "load.tip_force_n" || key == "load.tip_torque_nm" || key == "load.base") base["growth.enabled"].b = false;
    if (key == "friction.mu_kinetic") base["friction.mu_static"].num = 0.6;  // the default mu_static is 0
    const sd::SceneParams ref = sd::buildParams(base, "t");
    const sd::Values refValues = sd::valuesOf(ref, "model");
    REQUIRE(differingKeys(refValues, base) == "");
    bool tried = false;
    for (const sd::Value& v : otherValues(k)) {
      sd::Values changed = base;
      changed[key] = v;
      sd::SceneParams m;
      try {
        m = sd::buildParams(changed, "t");
      } catch (const SceneError& e) {
        MESSAGE(key << " = " << shown(v) << " breaks a relation: " << std::string(e.what()) << "; trying the next value");
        continue;
      }
      tried = true;
      // set then get: the value given, at that key only (a key whose setter or getter misses its field,
      // or touches another's, fails here)
      const sd::Values got = sd::valuesOf(m, "model");
      CHECK(differingKeys(got, changed) == "");
      CHECK(differingKeys(got, refValues) == key + " (" + shown(got.at(key)) + " vs " + shown(refValues.at(key)) + ") ");
      // model -> scene text -> model: every key's value bitwise
      const Scene typed = sceneOf(m.model, m.output);
      CHECK(typed.resolvedToml == sd::resolvedToml(got, "t"));
      const Scene loaded = parseScene(typed.resolvedToml, "runs/t.toml");
      CHECK(differingKeys(sd::valuesOf({loaded.model, loaded.output}, "loaded"), got) == "");
      ++checked;
      break;
    }
    CHECK_MESSAGE(tried, "no in-range value of " << key << " other than its default satisfies the relations");
  }
  CHECK(checked == static_cast<int>(keys.size()));
}
