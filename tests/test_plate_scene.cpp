// plate scenes and plate runs (src/io/plate_scene.cpp, src/io/run_plate.cpp; docs/plate.md): the tables'
// checks name file:line:key, a seedling's override changes that seedling only, [population] draws
// repeat from the seed and are written into the resolved scene, a plate run's folders
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rootsim/outputs.hpp"
#include "rootsim/rsml.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/units.hpp"
#include "scene_support.hpp"
#include "test_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using rootsim::test::errorOf;
using rootsim::test::slurp;

namespace fs = std::filesystem;

namespace {

// a short plate: the paper's waving root, 120 growth steps
const std::string kHead = R"([root]
radius_mm = 0.1
initial_length_mm = 1.1
element_length_mm = 0.05
[growth]
steps = 120
[tropism]
beta = 0.2
[plane]
alpha_deg = 40
[output]
every_steps = 20
vtk = false
[plate]
width_mm = 60
length_mm = 40
)";

std::string seedling(const std::string& name, double x, double y, const std::string& extra = "") {
  std::ostringstream os;
  os << "\n[[seedling]]\nname = \"" << name << "\"\nposition_mm = [" << x << ", " << y << "]\n" << extra;
  return os.str();
}


}  // namespace

TEST_CASE("plate scenes: bad seedlings are refused naming file:line and the key") {
  // two seedlings closer than their radii's sum (0.2 mm): line 20 is the second's position_mm
  const std::string close = kHead + seedling("a", 20, 5) + seedling("b", 20.15, 5);
  CHECK(errorOf(close).find("scenes/t.toml:24: seedling[2].position_mm [20.15, 5.0]: b's initial root comes within") == 0);
  // off the plate (60 x 40 mm): its initial root must lie at least R inside every edge
  CHECK(errorOf(kHead + seedling("a", 59.95, 5)).find("scenes/t.toml:20: seedling[1].position_mm [59.95, 5.0] puts a's "
                                                      "initial root off the plate") == 0);
  CHECK(errorOf(kHead + seedling("a", 20, 39.5)).find("off the plate") != std::string::npos);
  // an unknown key in an override, with a suggestion
  const std::string typo = kHead + seedling("a", 20, 5, "[seedling.set]\n\"tropism.betta\" = 0.3\n");
  CHECK(errorOf(typo) == "scenes/t.toml:22: unknown key seedling[1].set.tropism.betta (did you mean tropism.beta?)");
  // a key that is the plate's, not a seedling's
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set = { \"plane.alpha_deg\" = 30 }\n")).find(
            "seedling[1].set.plane.alpha_deg is the plate's") != std::string::npos);
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set = { \"growth.steps\" = 30 }\n")).find(
            "every root grows in the same steps") != std::string::npos);
  // a value out of the key's range, named with the seedling
  CHECK(errorOf(kHead + seedling("a", 20, 5, "[seedling.set.tropism]\nbeta = -1\n")).find(
            "scenes/t.toml:22: seedling[1].set.tropism.beta must be") == 0);
  // unknown seedling key, missing name or position, a name taken twice, a name that is no folder
  CHECK(errorOf(kHead + seedling("a", 20, 5, "angle = 3\n")) ==
        "scenes/t.toml:21: unknown key seedling[1].angle (seedling keys: name, genotype, position_mm, angle_deg, set_point_deg, "
        "set_point_final_deg, set_point_drift, set_point_drift_h, set)");
  CHECK(errorOf(kHead + "\n[[seedling]]\nposition_mm = [20, 5]\n").find("seedling[1].name is missing") != std::string::npos);
  CHECK(errorOf(kHead + "\n[[seedling]]\nname = \"a\"\n").find("seedling[1].position_mm is missing") != std::string::npos);
  CHECK(errorOf(kHead + seedling("a", 20, 5) + seedling("a", 40, 5)).find("\"a\" is taken by seedling[1]") != std::string::npos);
  CHECK(errorOf(kHead + seedling("../x", 20, 5)).find("seedling[1].name must be 1-64 letters") != std::string::npos);
  // [plate] and [population] need seedlings; their own keys are checked
  CHECK(errorOf("[plate]\nwidth_mm = 50\n").find("scenes/t.toml:1: [plate] without any [[seedling]]") == 0);
  CHECK(errorOf(kHead + "depth_mm = 3\n" + seedling("a", 20, 5)).find("unknown key plate.depth_mm") != std::string::npos);
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[population.spread]\n\"tropism.beta\" = { sd = 0.1 }\n")
            .find("population.spread.tropism.beta must be { normal_sd = S } or { uniform_half_width = W }") != std::string::npos);
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[population.spread]\n\"tropism.sensing\" = { normal_sd = 0.1 }\n")
            .find("only number keys vary") != std::string::npos);
}

TEST_CASE("plate scenes: a seedling's override changes that seedling only, and the resolved scene holds it") {
  const std::string text = kHead + seedling("wt", 15, 5) + seedling("mutant", 35, 5, "[seedling.set]\n\"tropism.beta\" = 0.3\n");
  const Scene sc = parseScene(text, "scenes/plate.toml");
  REQUIRE(sc.plate.seedlings.size() == 2);
  const Model& wt = sc.plate.seedlings[0].model;
  const Model& mu = sc.plate.seedlings[1].model;
  CHECK(wt.tropism.beta == 0.2);
  CHECK(mu.tropism.beta == 0.3);
  CHECK(sc.plate.seedlings[0].overrides.empty());
  CHECK(sc.plate.seedlings[1].overrides == std::vector<std::string>{"tropism.beta=0.3"});
  // everything else is the plate's: the models' resolved keys differ in that one key
  const std::vector<SceneValue> a = sceneValues(wt, sc.output), b = sceneValues(mu, sc.output);
  REQUIRE(a.size() == b.size());
  int differ = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].text != b[i].text) {
      ++differ;
      CHECK(a[i].key == "tropism.beta");
    }
  CHECK(differ == 1);
  // the resolved scene parses to the same plate
  const Scene again = parseScene(sc.resolvedToml, "scenes/plate.toml");
  CHECK(again.resolvedToml == sc.resolvedToml);
  CHECK(again.plate.seedlings[1].model.tropism.beta == 0.3);
  // a scene without seedlings is a single root, as before
  const Scene single = parseScene(kHead.substr(0, kHead.find("[plate]")), "scenes/one.toml");
  CHECK_FALSE(single.isPlate());
  CHECK(single.resolvedToml.find("[plate]") == std::string::npos);
}

TEST_CASE("plate scenes: population draws repeat from the seed and are written into the resolved scene") {
  std::string text = kHead + "\n[population]\nseed = 11\n[population.spread]\n\"tropism.beta\" = { normal_sd = 0.03 }\n"
                             "\"tropism.twist_r_tau\" = { uniform_half_width = 0.1 }\nangle_deg = { normal_sd = 4 }\n";
  for (int k = 0; k < 5; ++k) text += seedling("s" + std::to_string(k), 8 + 10 * k, 5);
  const Scene a = parseScene(text, "scenes/p.toml"), b = parseScene(text, "scenes/p.toml");
  CHECK(a.resolvedToml == b.resolvedToml);
  double lo = 1e9, hi = -1e9;
  for (int k = 0; k < 5; ++k) {
    const Model& m = a.plate.seedlings[static_cast<size_t>(k)].model;
    CHECK(m.tropism.beta == b.plate.seedlings[static_cast<size_t>(k)].model.tropism.beta);
    CHECK(std::abs(m.tropism.rTau) <= 0.1);
    lo = std::min(lo, m.tropism.beta);
    hi = std::max(hi, m.tropism.beta);
  }
  CHECK(hi > lo);  // five draws, not one value
  // another seed, another plate
  std::string other = text;
  other.replace(other.find("seed = 11"), 9, "seed = 12");
  CHECK(parseScene(other, "scenes/p.toml").plate.seedlings[0].model.tropism.beta != a.plate.seedlings[0].model.tropism.beta);
  // the drawn values are in the resolved scene: it loads to the same models without drawing again
  const Scene resolved = parseScene(a.resolvedToml, "scenes/p.toml");
  for (int k = 0; k < 5; ++k) {
    const auto u = static_cast<size_t>(k);
    CHECK(resolved.plate.seedlings[u].model.tropism.beta == a.plate.seedlings[u].model.tropism.beta);
    CHECK(resolved.plate.seedlings[u].model.tropism.rTau == a.plate.seedlings[u].model.tropism.rTau);
    CHECK(resolved.plate.seedlings[u].model.initial.angle == a.plate.seedlings[u].model.initial.angle);
  }
  CHECK(a.resolvedToml.find("[population]") == std::string::npos);  // the draws are made: the values stand
}

TEST_CASE("plate runs: a folder per root, each a run directory of that root alone, and plate.csv names overrides") {
  const fs::path dir = test::scratchDir("plate", "run");
  const std::string text = kHead + seedling("wt", 15, 5) + seedling("mutant", 35, 5, "set = { \"tropism.beta\" = 0.3 }\n");
  const Scene sc = parseScene(text, "scenes/plate.toml");
  runSceneToDir(sc, (dir / "run").string(), RunDirOptions{}, nullptr);
  for (const char* f : {"scene.toml", "summary.json", "plate.csv", "plate_timeseries.csv", ".rootsim-run"})
    CHECK(fs::is_regular_file(dir / "run" / f));
  // each root's folder: its own scene (the plate with that seedling alone) and the files of a run
  for (const char* name : {"wt", "mutant"}) {
    const fs::path r = dir / "run" / "roots" / name;
    for (const char* f : {"scene.toml", "summary.json", "result.csv", "timeseries.csv", "shape.csv", "trajectory.bin", ".rootsim-run"})
      CHECK(fs::is_regular_file(r / f));
    CHECK(whyNotWhole(r).empty());
    const Scene own = loadScene((r / "scene.toml").string());
    CHECK(own.plate.seedlings.size() == 1);
    CHECK(own.model.tropism.beta == (std::string(name) == "wt" ? 0.2 : 0.3));
  }
  // the wild type's shape is the single root's run (roots apart): same bytes of shape.csv
  Scene single = parseScene(kHead.substr(0, kHead.find("[plate]")), "scenes/plate.toml");
  Simulation sim(single.model);
  for (int k = 0; k < single.model.growth.steps; ++k) sim.growthStep();
  CHECK(slurp(dir / "run" / "roots" / "wt" / "shape.csv") == shapeCsv(single.model, sim.state(), sim.strains()));
  const std::string table = slurp(dir / "run" / "plate.csv");
  CHECK(table.rfind("root,genotype,parent,order,emerged_h,position_lateral_mm,position_downhill_mm,angle_deg,set_point_deg,overrides,scene,status,", 0) == 0);
  CHECK(table.find("\nmutant,,,0,0.0,35.0,5.0,0.0,0.0,tropism.beta=0.3,") != std::string::npos);
  // the same scene again: the same bytes in every root's files (same scene and seed, same bytes)
  runSceneToDir(sc, (dir / "again").string(), RunDirOptions{}, nullptr);
  for (const char* f : {"roots/mutant/shape.csv", "roots/mutant/timeseries.csv", "plate.csv", "plate_timeseries.csv"})
    CHECK(slurp(dir / "run" / f) == slurp(dir / "again" / f));
  // a plate's run directory is rootsim's: --force replaces it
  RunDirOptions force;
  force.force = true;
  CHECK_NOTHROW(runSceneToDir(sc, (dir / "run").string(), force, nullptr));
}

TEST_CASE("plate scenes: [laterals] keys are checked naming file:line and the key") {
  CHECK(errorOf(kHead + "\n[laterals]\nspacing_mm = 0\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:19: laterals.spacing_mm must be in (0, 1000] (got 0)");
  CHECK(errorOf(kHead + "\n[laterals]\nspacing_mm = -2\n" + seedling("a", 20, 5)).find("laterals.spacing_mm must be in (0, 1000]") !=
        std::string::npos);
  CHECK(errorOf(kHead + "\n[laterals]\nset_point_dg = 30\n" + seedling("a", 20, 5)).find(
            "scenes/t.toml:19: unknown key laterals.set_point_dg (did you mean laterals.set_point_deg?)") == 0);
  CHECK(errorOf(kHead + "\n[laterals]\nsides = \"left\"\n" + seedling("a", 20, 5)).find("laterals.sides must be one of") !=
        std::string::npos);
  CHECK(errorOf(kHead + "\n[laterals]\nmax_order = 0\n" + seedling("a", 20, 5)).find("laterals.max_order must be in [1, 4]") !=
        std::string::npos);
  CHECK(errorOf(kHead + "\n[laterals]\ninsertion_from = \"gravity\"\n" + seedling("a", 20, 5))
            .find("scenes/t.toml:19: laterals.insertion_from must be one of") == 0);
  CHECK_FALSE(parseScene(kHead + "\n[laterals]\ninsertion_from = \"downhill\"\n" + seedling("a", 20, 5), "scenes/d.toml")
                  .plate.params.laterals.fromParent);
  CHECK(errorOf(kHead + "\n[laterals]\ninitial_length_mm = 0.05\n" + seedling("a", 20, 5)).find("shorter than two elements") !=
        std::string::npos);
  CHECK(errorOf("[laterals]\nenabled = true\n").find("[laterals] without any [[seedling]]") != std::string::npos);
  // a resolved scene with laterals round-trips
  const Scene sc = parseScene(kHead + "\n[laterals]\nenabled = true\nset_point_deg = 45\n" + seedling("a", 20, 5), "scenes/l.toml");
  CHECK(sc.plate.params.laterals.enabled);
  CHECK(parseScene(sc.resolvedToml, "scenes/l.toml").resolvedToml == sc.resolvedToml);
}

TEST_CASE("plate scenes: the set-point drift keys, their defaults and their checks") {
  const std::string lat = "\n[laterals]\nenabled = true\n";
  // a final angle left out is the set-point angle, wherever that is set: no drift
  const Scene plain = parseScene(kHead + lat + "set_point_deg = 45\n" + seedling("a", 20, 5) +
                                     seedling("b", 40, 5, "set = { \"laterals.set_point_deg\" = 70 }\nset_point_deg = 20\n"),
                                 "scenes/p.toml");
  CHECK(plain.plate.params.laterals.setPointFinal == plain.plate.params.laterals.setPoint);
  ROOTSIM_CHECK_CLOSE(plain.plate.params.laterals.setPointFinal.value(), 45 * units::deg, kRoundoff);
  const Seedling& b = plain.plate.seedlings[1];
  CHECK(b.laterals->setPointFinal == b.laterals->setPoint);
  ROOTSIM_CHECK_CLOSE(b.laterals->setPointFinal.value(), 70 * units::deg, kRoundoff);
  CHECK(b.model.tropism.setPointFinal == b.model.tropism.setPoint);
  ROOTSIM_CHECK_CLOSE(b.model.tropism.setPointFinal.value(), 20 * units::deg, kRoundoff);
  CHECK(plain.plate.seedlings[0].model.tropism.setPointFinal == 0.0);
  CHECK(parseScene(plain.resolvedToml, "scenes/p.toml").resolvedToml == plain.resolvedToml);
  // a drift given: its final angle, law and time, plate-wide, a seedling's own and a seedling's laterals'
  const Scene drift = parseScene(kHead + lat + "set_point_deg = 70\nset_point_final_deg = 30\nset_point_drift = \"linear\"\n" +
                                     "set_point_drift_h = 48\n" + seedling("a", 20, 5) +
                                     seedling("b", 40, 5, "set_point_final_deg = 10\nset_point_drift_h = 6\n"
                                                          "set = { \"laterals.set_point_drift\" = \"exponential\" }\n"),
                                 "scenes/d.toml");
  const LateralParams& lp = drift.plate.params.laterals;
  ROOTSIM_CHECK_CLOSE(lp.setPoint, 70 * units::deg, kRoundoff);
  ROOTSIM_CHECK_CLOSE(lp.setPointFinal.value(), 30 * units::deg, kRoundoff);
  CHECK(lp.setPointDrift == SetPointDrift::Linear);
  ROOTSIM_CHECK_CLOSE(lp.setPointDriftTime, 48 * units::hour, kRoundoff);
  const Seedling& db = drift.plate.seedlings[1];
  CHECK(db.laterals->setPointDrift == SetPointDrift::Exponential);
  ROOTSIM_CHECK_CLOSE(db.laterals->setPointFinal.value(), 30 * units::deg, kRoundoff);
  CHECK(db.model.tropism.setPoint == 0.0);
  ROOTSIM_CHECK_CLOSE(db.model.tropism.setPointFinal.value(), 10 * units::deg, kRoundoff);
  ROOTSIM_CHECK_CLOSE(db.model.tropism.setPointDriftTime, 6 * units::hour, kRoundoff);
  CHECK(parseScene(drift.resolvedToml, "scenes/d.toml").resolvedToml == drift.resolvedToml);
  // a drawn set-point angle carries a final angle left out along (no drift), each seedling its own draw
  const Scene drawn = parseScene(kHead + lat + seedling("a", 20, 5) + seedling("b", 40, 5) +
                                     "\n[population]\nspread = { \"laterals.set_point_deg\" = { normal_sd = 10 } }\n",
                                 "scenes/s.toml");
  for (const Seedling& sd : drawn.plate.seedlings) {
    CHECK(sd.laterals->setPoint != 60 * units::deg);
    CHECK(sd.laterals->setPointFinal == sd.laterals->setPoint);
  }
  CHECK(parseScene(drawn.resolvedToml, "scenes/s.toml").resolvedToml == drawn.resolvedToml);
  // bad values: file:line, the key, what was expected
  CHECK(errorOf(kHead + "\n[laterals]\nset_point_drift_h = -1\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:19: laterals.set_point_drift_h must be in (0, 10000] (got -1)");
  CHECK(errorOf(kHead + "\n[laterals]\nset_point_drift = \"cubic\"\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:19: laterals.set_point_drift must be one of \"linear\", \"exponential\" (got \"cubic\")");
  CHECK(errorOf(kHead + "\n[laterals]\nset_point_final_deg = 200\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:19: laterals.set_point_final_deg must be in [0, 180] (got 200)");
  CHECK(errorOf(kHead + "\n[laterals]\nset_point_finl_deg = 20\n" + seedling("a", 20, 5)).find(
            "scenes/t.toml:19: unknown key laterals.set_point_finl_deg (did you mean laterals.set_point_final_deg?)") == 0);
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set_point_drift_h = 0\n")) ==
        "scenes/t.toml:21: seedling[1].set_point_drift_h must be in (0, 10000] (got 0)");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set_point_final_deg = 180\n")) ==
        "scenes/t.toml:21: seedling[1].set_point_final_deg must be in [0, 180) (got 180)");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set_point_drift = \"log\"\n")) ==
        "scenes/t.toml:21: seedling[1].set_point_drift must be one of \"linear\", \"exponential\" (got \"log\")");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set = { \"laterals.set_point_drift_h\" = -3 }\n")).find(
            "scenes/t.toml:21: seedling[1].set.laterals.set_point_drift_h must be in (0, 10000] (got -3)") == 0);
}

TEST_CASE("plate runs: lateral roots get their folders, rows in plate.csv and plants' roots in the plate's RSML") {
  const fs::path dir = test::scratchDir("plate", "laterals");
  const std::string text = kHead +
                           "\n[laterals]\nenabled = true\nfirst_mm = 0.5\nspacing_mm = 0.5\napical_unbranched_mm = 1.0\n" +
                           seedling("wt", 15, 5) + seedling("mu", 35, 5, "set = { \"tropism.beta\" = 0.3 }\n");
  const Scene sc = parseScene(text, "scenes/plate.toml");
  runSceneToDir(sc, (dir / "run").string(), RunDirOptions{}, nullptr);
  // two sites each (the roots grow to 2.3 mm: sites at 0.5 and 1.0 mm open once the tip is 1 mm beyond)
  for (const char* name : {"wt.1", "wt.2", "mu.1", "mu.2"}) {
    const fs::path r = dir / "run" / "roots" / name;
    REQUIRE(fs::is_regular_file(r / "scene.toml"));
    CHECK(whyNotWhole(r).empty());
    const Scene own = loadScene((r / "scene.toml").string());
    REQUIRE(own.plate.seedlings.size() == 1);
    ROOTSIM_CHECK_CLOSE(own.model.rod.radius, 0.06e-3, kRoundoff);
    ROOTSIM_CHECK_CLOSE(own.model.tropism.setPoint, 60 * units::deg, kRoundoff);
  }
  CHECK_FALSE(fs::exists(dir / "run" / "roots" / "wt.3"));
  const std::string table = slurp(dir / "run" / "plate.csv");
  CHECK(table.find("\nwt.2,,wt,1,") != std::string::npos);
  // the plate's RSML: a plant per seedling, its laterals nested in it
  const test::Result ex = test::run("export " + (dir / "run").string() + " --rsml " + (dir / "plate.rsml").string() + " --quiet");
  REQUIRE(ex.code == 0);
  const rsml::Document doc = rsml::readRsml(dir / "plate.rsml");
  REQUIRE(doc.plants.size() == 2);
  REQUIRE(doc.plants[0].roots.size() == 3);
  CHECK(doc.plants[0].label == "wt");
  CHECK(doc.plants[0].roots[1].parent == 0);
  CHECK(doc.plants[0].roots[1].order == 1);
  // in plate coordinates: the mutant's base is at its place on the plate
  CHECK(doc.plants[1].roots[0].x.front() == doctest::Approx(35.0).epsilon(1e-9));
  CHECK(doc.plants[1].roots[0].y.front() == doctest::Approx(5.0).epsilon(1e-9));
}

TEST_CASE("plate runs: a command of one root given a plate names the root to pass, and fit refuses a plate's scene") {
  const fs::path dir = test::scratchDir("plate", "refuse");
  const std::string scene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/plate_collision.toml";
  REQUIRE(test::run("run " + scene + " --set growth.steps=10 --quiet --out " + (dir / "run").string()).code == 0);
  // modes of a plate's run without --root: which root is not guessed
  const test::Result modes = test::run("modes " + (dir / "run").string());
  CHECK(modes.code == 2);
  CHECK(modes.out.find("a plate's run; give --root NAME (a root of its roots/ folder) or pass roots/NAME") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "run" / "modes.csv"));
  // each root's folder, or --root, is a run of one root: the same command takes it
  CHECK(test::run("modes " + (dir / "run" / "roots" / "down").string() + " --quiet").code == 0);
  CHECK(test::run("modes " + (dir / "run").string() + " --root across --quiet").code == 0);
  const test::Result stray = test::run("modes " + (dir / "run").string() + " --root sideways");
  CHECK(stray.code == 2);
  CHECK(stray.out.find("--root sideways: " + (dir / "run").string() + " has no root folder roots/sideways") != std::string::npos);
  // a fit runs the scene of one root against one traced root
  CHECK(test::run("export " + (dir / "run" / "roots" / "down").string() + " --rsml " + (dir / "down.rsml").string()).code == 0);
  const test::Result fit = test::run("fit " + (dir / "down.rsml").string() + " --scene " + scene +
                                     " --free tropism.beta=0.1:0.3 --out " + (dir / "fit").string());
  CHECK(fit.code == 2);
  CHECK(fit.out.find("--scene " + scene + ": a plate's scene; fit takes the scene of one root") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "fit"));
}

TEST_CASE("plate scenes: laterals are checked when the plate is read - their spacing and count and their own scene") {
  // sites closer than a lateral's diameter: laterals on one side would overlap (1e-9 mm ran out of memory,
  // 0.01 mm did not finish)
  for (const char* spacing : {"1e-09", "0.01"})
    CHECK(errorOf(kHead + "\n[laterals]\nenabled = true\nspacing_mm = " + spacing + "\n" + seedling("a", 20, 5)) ==
          "scenes/t.toml:20: laterals.spacing_mm " + std::string(spacing) +
              " mm is less than a lateral's diameter, 2 * laterals.radius_mm = 0.12 mm (two laterals on one side would overlap)");
  // the roots a plate can grow, counted before it starts: 2 seedlings growing to 301 mm with a lateral every
  // 0.12 mm up to order 2
  const std::string many = errorOf(kHead + "\n[laterals]\nenabled = true\nfirst_mm = 0.5\nspacing_mm = 0.12\nmax_order = 2\n" +
                                       seedling("a", 20, 5) + seedling("b", 40, 5),
                                   {"growth.steps=30000"});
  CHECK(many.find("scenes/t.toml:18: a plate of 2 seedling(s) with laterals every 0.12 mm (laterals.spacing_mm) up to order 2 "
                  "(laterals.max_order): would make ") == 0);
  CHECK_MESSAGE(many.find("roots, more than the cap of 2000") != std::string::npos, many);
  // the same laterals at order 1 on a short run fit
  CHECK(errorOf(kHead + "\n[laterals]\nenabled = true\nfirst_mm = 0.5\nspacing_mm = 0.12\n" + seedling("a", 20, 5)) == "(no error)");
  // a lateral's own scene (roots/NAME/scene.toml, as render and export read it) fails a check the plate's
  // keys pass: 0.6 mm zones of 0.1 mm elements; refused at the start, not after the run
  const std::string coarse = errorOf(kHead + "\n[laterals]\nenabled = true\n" + seedling("a", 20, 5), {"root.element_length_mm=0.1"});
  CHECK(coarse.find("scenes/t.toml:18: [laterals] gives a's laterals a scene that render and export would refuse "
                    "(roots/a.1/scene.toml:") == 0);
  CHECK(coarse.find("root.element_length_mm must give at least 10 elements in the growth zone") != std::string::npos);
  // without laterals the same plate is fine
  CHECK(errorOf(kHead + seedling("a", 20, 5), {"root.element_length_mm=0.1"}) == "(no error)");
}

TEST_CASE("root.initial_angle_deg: a one-root scene's start direction, which a seedling's set refuses") {
  // a one-root scene sows its root at the angle, positive towards +lateral like theta
  const Scene one = parseScene("[root]\ninitial_angle_deg = 30\n", "scenes/one.toml");
  ROOTSIM_CHECK_CLOSE(one.model.initial.angle, 30 * units::deg, kRoundoff);
  CHECK(parseScene("", "scenes/one.toml").model.initial.angle == 0.0);
  CHECK(errorOf("[root]\ninitial_angle_deg = 200\n").find("root.initial_angle_deg") != std::string::npos);
  // a plate sows each seedling at its own angle_deg: a seedling's set may not give the one-root key
  const std::string set = errorOf(kHead + seedling("a", 20, 5, "set = { \"root.initial_angle_deg\" = 5 }\n"));
  CHECK_MESSAGE(set.find("root.initial_angle_deg is a one-root scene's: a seedling's direction is its angle_deg") != std::string::npos, set);
  // a seedling sown at an angle is written back as its angle_deg, and the resolved plate reads again
  const Scene plate = parseScene(kHead + seedling("a", 20, 5, "angle_deg = 7\n"), "scenes/t.toml");
  CHECK(plate.resolvedToml.find("\"root.initial_angle_deg\"") == std::string::npos);
  CHECK(plate.resolvedToml.find("angle_deg = 7.0") != std::string::npos);
  CHECK(parseScene(plate.resolvedToml, "scenes/t.toml").resolvedToml == plate.resolvedToml);
}

TEST_CASE("plate scenes: the plate's keys are the scene schema's - type, range, did you mean, file:line") {
  // [plate]: a near miss names the key it meant; a value of the wrong type or out of range names the key
  CHECK(errorOf(kHead + "widht_mm = 50\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:17: unknown key plate.widht_mm (did you mean plate.width_mm?)");
  CHECK(errorOf(kHead + "depth_mm = 3\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:17: unknown key plate.depth_mm (plate keys: width_mm, length_mm)");
  CHECK(errorOf("[plate]\nwidth_mm = \"wide\"\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:2: plate.width_mm must be a number (got the string \"wide\")");
  CHECK(errorOf("[plate]\nlength_mm = 1e4\n" + seedling("a", 20, 5)) ==
        "scenes/t.toml:2: plate.length_mm must be in (0, 1000] (got 10000)");
  // [population]: its seed is an integer >= 0; an unknown key is suggested among seed and spread
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[population]\nseed = -1\n").find("scenes/t.toml:23: population.seed must be in [0, ") == 0);
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[population]\nsed = 3\n") ==
        "scenes/t.toml:23: unknown key population.sed (did you mean population.seed?)");
  // a section name one edit away from a plate table is suggested
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[latrals]\nenabled = true\n").find("unknown section [latrals] (did you mean [laterals]?)") !=
        std::string::npos);
  // a seedling's keys: type and range from the schema; a near miss suggested
  CHECK(errorOf(kHead + seedling("a", 20, 5, "angle_deg = 200\n")) == "scenes/t.toml:21: seedling[1].angle_deg must be in [-180, 180] (got 200)");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "set_point_deg = 180\n")) == "scenes/t.toml:21: seedling[1].set_point_deg must be in [0, 180) (got 180)");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "angle_dg = 3\n")) == "scenes/t.toml:21: unknown key seedling[1].angle_dg (did you mean seedling[1].angle_deg?)");
  CHECK(errorOf(kHead + "\n[[seedling]]\nname = \"a\"\nposition_mm = [20, 5, 1]\n") ==
        "scenes/t.toml:20: seedling[1].position_mm must be an array of 2 numbers [lateral, downhill] (got an array of 3)");
  CHECK(errorOf(kHead + "\n[[seedling]]\nname = 3\nposition_mm = [20, 5]\n") == "scenes/t.toml:19: seedling[1].name must be a string (got the integer 3)");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "genotype = \"a\\\"b\"\n")).find("seedling[1].genotype must be at most 64 printable characters") !=
        std::string::npos);
  // a [seedling.set] key outside the schema: file:line, the key, and the key it resembles (laterals.* too)
  CHECK(errorOf(kHead + seedling("a", 20, 5, "[seedling.set]\n\"laterals.delay_hh\" = 3\n")) ==
        "scenes/t.toml:22: unknown key seedling[1].set.laterals.delay_hh (did you mean laterals.delay_h?)");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "[seedling.set]\n\"plate.width_mm\" = 3\n")) == "scenes/t.toml:22: unknown key seedling[1].set.plate.width_mm");
  CHECK(errorOf(kHead + seedling("a", 20, 5, "[seedling.set]\n\"laterals.seed\" = 3\n")).find(
            "scenes/t.toml:22: seedling[1].set.laterals.seed is the plate's") == 0);
  CHECK(errorOf(kHead + seedling("a", 20, 5, "[seedling.set.laterals]\nspacing_mm = -1\n")) ==
        "scenes/t.toml:22: seedling[1].set.laterals.spacing_mm must be in (0, 1000] (got -1)");
  // [population.spread]: a laterals key varies; a key outside the schema is refused with a suggestion
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[population.spread]\n\"laterals.delai_h\" = { normal_sd = 1 }\n") ==
        "scenes/t.toml:23: unknown key population.spread.laterals.delai_h (did you mean laterals.delay_h?)");
  CHECK(errorOf(kHead + seedling("a", 20, 5) + "\n[population.spread]\n\"laterals.delay_h\" = { normal_sd = -1 }\n") ==
        "scenes/t.toml:23: population.spread.laterals.delay_h.normal_sd must be > 0 (got -1)");
}

TEST_CASE("plate scenes: a [seedling.set] key outside the schema stops rootsim check and run with exit 2 and file:line:key") {
  const fs::path d = test::scratchDir("plate_scene", "set_key");
  const fs::path file = d / "plate.toml";
  std::ofstream(file) << kHead << seedling("a", 20, 5, "[seedling.set]\n\"tropism.betta\" = 0.3\n");
  for (const std::string& cmd : std::vector<std::string>{"check", "run --quiet --out " + (d / "run").string()}) {
    const test::Result r = test::run(cmd + " " + file.string());
    CHECK(r.code == 2);
    CHECK(r.out == "rootsim: error: " + file.string() + ":22: unknown key seedling[1].set.tropism.betta (did you mean tropism.beta?)\n");
  }
  CHECK_FALSE(fs::exists(d / "run"));  // nothing written
}

TEST_CASE("plate scenes: a seedling's own lateral keys and their spread over the population") {
  const std::string lat = "\n[laterals]\nenabled = true\ndelay_h = 2\n";
  // one seedling delays its laterals: its own, the other keeps the plate's; the summary names it
  const Scene sc = parseScene(kHead + lat + seedling("a", 15, 5) + seedling("b", 35, 5, "set = { \"laterals.delay_h\" = 5 }\n"), "scenes/t.toml");
  REQUIRE(sc.plate.seedlings.size() == 2);
  CHECK(sc.plate.params.laterals.delay == 2 * units::hour);
  CHECK(lateralsOf(sc.plate.seedlings[0], sc.plate.params).delay == 2 * units::hour);
  CHECK(lateralsOf(sc.plate.seedlings[1], sc.plate.params).delay == 5 * units::hour);
  CHECK(sc.plate.seedlings[0].overrides.empty());
  CHECK(sc.plate.seedlings[1].overrides == std::vector<std::string>{"laterals.delay_h=5.0"});
  // the resolved scene holds it in the seedling's set and loads to the same laterals
  CHECK(sc.resolvedToml.find("\"laterals.delay_h\" = 5.0\n") != std::string::npos);
  const Scene again = parseScene(sc.resolvedToml, "scenes/t.toml");
  CHECK(again.resolvedToml == sc.resolvedToml);
  CHECK(lateralsOf(again.plate.seedlings[1], again.plate.params).delay == 5 * units::hour);
  // a seedling's lateral keys meet the same relations as the plate's, naming the seedling
  CHECK(errorOf(kHead + lat + seedling("a", 15, 5, "set = { \"laterals.spacing_mm\" = 0.1 }\n")) ==
        "scenes/t.toml:25: laterals.spacing_mm 0.1 mm is less than a lateral's diameter, 2 * laterals.radius_mm = 0.12 mm (two "
        "laterals on one side would overlap) (in seedling[1], a)");
  // laterals' relations bind only where laterals are asked for: a plate without [laterals] has coarse elements
  const std::vector<std::string> coarse = {"root.element_length_mm=0.2", "growth.growth_zone_mm=2"};
  CHECK(errorOf(kHead + seedling("a", 15, 5), coarse) == "(no error)");
  CHECK(errorOf(kHead + seedling("a", 15, 5, "set = { \"laterals.enabled\" = true }\n"), coarse).find(
            "laterals.initial_length_mm 0.3 mm is shorter than two elements") != std::string::npos);
  // a spread of a lateral key: each seedling draws its own, repeatably, within the key's range
  std::string text = kHead + lat + "\n[population]\nseed = 5\n[population.spread]\n\"laterals.delay_h\" = { normal_sd = 3 }\n";
  for (int k = 0; k < 5; ++k) text += seedling("s" + std::to_string(k), 8 + 10 * k, 5);
  const Scene p = parseScene(text, "scenes/p.toml"), q = parseScene(text, "scenes/p.toml");
  CHECK(p.resolvedToml == q.resolvedToml);
  std::vector<double> delays;
  for (const Seedling& sd : p.plate.seedlings) {
    delays.push_back(lateralsOf(sd, p.plate.params).delay);
    CHECK(delays.back() >= 0.0);
  }
  std::sort(delays.begin(), delays.end());
  CHECK(std::unique(delays.begin(), delays.end()) == delays.end());  // five draws, five delays
  const Scene resolved = parseScene(p.resolvedToml, "scenes/p.toml");
  for (size_t k = 0; k < 5; ++k)
    CHECK(lateralsOf(resolved.plate.seedlings[k], resolved.plate.params).delay ==
          lateralsOf(p.plate.seedlings[k], p.plate.params).delay);
  // the per-site spread is a [laterals] key, a seedling's own too
  const Scene sites = parseScene(kHead + lat + "delay_spread_h = 1.5\n" + seedling("a", 15, 5), "scenes/t.toml");
  CHECK(lateralsOf(sites.plate.seedlings[0], sites.plate.params).delaySpread == 1.5 * units::hour);
  CHECK(sites.resolvedToml.find("delay_spread_h = 1.5\n") != std::string::npos);
}
