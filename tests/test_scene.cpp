// scene files: every bad input is an error naming the file, line and key (src/io/scene.cpp)
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <filesystem>
#include <fstream>

#include "rootsim/scene.hpp"
#include "scene_support.hpp"
#include "test_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::errorOf;
using rootsim::test::oneLine;
using rootsim::test::sweepError;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("scene", name); }
}  // namespace

TEST_CASE("defaults are the paper's values (docs/model.md, Experiment and parameters)") {
  const Scene s = parseScene("", "scenes/empty.toml");
  ROOTSIM_CHECK_CLOSE(s.model.rod.radius, 1e-4, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.initial.length, 1.1e-3, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.rod.youngs, 50e6, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.growth.rate, 0.2 / 3600, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.growth.zoneLength, 1e-3, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.tropism.beta, 0.1, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.env.plane.k, 1000, kRoundoff);  // deliberate deviation, see scene_schema.cpp
  ROOTSIM_CHECK_CLOSE(s.model.env.plane.c, 0.01, kRoundoff);
  ROOTSIM_CHECK_CLOSE(s.model.env.kAdhesion, 1000, kRoundoff);
  CHECK(s.model.name == "empty");
}

TEST_CASE("the resolved scene round-trips to the same model") {
  const Scene a = parseScene("[tropism]\nbeta = 0.3\nsensing = \"apical\"\n[plane]\nalpha_deg = 12.5\n", "a.toml");
  const Scene b = parseScene(a.resolvedToml, "a.toml");
  CHECK(b.resolvedToml == a.resolvedToml);
  CHECK(b.model.tropism.sensing == Sensing::Apical);
  ROOTSIM_CHECK_CLOSE(b.model.env.plane.alpha, 12.5 * std::numbers::pi / 180, kRoundoff);
}

TEST_CASE("scene errors name file, line and key") {
  CHECK(errorOf("[tropism]\nbeta = 0.1\nbta = 0.2\n").find("scenes/t.toml:3: unknown key tropism.bta (did you mean tropism.beta?)") != std::string::npos);
  CHECK(errorOf("[tropsim]\nbeta = 0.1\n").find("scenes/t.toml:1: unknown section [tropsim] (did you mean [tropism]?)") != std::string::npos);
  CHECK(errorOf("beta = 0.2\n").find("did you mean tropism.beta?") != std::string::npos);
  CHECK(errorOf("[root]\nradius_mm = \"thin\"\n").find("scenes/t.toml:2: root.radius_mm must be a number (got the string \"thin\")") != std::string::npos);
  CHECK(errorOf("[root]\nradius_mm = -0.1\n").find("scenes/t.toml:2: root.radius_mm must be in (0, 100] (got -0.1)") != std::string::npos);
  CHECK(errorOf("[plane]\n\nalpha_deg = nan\n").find("scenes/t.toml:3: plane.alpha_deg must be finite") != std::string::npos);
  CHECK(errorOf("[plane]\nalpha_deg = 95\n").find("plane.alpha_deg must be in [0, 90] (got 95)") != std::string::npos);
  CHECK(errorOf("[growth]\nsteps = 1.5\n").find("scenes/t.toml:2: growth.steps must be an integer (got the number 1.5)") != std::string::npos);
  CHECK(errorOf("[tropism]\nsensing = \"global\"\n").find("tropism.sensing must be one of \"local\", \"apical\" (got \"global\")") != std::string::npos);
  CHECK(errorOf("[load]\ntip_force_n = [1, 2]\n").find("load.tip_force_n must be an array of 3 numbers") != std::string::npos);
  CHECK(errorOf("[load]\ntip_force_n = [1, 2, inf]\n").find("load.tip_force_n must have finite components") != std::string::npos);
  CHECK(errorOf("[root\nradius_mm = 1\n").find("scenes/t.toml:1: TOML syntax error") != std::string::npos);
  CHECK(errorOf("[root]\nelement_length_mm = 0.2\n").find("scenes/t.toml:2: root.element_length_mm must give at least 10 elements in the growth zone") != std::string::npos);
  CHECK(errorOf("[load]\ntip_force_n = [0, 0, 1e-5]\n").find("load.tip_force_n and load.tip_torque_nm apply to mechanics-only scenes") != std::string::npos);
}

TEST_CASE("--set overrides, and their errors name the flag") {
  const Scene s = parseScene("", "t.toml", {"tropism.beta=0.5", "tropism.sensing=apical", "load.tip_force_n=[0,0,1]", "growth.enabled=false"});
  ROOTSIM_CHECK_CLOSE(s.model.tropism.beta, 0.5, kRoundoff);
  CHECK(s.model.tropism.sensing == Sensing::Apical);
  ROOTSIM_CHECK_CLOSE(s.model.env.tipForce.z(), 1.0, kRoundoff);
  CHECK(errorOf("", {"tropism.bta=0.5"}).find("--set tropism.bta=0.5: unknown key tropism.bta (did you mean tropism.beta?)") != std::string::npos);
  CHECK(errorOf("", {"tropism.beta=abc"}).find("--set tropism.beta=abc: tropism.beta must be a number (got \"abc\")") != std::string::npos);
  CHECK(errorOf("", {"tropism.beta=-1"}).find("--set tropism.beta=-1: tropism.beta must be in [0, 100] (got -1)") != std::string::npos);
  CHECK(errorOf("", {"beta=1"}).find("expected section.key=value") != std::string::npos);
}

TEST_CASE("missing and unreadable files") {
  try {
    loadScene("/nonexistent/scene.toml");
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find("/nonexistent/scene.toml: no such scene file") != std::string::npos);
  }
}

// --- contact keys (docs/model.md, Contact and friction): [self_contact], [friction], [[obstacle]] ---

TEST_CASE("contact keys: defaults, and obstacles that round-trip through the resolved scene") {
  const Scene d = parseScene("", "scenes/empty.toml");
  CHECK(d.model.env.selfContact.enabled);
  CHECK(!d.model.env.friction.enabled);
  CHECK(d.model.env.obstacles.empty());
  const std::string text =
      "[friction]\nenabled = true\nmu_static = 0.4\nmu_kinetic = 0.3\naxial_ratio = 0.5\n"
      "[[obstacle]]\nshape = \"peg\"\ncenter_mm = [0.1, 3]\nradius_mm = 0.5\n"
      "[[obstacle]]\nshape = \"wall\"\nfrom_mm = [-1.5, 2.5]\nto_mm = [1, 3.2]\nthickness_mm = 0.2\n";
  const Scene a = parseScene(text, "o.toml");
  REQUIRE(a.model.env.obstacles.size() == 2);
  const Obstacle& peg = a.model.env.obstacles[0];
  CHECK(peg.shape == Obstacle::Shape::Peg);
  ROOTSIM_CHECK_CLOSE(peg.from.x(), 1e-4, kRoundoff);
  ROOTSIM_CHECK_CLOSE(peg.from.y(), 3e-3, kRoundoff);
  CHECK(peg.to == peg.from);
  ROOTSIM_CHECK_CLOSE(peg.radius, 5e-4, kRoundoff);
  const Obstacle& wall = a.model.env.obstacles[1];
  CHECK(wall.shape == Obstacle::Shape::Wall);
  ROOTSIM_CHECK_CLOSE(wall.to.y(), 3.2e-3, kRoundoff);
  ROOTSIM_CHECK_CLOSE(wall.radius, 1e-4, kRoundoff);  // half the thickness
  ROOTSIM_CHECK_CLOSE(a.model.env.friction.axialRatio, 0.5, kRoundoff);
  const Scene b = parseScene(a.resolvedToml, "o.toml");
  CHECK(b.resolvedToml == a.resolvedToml);
  CHECK(b.model.env.obstacles.size() == 2);
}

TEST_CASE("contact keys: bad obstacles and friction are errors naming file:line and key") {
  auto peg = [](const std::string& body) { return "[[obstacle]]\nshape = \"peg\"\n" + body; };
  CHECK(errorOf(peg("center_mm = [0.05, 0.5]\nradius_mm = 0.2\n"))
            .find("scenes/t.toml:3: obstacle[1].center_mm overlaps the initial root by 0.25 mm") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [0, 5]\nradius_mm = -0.5\n"))
            .find("scenes/t.toml:4: obstacle[1].radius_mm must be > 0 (got -0.5)") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [0, 5]\nradius_mm = nan\n"))
            .find("scenes/t.toml:4: obstacle[1].radius_mm must be finite") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [inf, 5]\nradius_mm = 0.5\n"))
            .find("scenes/t.toml:3: obstacle[1].center_mm must be finite") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [0, 5, 1]\nradius_mm = 0.5\n"))
            .find("scenes/t.toml:3: obstacle[1].center_mm must be an array of 2 numbers") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [0, 5]\nradius_mn = 0.5\n"))
            .find("scenes/t.toml:4: unknown key obstacle[1].radius_mn (did you mean radius_mm?)") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [0, 5]\n")).find("obstacle[1].radius_mm is missing") != std::string::npos);
  CHECK(errorOf(peg("center_mm = [0, 5]\nradius_mm = 0.5\nfrom_mm = [0, 1]\n"))
            .find("scenes/t.toml:5: obstacle[1].from_mm does not apply to a peg") != std::string::npos);
  CHECK(errorOf("[[obstacle]]\nshape = \"cone\"\n").find("scenes/t.toml:2: obstacle[1].shape must be one of \"peg\", \"wall\"") !=
        std::string::npos);
  CHECK(errorOf("[[obstacle]]\nshape = \"peg\"\ncenter_mm = [0, 5]\nradius_mm = 0.5\n"
                "[[obstacle]]\nshape = \"wall\"\nfrom_mm = [-1, 0.5]\nto_mm = [1, 0.5]\nthickness_mm = 0.2\n")
            .find("scenes/t.toml:7: obstacle[2].from_mm overlaps the initial root") != std::string::npos);
  CHECK(errorOf("[[obstacle]]\nshape = \"wall\"\nfrom_mm = [1, 5]\nto_mm = [1, 5]\nthickness_mm = 0.2\n")
            .find("scenes/t.toml:4: obstacle[1].to_mm must differ from from_mm") != std::string::npos);
  CHECK(errorOf("obstacle = 3\n").find("scenes/t.toml:1: obstacle must be an array of tables") != std::string::npos);
  CHECK(errorOf("[friction]\nmu_static = 0.2\nmu_kinetic = 0.3\n")
            .find("scenes/t.toml:3: friction.mu_kinetic must be at most friction.mu_static") != std::string::npos);
  CHECK(errorOf("[friction]\nmu_static = -0.2\n").find("scenes/t.toml:2: friction.mu_static must be in [0, 100] (got -0.2)") !=
        std::string::npos);
  CHECK(errorOf("[self_contact]\nk_n_per_m = 0\n").find("scenes/t.toml:2: self_contact.k_n_per_m must be in (0, 1e+06]") !=
        std::string::npos);
}

TEST_CASE("a string value or key with control characters is escaped in the message") {
  const std::string a = errorOf("[tropism]\nsensing = \"api\\ncal\"\n");
  CHECK(oneLine(a));
  CHECK(a.find("(got \"api\\ncal\")") != std::string::npos);
  const std::string b = errorOf("[tropism]\nbeta = \"x\\ty\"\n");
  CHECK(oneLine(b));
  CHECK(b.find("the string \"x\\ty\"") != std::string::npos);
  const std::string c = errorOf("[tropism]\n\"be\\nta\" = 1\n");
  CHECK(oneLine(c));
  CHECK(c.find("unknown key tropism.be\\nta") != std::string::npos);
}

TEST_CASE("integers beyond 2^53 and numbers that underflow are refused with the key's range") {
  // 9007199254740993 became ...992 as a double
  CHECK(errorOf("", {"solver.seed=9007199254740993"}) ==
        "--set solver.seed=9007199254740993: solver.seed must be in [0, 9007199254740992] (got 9007199254740993, more "
        "than a double holds exactly)");
  CHECK(errorOf("[solver]\nseed = 9223372036854775807\n").find("scenes/t.toml:2: solver.seed must be in [0, 9007199254740992]") == 0);
  CHECK(errorOf("", {"solver.seed=9007199254740992"}) == "(no error)");
  // 1e-400 became 0 (while 1e400 is refused)
  CHECK(errorOf("", {"tropism.beta=1e-400"}) ==
        "--set tropism.beta=1e-400: tropism.beta must be in [0, 100] (got 1e-400, which a double holds only as 0.0: "
        "non-zero magnitudes below 2.2250738585072014e-308 underflow)");
  CHECK(errorOf("[tropism]\nbeta = 4e-320\n").find("scenes/t.toml:2: tropism.beta must be in [0, 100] (got 4e-320, which a double holds only as 4e-320") == 0);
  CHECK(errorOf("[load]\ntip_force_n = [0, 0, -1.5e-999]\n").find("scenes/t.toml:2: load.tip_force_n must be an array of 3 numbers: element 3 of 3 (got -1.5e-999") == 0);
  // zeros as written are zeros
  CHECK(errorOf("[tropism]\nbeta = 0.0e-400\ngamma = 0e5\n") == "(no error)");
  CHECK(errorOf("", {"tropism.beta=-0.0"}) == "(no error)");
  // an analysis threshold of 0 called rounding noise a wave (amplitude 1.4e-26 mm) or a skew
  CHECK(errorOf("", {"analysis.wave_min_amplitude_r=0"}) ==
        "--set analysis.wave_min_amplitude_r=0: analysis.wave_min_amplitude_r must be in [0.001, 1000] (got 0)");
  CHECK(errorOf("", {"analysis.skew_threshold_deg=0"}) ==
        "--set analysis.skew_threshold_deg=0: analysis.skew_threshold_deg must be in [0.001, 90] (got 0)");
  CHECK(errorOf("", {"analysis.wave_min_amplitude_r=0.001", "analysis.skew_threshold_deg=0.001"}) == "(no error)");
}

TEST_CASE("an array element of the wrong type is named and a sweep point's error names its grid line") {
  CHECK(errorOf("[load]\ntip_force_n = [0, 0, \"a\"]\n") ==
        "scenes/t.toml:2: load.tip_force_n must be an array of 3 numbers: element 3 of 3 must be a number (got the "
        "string \"a\")");
  CHECK(errorOf("", {"load.tip_force_n=[true,0,0]"}) ==
        "--set load.tip_force_n=[true,0,0]: load.tip_force_n must be an array of 3 numbers: element 1 of 3 must be a "
        "number (got true)");
  CHECK(errorOf("[load]\ntip_force_n = [0, 0]\n") ==
        "scenes/t.toml:2: load.tip_force_n must be an array of 3 numbers (got an array of 2)");
  const fs::path d = scratch("pointline");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/fig2b_waving.toml\"\n"
                                << "[grid]\n\"tropism.beta\" = [0.1, 0.2]\n\n\"plane.alpha_deg\" = [30, 95]\n"
                                << "[set]\n\"growth.steps\" = 10\n";
  }
  CHECK(sweepError(d / "s.toml") == (d / "s.toml").string() +
                                        ":6: point 2: --set plane.alpha_deg=95: plane.alpha_deg must be in [0, 90] (got 95)");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/fig2b_waving.toml\"\n"
                                << "[grid]\n\"tropism.beta\" = [0.1, 0.2]\n[set]\n\"root.radius_mm\" = -1\n";
  }
  CHECK(sweepError(d / "s.toml").find((d / "s.toml").string() + ":6: point 0: --set root.radius_mm=-1: ") == 0);
  fs::remove_all(d);
}
