// input limits of the audit (issue 15): physically sane ranges, the element cap, sweep grids and names,
// corrupt trajectories and control characters in messages (src/io/scene_schema.cpp, sweep.cpp,
// outputs.cpp). The command-line side (exit codes, nothing written) is in test_reliability.cpp.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "rootsim/number_text.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/sweep.hpp"
#include "test_files.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
std::string errorOf(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parseScene(text, "scenes/t.toml", sets);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("limits", name); }

std::string sweepError(const fs::path& file) {
  try {
    loadSweep(file.string());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

bool oneLine(const std::string& s) { return s.find('\n') == std::string::npos && s.find('\r') == std::string::npos; }
}  // namespace

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

TEST_CASE("sweep grids are counted before they are expanded") {
  const fs::path d = scratch("grid");
  std::string axis = "[";
  for (int i = 0; i < 40; ++i) axis += (i ? ", " : "") + std::to_string(0.01 * (i + 1));
  axis += "]";
  {
    std::ofstream(d / "big.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/fig2b_waving.toml\"\n[grid]\n"
                                  << "\"tropism.beta\" = " << axis << "\n\"tropism.gamma\" = " << axis << "\n"
                                  << "\"plane.alpha_deg\" = " << axis << "\n\"growth.rate_per_h\" = " << axis << "\n";
  }
  const std::string e = sweepError(d / "big.toml");
  CHECK(e.find((d / "big.toml").string() + ":") == 0);
  CHECK(e.find(": the grid has more than 10000 points (the product of the grid arrays' lengths") != std::string::npos);
  // a key in [grid] and [set] would make every point the same
  {
    std::ofstream(d / "both.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/fig2b_waving.toml\"\n"
                                   << "[grid]\n\"tropism.beta\" = [0.1, 0.2]\n[set]\n\"tropism.beta\" = 0.3\n";
  }
  CHECK(sweepError(d / "both.toml").find(":6: set.tropism.beta is also a grid key") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("sweep run-directory names stay short and unique and deterministic") {
  const fs::path d = scratch("names");
  {
    std::ofstream(d / "long.toml")
        << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/cantilever_tip_load.toml\"\n[grid]\n"
        << "\"load.tip_force_n\" = [[0.000012345678901234567, 0.000012345678901234567, -0.000012345678901234567],"
           " [0.000012345678901234568, 0.000012345678901234567, -0.000012345678901234567]]\n"
        << "\"load.tip_torque_nm\" = [[0.000000012345678901234567, 0.000000012345678901234567, 0.000000012345678901234567]]\n"
        << "\"root.youngs_modulus_mpa\" = [12.345678901234567]\n\"root.density_kg_per_m3\" = [1234.5678901234567]\n"
        << "\"solver.force_tol\" = [0.00012345678901234567]\n";
  }
  const SweepPlan a = loadSweep((d / "long.toml").string());
  const SweepPlan b = loadSweep((d / "long.toml").string());
  REQUIRE(a.points.size() == 2);
  std::set<std::string> names;
  for (size_t i = 0; i < a.points.size(); ++i) {
    CAPTURE(a.points[i].dirName);
    CHECK(a.points[i].dirName.size() <= 200);
    CHECK(a.points[i].dirName.rfind("run_000" + std::to_string(i) + "_tip_force_n=", 0) == 0);
    CHECK(a.points[i].dirName.find("_h") != std::string::npos);
    CHECK(a.points[i].dirName == b.points[i].dirName);
    names.insert(a.points[i].dirName);
  }
  CHECK(names.size() == 2);
  // short names are unchanged
  const SweepPlan s = loadSweep(std::string(ROOTSIM_SOURCE_DIR) + "/sweeps/fig3a_scaling.toml");
  CHECK(s.points[0].dirName == "run_0000_alpha_deg=20_beta=0.05");
  fs::remove_all(d);
}

TEST_CASE("sweep keys with control characters are escaped in messages") {
  const fs::path d = scratch("ctl");
  const std::string scene = std::string("[sweep]\nscene = \"") + ROOTSIM_SOURCE_DIR + "/scenes/fig2b_waving.toml\"\n";
  const std::pair<std::string, std::string> cases[] = {
      {scene + "[grid]\n\"tropism.be\\nta\" = [0.1]\n", "tropism.be\\nta"},
      {scene + "[set]\n\"tropism.be\\tta\" = 0.1\n", "tropism.be\\tta"},
      {scene + "[\"gr\\nid\"]\nx = 1\n", "[gr\\nid]"},
      {scene + "\"sc\\u0001ene\" = 1\n", "sweep.sc\\x01ene"},
      {scene + "[grid]\n\"tropism.be\\nta\" = 3\n", "grid.tropism.be\\nta must be a non-empty array"},
  };
  for (const auto& [text, shown] : cases) {
    { std::ofstream(d / "s.toml") << text; }
    const std::string e = sweepError(d / "s.toml");
    CAPTURE(e);
    CHECK(oneLine(e));
    CHECK(e.find(shown) != std::string::npos);
  }
  fs::remove_all(d);
}

TEST_CASE("a trajectory with NaN or inf or a malformed cell is refused naming file and line") {
  const fs::path d = scratch("traj");
  const std::string head = "frame,step,time_h,node,x_mm,y_mm,z_mm,d1x,d1y,d1z,d3x,d3y,d3z,radius_mm\n";
  const std::string good = "0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n";
  const std::pair<std::string, std::string> cases[] = {
      {"0,0,0,0,nan,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":2: x_mm: not a finite number (got nan)"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-inf,-0.3,,,,,,,\n", ":3: y_mm: not a finite number (got -inf)"},
      {good + "1,5,1e999,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n", ":4: time_h: expected a number (got \"1e999\")"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0x,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":3: frame: expected an integer (got \"0x\")"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":2: radius_mm: must be > 0 (got 0)"},
      {"0,0,0,0,0,0,0.1,,,,,,,\n", ":2: frame 0 has one node"},
  };
  for (const auto& [rows, expected] : cases) {
    { std::ofstream(d / "trajectory.csv") << head << rows; }
    std::string e = "(no error)";
    try {
      readTrajectory(d / "trajectory.csv");
    } catch (const SceneError& x) {
      e = x.what();
    }
    CHECK(e.find((d / "trajectory.csv").string() + expected) == 0);
  }
  { std::ofstream(d / "trajectory.csv") << head << good; }
  CHECK(readTrajectory(d / "trajectory.csv").size() == 1);
  fs::remove_all(d);
}

TEST_CASE("non-ASCII text is accepted in comments only (toml++ 3.3 has undefined behaviour on some of it)") {
  // comments may say 40 degrees with the sign, or alpha in Greek
  CHECK(errorOf("# tilt 40\xc2\xb0\n[plane]\nalpha_deg = 40 # \xce\xb1, and a '\"' in a comment\n") == "(no error)");
  // outside comments it is refused before toml++ sees it (upstream issues #190 and #295 of
  // marzer/tomlplusplus: these inputs reach __builtin_unreachable() in 3.3.0)
  CHECK(errorOf("[root]\nradius_mm = 0.1 \xcd\x88\n") ==
        "scenes/t.toml:2: non-ASCII character outside a comment (scene and sweep files are ASCII TOML; other text "
        "may only appear in # comments)");
  CHECK(errorOf("s = \"\"\"\\\n\xc2\xa7\"\"\"\n").find("scenes/t.toml:2: non-ASCII character outside a comment") == 0);
  CHECK(errorOf("[tropism]\nsensing = \"\xc3\xa9\" # \xc3\xa9\n").find("scenes/t.toml:2: non-ASCII") == 0);
  // a '#' inside a string starts no comment
  CHECK(errorOf("[tropism]\nsensing = \"a#\xc3\xa9\"\n").find("scenes/t.toml:2: non-ASCII") == 0);
  CHECK(errorOf("", {"tropism.beta=0.1 \xcd\x88"}) ==
        "--set tropism.beta=0.1 \xcd\x88: non-ASCII characters are not allowed (scene values are ASCII)");
}

TEST_CASE("deep nesting and long keys are refused before toml++ parses them (its recursion overflowed the stack)") {
  // a dotted key of 35 000 parts (80 kB) crashed toml++ with SIGSEGV; refused naming file:line and the limit
  std::string deep = "[root]\nradius_mm = 0.1\na";
  for (int i = 0; i < 40000; ++i) deep += ".a";
  CHECK(errorOf(deep + " = 1\n") ==
        "scenes/t.toml:3: a key nested more than 64 levels deep (its dotted parts, with those of its [table] header "
        "and of the inline tables around it; at most 64)");
  // the same in a [table] header, and counted with the header's parts
  std::string header = "[a";
  for (int i = 0; i < 64; ++i) header += ".b";
  CHECK(errorOf(header + "]\n").find("scenes/t.toml:1: a key nested more than 64 levels deep") == 0);
  std::string in63 = "[t.u]\nk";
  for (int i = 0; i < 62; ++i) in63 += ".b";  // 2 + 63 parts
  CHECK(errorOf(in63 + " = 1\n").find("scenes/t.toml:2: a key nested more than 64 levels deep") == 0);
  // 64 levels pass the screen (and are then refused as an unknown section by the schema)
  std::string at64 = "[t]\nk";
  for (int i = 0; i < 62; ++i) at64 += ".b";
  CHECK(errorOf(at64 + " = 1\n").find("scenes/t.toml:1: unknown section [t]") == 0);
  // inline arrays and tables
  const std::string arrays = "[load]\ntip_force_n = " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  CHECK(errorOf(arrays) == "scenes/t.toml:2: arrays or inline tables nested more than 64 levels deep (with the dotted "
                           "parts of the keys around them; at most 64)");
  std::string tables = "[load]\ntip_force_n = ";
  for (int i = 0; i < 30000; ++i) tables += "{a = ";
  tables += "1" + std::string(30000, '}') + "\n";
  CHECK(errorOf(tables).find("scenes/t.toml:2: a") == 0);
  CHECK(errorOf(tables).find("nested more than 64 levels deep") != std::string::npos);
  // strings and comments hold brackets freely; a multi-line array counts its lines
  CHECK(errorOf("# [[[[[[[[\n[tropism]\nsensing = \"[[[[{{{{.a.a\" # {{{{\n") .find("sensing must be one of") != std::string::npos);
  CHECK(errorOf("[load]\ntip_force_n = [\n  0,\n  0,\n  " + std::string(70, '[') + "\n") .find("scenes/t.toml:5: arrays") == 0);
  // a key of more than 1024 bytes, bare or quoted
  CHECK(errorOf("[root]\n" + std::string(1025, 'k') + " = 1\n") ==
        "scenes/t.toml:2: a key longer than 1024 bytes (at most 1024)");
  CHECK(errorOf("[root]\n\"" + std::string(1030, 'k') + "\" = 1\n").find("scenes/t.toml:2: a key longer than 1024") == 0);
  CHECK(errorOf("[root]\n" + std::string(1024, 'k') + " = 1\n").find("unknown key root.kkk") != std::string::npos);
  // --set values and sweep files go through the same screen
  CHECK(errorOf("", {"load.tip_force_n=" + std::string(70, '[') + std::string(70, ']')}) ==
        "--set load.tip_force_n=" + std::string(70, '[') + std::string(70, ']') +
            ": arrays or inline tables nested more than 64 levels deep (with the dotted parts of the keys around "
            "them; at most 64)");
  const fs::path d = scratch("deep");
  { std::ofstream(d / "deep.toml") << "[sweep]\nscene = \"x.toml\"\n" << deep.substr(deep.rfind('\n') + 1) << " = 1\n"; }
  CHECK(sweepError(d / "deep.toml").find((d / "deep.toml").string() + ":3: a key nested more than 64 levels deep") == 0);
  fs::remove_all(d);
}

TEST_CASE("a trajectory with a huge coordinate or radius is refused naming file line frame and node") {
  const fs::path d = scratch("trajbound");
  const std::string head = "frame,step,time_h,node,x_mm,y_mm,z_mm,d1x,d1y,d1z,d3x,d3y,d3z,radius_mm\n";
  const std::string good = "0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n";
  const std::pair<std::string, std::string> cases[] = {
      {good + "1,5,1,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n1,5,1,1,0,-1e7,-0.3,,,,,,,\n",
       ":5: frame 1, node 1: y_mm = -1e+07 is outside -10000 .. 10000 mm (positions are bounded to |x|, |y|, |z| <= 10 m)"},
      {"0,0,0,0,10000.5,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":2: frame 0, node 0: x_mm = 10000.5 is outside"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,200\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n",
       ":2: frame 0, node 0: radius_mm = 200 is above 100 mm (radii are bounded to 0.1 m)"},
  };
  for (const auto& c : cases) {
    // (not a structured binding: clang before 16 cannot capture one in CAPTURE's lambda)
    const std::string& rows = c.first;
    const std::string& expected = c.second;
    CAPTURE(expected);
    { std::ofstream(d / "trajectory.csv") << head << rows; }
    std::string e = "(no error)";
    try {
      readTrajectory(d / "trajectory.csv");
    } catch (const SceneError& x) {
      e = x.what();
    }
    CHECK(e.find((d / "trajectory.csv").string() + expected) == 0);
  }
  // at the bounds: accepted
  { std::ofstream(d / "trajectory.csv") << head << "0,0,0,0,-10000,0,0.1,1,0,0,0,-0.6,-0.8,100\n0,0,0,1,0,10000,-0.3,,,,,,,\n"; }
  CHECK(readTrajectory(d / "trajectory.csv").size() == 1);
  fs::remove_all(d);
}

TEST_CASE("numbers are written in the shortest form that reads back exactly") {
  CHECK(shortestNumber(0.3) == "0.3");
  CHECK(shortestNumber(35.7) == "35.7");
  CHECK(shortestNumber(0.1 + 0.2) == "0.30000000000000004");  // not 0.3: another double
  CHECK(shortestNumber(2) == "2.0");
  CHECK(shortestNumber(-0.0) == "-0.0");
  CHECK(shortestNumber(1e-7) == "1e-07");
  CHECK(shortestNumber(1e300) == "1e+300");
  const fs::path d = scratch("numbers");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/cantilever_tip_load.toml\"\n"
                                << "[grid]\n\"plane.alpha_deg\" = [35.7, 40.0]\n\"tropism.twist_r_tau\" = [0.3]\n"
                                << "\"load.tip_force_n\" = [[0, 0.1, -2.5e-5]]\n";
  }
  // (grid keys in the order toml++ gives them: sorted)
  const SweepPlan p = loadSweep((d / "s.toml").string());
  REQUIRE(p.points.size() == 2);
  CHECK(p.points[0].dirName == "run_0000_tip_force_n=_0_0.1_-2.5e-05__alpha_deg=35.7_twist_r_tau=0.3");
  CHECK(p.points[1].dirName == "run_0001_tip_force_n=_0_0.1_-2.5e-05__alpha_deg=40.0_twist_r_tau=0.3");
  REQUIRE(p.points[0].grid.size() == 3);
  CHECK(p.points[0].grid[1].second == "35.7");  // table.csv's grid column
  CHECK(p.points[0].grid[0].second == "[0,0.1,-2.5e-05]");
  CHECK(p.points[0].overrides[2] == "tropism.twist_r_tau=0.3");
  // the resolved scene writes the value as given
  CHECK(p.points[0].resolvedToml.find("\nalpha_deg = 35.7 ") != std::string::npos);
  fs::remove_all(d);
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
