// the rootsim binary: exit codes, messages, run directories, determinism (src/cli, src/io/run_dir.cpp)
#include <doctest/doctest.h>

#include <chrono>

#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
#include <sys/stat.h>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;

using rootsim::test::slurp;

// a fresh scratch folder per test
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("cli", name); }

using rootsim::test::kCantilever;
using rootsim::test::kScene;
using rootsim::test::lines;
using rootsim::test::runIn;

// every file and folder below d, to compare a folder before and after
std::map<std::string, std::string> tree(const fs::path& d) { return rootsim::test::fileTree(d, true); }

const std::string kSmall = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml --set growth.steps=30 "
                           "--set output.every_steps=5 --quiet";
}  // namespace

TEST_CASE("--version and --help exit 0") {
  const Result v = run("--version");
  CHECK(v.code == 0);
  CHECK(v.out.find("rootsim 0.") != std::string::npos);
  CHECK(run("--help").code == 0);
  CHECK(run("run --help").code == 0);
}

TEST_CASE("bad usage exits 2") {
  CHECK(run("").code == 2);
  CHECK(run("frobnicate").code == 2);
  const Result r = run("run /nonexistent/x.toml");
  CHECK(r.code == 2);
  CHECK(r.out.find("/nonexistent/x.toml: no such scene file") != std::string::npos);
}

TEST_CASE("an obstacle overlapping the initial root exits 2 naming file:line and key") {
  const fs::path d = scratch("badobstacle");
  { std::ofstream(d / "peg.toml") << "[[obstacle]]\nshape = \"peg\"\ncenter_mm = [0, 0.5]\nradius_mm = 0.3\n"; }
  const Result r = run("run " + (d / "peg.toml").string() + " --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("peg.toml:3: obstacle[1].center_mm overlaps the initial root") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
}

TEST_CASE("a rod with no static equilibrium exits 1 saying it slides and naming the node, not at the sub-step cap") {
  // a free 1 mm rod on a plate tilted by 60 deg under its weight, mu_s 5 % below cot(60 deg)
  const fs::path d = scratch("slides");
  {
    std::ofstream(d / "slide.toml") << "[root]\ninitial_length_mm = 1\n[growth]\nenabled = false\n[plane]\n"
                                       "alpha_deg = 60\n[adhesion]\nenabled = false\n[load]\nbase = \"free\"\n"
                                       "gravity = true\n[friction]\nenabled = true\nmu_static = 0.55\n"
                                       "mu_kinetic = 0.5\n";  // physical gravity, the default tolerances
  }
  // (how fast is measured, not asserted: it takes seconds in Release, minutes under ASan)
  const Result r = run("run " + (d / "slide.toml").string() + " --quiet --out " + (d / "out").string());
  CHECK(r.code == 1);
  CHECK(r.out.find("slides: no static equilibrium") != std::string::npos);
  CHECK(r.out.find("node ") != std::string::npos);
  CHECK(r.out.find("did not reach equilibrium in") == std::string::npos);  // found by the slide check, not the cap
  // 5 % above cot(alpha) it stays: the same scene runs to completion
  CHECK(run("run " + (d / "slide.toml").string() + " --set friction.mu_static=0.61 --quiet --out " + (d / "stays").string()).code == 0);
}

TEST_CASE("a bad scene exits 2 with file:line:key and writes nothing") {
  const fs::path d = scratch("bad");
  { std::ofstream(d / "bad.toml") << "[tropism]\nbeta = 0.1\nbta = 0.2\n"; }
  const Result r = run("run " + (d / "bad.toml").string() + " --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("bad.toml:3: unknown key tropism.bta (did you mean tropism.beta?)") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
  CHECK(!fs::exists(d / "out.partial"));
  const Result s = run("run " + kSmall + " --set plane.alpha_deg=120 --out " + (d / "out").string());
  CHECK(s.code == 2);
  CHECK(s.out.find("--set plane.alpha_deg=120: plane.alpha_deg must be in [0, 90]") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
}

TEST_CASE("an unwritable or foreign output folder exits 2") {
  const Result r = run("run " + kSmall + " --out /proc/rootsim_cannot_write_here");
  CHECK(r.code == 2);
  CHECK(r.out.find("cannot create") != std::string::npos);
  const fs::path d = scratch("foreign");
  { std::ofstream(d / "notes.txt") << "mine\n"; }
  const Result f = run("run " + kSmall + " --out " + d.string());
  CHECK(f.code == 2);
  CHECK(f.out.find("is not a rootsim run directory") != std::string::npos);
  CHECK(fs::exists(d / "notes.txt"));
}

TEST_CASE("a run that fails exits 1 and keeps its partial output marked incomplete") {
  const fs::path d = scratch("fail");
  const Result r = run("run " + kSmall + " --set solver.kind=dynamic --set solver.max_substeps=3 --out " + (d / "out").string());
  CHECK(r.code == 1);
  CHECK(r.out.find("did not reach equilibrium in 3 sub-steps") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
  CHECK(fs::exists(d / "out.incomplete" / "ERROR.txt"));
  CHECK(fs::exists(d / "out.incomplete" / "scene.toml"));
}

TEST_CASE("a run that fails at a growth step keeps its time series, trajectory and ParaView files up to the last output before it") {
  const fs::path d = scratch("failstep");
  // the explicit solver capped at 200 sub-steps: the first steps settle, the first snap does not
  const Result r = run("run " + std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml --set root.element_length_mm=0.1 "
                       "--set growth.steps=200 --set growth.step_h=0.1 --set solver.kind=dynamic --set solver.max_substeps=200 "
                       "--set output.every_steps=5 --quiet --out " + (d / "out").string());
  REQUIRE(r.code == 1);
  const fs::path inc = d / "out.incomplete";
  const std::string err = slurp(inc / "ERROR.txt");
  int failed = -1;
  REQUIRE(std::sscanf(err.c_str(), "growth step %d", &failed) == 1);
  REQUIRE(failed > 5);
  // whole rows, one every 5 steps from 0 to the last output step before the failing one
  std::istringstream ts(slurp(inc / "timeseries.csv"));
  std::string line, header;
  std::getline(ts, header);
  const auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  int rows = 0, last = -1;
  while (std::getline(ts, line)) {
    CHECK(fields(line) == fields(header));
    last = std::stoi(line.substr(0, line.find(',')));
    CHECK(last == 5 * rows);
    ++rows;
  }
  CHECK(last == 5 * ((failed - 1) / 5));
  CHECK(!fs::exists(inc / "timeseries.csv.tmp"));
  // the trajectory and the ParaView index hold the same frames
  CHECK(fs::file_size(inc / "trajectory.bin") > 0);
  const std::string pvd = slurp(inc / "trajectory.pvd");
  int frames = 0;
  for (size_t p = pvd.find("<DataSet"); p != std::string::npos; p = pvd.find("<DataSet", p + 1)) ++frames;
  CHECK(frames == rows);
  CHECK(fs::exists(inc / "vtk" / "step_000000.vtp"));
}

TEST_CASE("a Newton run that cannot reach equilibrium fails with the step and the solver's message") {
  const fs::path d = scratch("newtonfail");
  // one Newton iteration, then the explicit relaxation with a cap of 3 sub-steps: neither gets there
  const Result r = run("run " + kSmall + " --set solver.kind=newton --set solver.newton_max_iterations=1 "
                       "--set solver.max_substeps=3 --out " + (d / "out").string());
  CHECK(r.code == 1);
  CHECK(r.out.find("growth step") != std::string::npos);
  CHECK(r.out.find("did not reach equilibrium") != std::string::npos);
  CHECK(fs::exists(d / "out.incomplete" / "ERROR.txt"));
}

TEST_CASE("determinism: the same scene twice gives identical files") {
  const fs::path d = scratch("det");
  REQUIRE(run("run " + kSmall + " --out " + (d / "a").string()).code == 0);
  REQUIRE(run("run " + kSmall + " --out " + (d / "b").string()).code == 0);
  for (const char* f : {"scene.toml", "timeseries.csv", "shape.csv", "trajectory.bin", "trajectory.pvd",
                        "vtk/step_000030.vtp"}) {
    INFO(f);
    const std::string a = slurp(d / "a" / f), b = slurp(d / "b" / f);
    CHECK(!a.empty());
    CHECK(a == b);
  }
  // summary.json: identical except the wall time
  auto strip = [](std::string s) {
    const auto p = s.find("\"wall_time_s\"");
    return p == std::string::npos ? s : s.substr(0, p);
  };
  CHECK(strip(slurp(d / "a" / "summary.json")) == strip(slurp(d / "b" / "summary.json")));
  // the resolved scene reproduces the run
  REQUIRE(run("run " + (d / "a" / "scene.toml").string() + " --quiet --out " + (d / "c").string()).code == 0);
  CHECK(slurp(d / "c" / "timeseries.csv") == slurp(d / "a" / "timeseries.csv"));
}

TEST_CASE("check prints the resolved scene and the theory") {
  const Result r = run("check " + std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml");
  CHECK(r.code == 0);
  CHECK(r.out.find("beta = 0.2") != std::string::npos);
  CHECK(r.out.find("\"T0_h\": 5.18") != std::string::npos);
}

TEST_CASE("every shipped scene and sweep validates, and every scene runs coarsened") {
  const fs::path src = ROOTSIM_SOURCE_DIR;
  const fs::path d = scratch("scenes");
  int n = 0;
  for (const auto& e : fs::directory_iterator(src / "scenes")) {
    if (e.path().extension() != ".toml") continue;
    INFO(e.path().string());
    CHECK(run("check " + e.path().string()).code == 0);
    // coarsened: 20 growth steps of 0.1 h with 0.1 mm elements (mechanics scenes: as they are)
    const std::string scene = slurp(e.path());
    const bool grows = scene.find("[growth]\nenabled = false") == std::string::npos;
    // (a plate with laterals keeps its elements: its laterals' 0.6 mm zones need 10 of them, and a plate
    // whose laterals' scene readers would refuse is refused when it starts)
    const bool laterals = scene.find("[laterals]") != std::string::npos;
    const std::string sets = grows ? " --set growth.steps=20 --set growth.step_h=0.1" +
                                         std::string(laterals ? "" : " --set root.element_length_mm=0.1")
                                   : "";
    const Result r = run("run " + e.path().string() + sets + " --quiet --set output.vtk=false --out " +
                         (d / e.path().stem()).string());
    CHECK(r.code == 0);
    CHECK(fs::exists(d / e.path().stem() / "summary.json"));
    ++n;
  }
  CHECK(n >= 10);
  for (const auto& e : fs::directory_iterator(src / "sweeps")) {
    INFO(e.path().string());
    // --shard 1/1000 keeps at most one point: validates the whole grid, runs almost nothing
    const Result r = run("sweep " + e.path().string() + " --shard 1000/1000 --quiet --out " +
                         (d / ("sweep_" + e.path().stem().string())).string());
    CHECK(r.code == 0);
  }
}

TEST_CASE("shipped scenes coarsened: the 10 mm alpha = 40 root waves (not skews), 0 is straight, 80 coils, twist skews") {
  // 0.1 mm elements and 0.1 h steps as the coarse tests do; grown to 10 mm (the scene's own length)
  const fs::path src = ROOTSIM_SOURCE_DIR;
  const fs::path d = scratch("patterns");
  const std::string coarse = " --set root.element_length_mm=0.1 --set growth.step_h=0.1 --set output.vtk=false"
                             " --set output.trajectory=false --quiet";
  struct Expect { const char* scene; const char* sets; const char* pattern; };
  const Expect cases[] = {
      {"fig2a_alpha40", " --set growth.steps=450", "waving"},  // 1.1 + 450 x 0.02 mm = 10.1 mm
      {"fig2a_alpha0", " --set growth.steps=450", "straight"},
      {"fig2a_alpha80", " --set growth.steps=450", "coiling"},
      {"fig4a_skewing", " --set growth.steps=500", "skewing"},
  };
  for (const auto& c : cases) {
    INFO(c.scene);
    const fs::path out = d / c.scene;
    const Result r = run("run " + (src / "scenes" / (std::string(c.scene) + ".toml")).string() + coarse + c.sets +
                         " --out " + out.string());
    REQUIRE(r.code == 0);
    const std::string j = slurp(out / "summary.json");
    INFO(j);
    CHECK(j.find(std::string("\"pattern\": \"") + c.pattern + "\"") != std::string::npos);
    CHECK(j.find("\"amplitude_half_mm\"") != std::string::npos);
    CHECK(slurp(out / "result.csv").find(",amplitude_mm,amplitude_half_mm,") != std::string::npos);
  }
}

// --- rootsim never deletes or overwrites what it did not write (the run-directory marker) ---

TEST_CASE("--out at a user's folder holding the scene: refused, the folder untouched") {
  const fs::path d = scratch("ownscene");
  fs::create_directories(d / "e");
  fs::copy_file(fs::path(ROOTSIM_SOURCE_DIR) / "scenes/fig2b_waving.toml", d / "e" / "scene.toml",
                fs::copy_options::overwrite_existing);
  { std::ofstream(d / "e" / "notes.txt") << "x\n"; }
  const auto before = tree(d);
  const Result r = run("run " + (d / "e" / "scene.toml").string() + " --set growth.steps=5 --quiet --out " +
                       (d / "e").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("contains") != std::string::npos);
  CHECK(tree(d) == before);
  // the same with --force: still refused, still untouched
  CHECK(run("run " + (d / "e" / "scene.toml").string() + " --set growth.steps=5 --quiet --force --out " +
            (d / "e").string()).code == 2);
  CHECK(tree(d) == before);
  // a folder holding a scene.toml that is not the one run: not a run directory (no marker)
  const Result f = run("run " + kSmall + " --force --out " + (d / "e").string());
  CHECK(f.code == 2);
  CHECK(f.out.find("is not a rootsim run directory") != std::string::npos);
  CHECK(tree(d) == before);
}

TEST_CASE("--out . and ancestors of the working folder are refused, and nothing is lost") {
  const fs::path d = scratch("dot");
  fs::copy_file(fs::path(ROOTSIM_SOURCE_DIR) / "scenes/fig2b_waving.toml", d / "s.toml");
  fs::copy_file(d / "s.toml", d / "scene.toml");
  { std::ofstream(d / "precious.txt") << "keep\n"; }
  const auto before = tree(d);
  for (const char* out : {".", "./", "..", "../", "/", "./sub/.."}) {
    INFO(out);
    const Result r = runIn(d, std::string("run s.toml --set growth.steps=5 --quiet --force --out ") + out);
    CHECK(r.code == 2);
    CHECK(tree(d) == before);
  }
  const Result a = runIn(d, "run s.toml --set growth.steps=5 --quiet --out " + d.parent_path().string());
  CHECK(a.code == 2);
  CHECK(a.out.find("contains") != std::string::npos);
  CHECK(tree(d) == before);
}

TEST_CASE("--out with a trailing slash or ./ prefix writes the run where the user meant") {
  const fs::path d = scratch("slash");
  REQUIRE(runIn(d, "run " + kSmall + " --out out/").code == 0);
  CHECK(fs::exists(d / "out" / "summary.json"));
  CHECK(fs::exists(d / "out" / ".rootsim-run"));
  CHECK(!fs::exists(d / "out.partial"));
  REQUIRE(runIn(d, "run " + kSmall + " --out ./a/b/").code == 0);
  CHECK(fs::exists(d / "a" / "b" / "summary.json"));
  CHECK(!fs::exists(d / "a" / "b.partial"));
}

TEST_CASE("an earlier run is replaced only with --force, and never when it holds a user's file") {
  const fs::path d = scratch("force");
  const std::string out = (d / "out").string();
  REQUIRE(run("run " + kSmall + " --out " + out).code == 0);
  const auto first = tree(d);
  const Result again = run("run " + kSmall + " --set tropism.beta=0.3 --out " + out);
  CHECK(again.code == 2);
  CHECK(again.out.find("pass --force") != std::string::npos);
  CHECK(tree(d) == first);
  REQUIRE(run("run " + kSmall + " --set tropism.beta=0.3 --force --out " + out).code == 0);
  CHECK(slurp(d / "out" / "scene.toml").find("beta = 0.3") != std::string::npos);
  CHECK(!fs::exists(d / "out.replaced"));
  // a user's file inside the run directory: --force refuses, the file stays
  { std::ofstream(d / "out" / "my_analysis.py") << "print(1)\n"; }
  const auto withUser = tree(d);
  const Result f = run("run " + kSmall + " --force --out " + out);
  CHECK(f.code == 2);
  CHECK(f.out.find("my_analysis.py") != std::string::npos);
  CHECK(tree(d) == withUser);
}

TEST_CASE("an interrupted DIR.partial is kept unless --force, and a foreign DIR.partial is never removed") {
  const fs::path d = scratch("partial");
  fs::create_directories(d / "out.partial");
  { std::ofstream(d / "out.partial" / ".rootsim-run") << "rootsim run directory\n"; }
  { std::ofstream(d / "out.partial" / "timeseries.csv") << "step\n"; }
  const Result r = run("run " + kSmall + " --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("interrupted run") != std::string::npos);
  CHECK(fs::exists(d / "out.partial" / "timeseries.csv"));
  REQUIRE(run("run " + kSmall + " --force --out " + (d / "out").string()).code == 0);
  CHECK(fs::exists(d / "out" / "summary.json"));
  CHECK(!fs::exists(d / "out.partial"));
  fs::create_directories(d / "x.partial");
  { std::ofstream(d / "x.partial" / "mine.txt") << "mine\n"; }
  CHECK(run("run " + kSmall + " --force --out " + (d / "x").string()).code == 2);
  CHECK(fs::exists(d / "x.partial" / "mine.txt"));
}

TEST_CASE("contradictory or smuggled options are refused before the run") {
  const fs::path d = scratch("contra");
  const Result m = run("run " + kSmall + " --movie --set output.trajectory=false --out " + (d / "out").string());
  CHECK(m.code == 2);
  CHECK(m.out.find("--movie needs the trajectory") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
  CHECK(!fs::exists(d / "out.partial"));
  // a newline inside --set would carry a second assignment that was silently dropped
  const Result n = run("run " + kSmall + " --set \"$(printf 'tropism.beta=0.3\\nplane.alpha_deg=80')\" --out " + (d / "n").string());
  CHECK(n.code == 2);
  CHECK(n.out.find("control characters") != std::string::npos);
  CHECK(n.out.find("\\n") != std::string::npos);
  CHECK(!fs::exists(d / "n.partial"));
  // a bad figure name creates no folder
  const Result f = runIn(d, "figure nope --out a/b/c");
  CHECK(f.code == 2);
  CHECK(!fs::exists(d / "a"));
}

TEST_CASE("a scene path that is not a regular file, or is huge, exits 2 at once") {
  CHECK(run("check /dev/zero").code == 2);
  CHECK(run("check /dev/zero").out.find("not a regular file") != std::string::npos);
  const fs::path d = scratch("fifo");
  REQUIRE(::mkfifo((d / "f.toml").c_str(), 0600) == 0);
  const Result f = run("check " + (d / "f.toml").string());
  CHECK(f.code == 2);
  { std::ofstream(d / "big.toml") << std::string(2 << 20, '#'); }
  const Result b = run("check " + (d / "big.toml").string());
  CHECK(b.code == 2);
  CHECK(b.out.find("larger than 1 MiB") != std::string::npos);
}

TEST_CASE("modes writes the softest stiffness modes of a run's final state") {
  const fs::path d = scratch("modes");
  REQUIRE(run("run " + kSmall + " --set solver.kind=newton --out " + (d / "r").string()).code == 0);
  const Result r = run("modes " + (d / "r").string() + " --count 3 --quiet");
  REQUIRE(r.code == 0);
  std::istringstream csv(slurp(d / "r" / "modes.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "mode,eigenvalue_n_per_m,node,s_mm,x_mm,y_mm,z_mm,ux,uy,uz");
  std::map<int, double> eig;
  while (std::getline(csv, line)) {
    const int mode = std::stoi(line.substr(0, line.find(',')));
    eig[mode] = std::stod(line.substr(line.find(',') + 1));
  }
  REQUIRE(eig.size() == 3);
  CHECK(eig[1] > 0);  // a relaxed, stable root
  CHECK(eig[1] <= eig[2]);
  CHECK(eig[2] <= eig[3]);
  CHECK(slurp(d / "r" / "modes.vtp").find("Name=\"mode_3\"") != std::string::npos);
  // a folder that is not a run
  CHECK(run("modes " + d.string() + " --quiet").code == 2);
  CHECK(run("modes " + (d / "r").string() + " --count 0").code == 2);
}

TEST_CASE("modes of a plate's root: the whole plate repeated, the files in the root's folder, by --root or by its folder") {
  const fs::path d = scratch("plate_modes");
  {
    std::ofstream(d / "plate.toml") << "[root]\nelement_length_mm = 0.1\n[growth]\nsteps = 30\nstep_h = 0.1\n[output]\nvtk = false\n"
                                       "[plate]\nwidth_mm = 30\nlength_mm = 20\n[[seedling]]\nname = \"a\"\nposition_mm = [10, 5]\n"
                                       "[[seedling]]\nname = \"b\"\nposition_mm = [20, 5]\nset = { \"tropism.beta\" = 0.3 }\n";
  }
  REQUIRE(run("run " + (d / "plate.toml").string() + " --set solver.kind=newton --out " + (d / "r").string() + " --quiet").code == 0);
  // the plate itself: which root?
  const Result which = run("modes " + (d / "r").string() + " --quiet");
  CHECK(which.code == 2);
  CHECK(which.out.find("a plate's run; give --root NAME") != std::string::npos);
  const Result nosuch = run("modes " + (d / "r").string() + " --root zz --quiet");
  CHECK(nosuch.code == 2);
  CHECK(nosuch.out.find("--root zz") != std::string::npos);
  const Result r = run("modes " + (d / "r").string() + " --root b --count 3 --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  CHECK_FALSE(fs::exists(d / "r" / "modes.csv"));
  const std::string csv = slurp(d / "r" / "roots" / "b" / "modes.csv");
  // three modes of b's nodes (its shape.csv's rows), softest first and positive
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::map<int, double> eig;
  std::map<int, int> nodes;
  while (std::getline(in, line)) {
    const int mode = std::stoi(line.substr(0, line.find(',')));
    eig[mode] = std::stod(line.substr(line.find(',') + 1));
    ++nodes[mode];
  }
  REQUIRE(eig.size() == 3);
  CHECK(eig[1] > 0);
  CHECK(eig[1] <= eig[2]);
  CHECK(eig[2] <= eig[3]);
  CHECK(nodes[1] == lines(slurp(d / "r" / "roots" / "b" / "shape.csv")) - 1);
  // the root's folder gives the same files; another root's, its own
  const Result byFolder = run("modes " + (d / "r" / "roots" / "b").string() + " --count 3 --force --quiet");
  REQUIRE_MESSAGE(byFolder.code == 0, byFolder.out);
  CHECK(slurp(d / "r" / "roots" / "b" / "modes.csv") == csv);
  REQUIRE(run("modes " + (d / "r" / "roots" / "a").string() + " --count 3 --quiet").code == 0);
  CHECK(slurp(d / "r" / "roots" / "a" / "modes.csv") != csv);  // a's beta differs: another shape
  const Result mismatch = run("modes " + (d / "r" / "roots" / "a").string() + " --root b --quiet");
  CHECK(mismatch.code == 2);
}

TEST_CASE("a value beyond its physical bound exits 2 naming key and range and writes nothing") {
  const fs::path d = scratch("bounds");
  const Result c = run("check " + kScene + " --set root.radius_mm=1e300");
  CHECK(c.code == 2);
  CHECK(c.out == "rootsim: error: --set root.radius_mm=1e300: root.radius_mm must be in (0, 100] (got 1e+300)\n");
  // growth_zone_mm = 1e300 ran for minutes before failing
  const Result r = run("run " + kScene + " --set growth.growth_zone_mm=1e300 --quiet --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("growth.growth_zone_mm must be in (0, 1000] (got 1e+300)") != std::string::npos);
  CHECK(fs::is_empty(d));
  // `check` documents the range of every number key
  const Result k = run("check " + kScene);
  CHECK(k.code == 0);
  CHECK(k.out.find("# root radius R [mm]; in (0, 100]\n") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("scenes beyond the element cap exit 2 at once naming the keys and the cap") {
  const fs::path d = scratch("cap");
  const std::string out = " --quiet --out " + (d / "out").string();
  const Result a = run("run " + kScene + " --set root.initial_length_mm=1e4" + out);
  CHECK(a.code == 2);
  CHECK(a.out.find("root.initial_length_mm / root.element_length_mm = 10000 mm / 0.05 mm = 200000 elements at the "
                   "start; at most 20000 elements are allowed") != std::string::npos);
  const Result b = run("run " + kScene + " --set root.element_length_mm=1e-12" + out);
  CHECK(b.code == 2);
  CHECK(b.out.find("--set root.element_length_mm: root.element_length_mm = 1e-12: ") != std::string::npos);
  const Result c = run("run " + kCantilever + " --set root.initial_length_mm=9000 --set root.element_length_mm=0.01" + out);
  CHECK(c.code == 2);
  CHECK(c.out.find("= 900000 elements at the start; at most 20000 elements are allowed") != std::string::npos);
  const Result g = run("run " + kScene + " --set growth.steps=1000000" + out);
  CHECK(g.code == 2);
  CHECK(g.out.find("growth.steps = 1000000: the root grows to 10001.1 mm") != std::string::npos);
  CHECK(fs::is_empty(d));
  fs::remove_all(d);
}

TEST_CASE("render on a trajectory with NaN or inf exits 2 naming file and line") {
  const fs::path d = scratch("nanrender");
  const Result r = run("run " + kScene + " --set growth.steps=20 --set output.every_steps=10 --set output.vtk=false "
                       "--set output.trajectory_format=csv --quiet --out " + (d / "out").string());
  REQUIRE(r.code == 0);
  const fs::path traj = d / "out" / "trajectory.csv";
  const std::string good = slurp(traj);
  for (const char* bad : {"nan", "inf", "-inf"}) {
    CAPTURE(bad);
    // line 5: the fourth node of the first frame; its x_mm (5th column) becomes bad
    std::istringstream in(good);
    std::string text, line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (n == 5) {
        size_t c = 0;
        for (int k = 0; k < 4; ++k) c = line.find(',', c) + 1;
        line = line.substr(0, c) + bad + line.substr(line.find(',', c));
      }
      text += line + "\n";
    }
    { std::ofstream(traj, std::ios::binary) << text; }
    const Result m = run("render " + (d / "out").string() + " --quiet --mp4 " + (d / "m.mp4").string());
    CHECK(m.code == 2);
    CHECK(m.out == "rootsim: error: " + traj.string() + ":5: x_mm: not a finite number (got " + bad + ")\n");
    CHECK(!fs::exists(d / "m.mp4"));
  }
  fs::remove_all(d);
}

TEST_CASE("a free 2 mm rod under its weight on a plate at 80 deg slides at mu_s = 0.01 and without friction, stays at mu_s = 0.5") {
  // physical gravity and the default tolerances, both solvers: the downhill pull (3e-9 N per node) is far
  // below B1/Lref^2 * force_tol (9.8e-8 N), which once let the rod "converge" unmoved in a few sub-steps
  const fs::path d = scratch("incline80");
  {
    std::ofstream(d / "incline.toml") << "[root]\ninitial_length_mm = 2\n[growth]\nenabled = false\n[plane]\n"
                                         "alpha_deg = 80\n[adhesion]\nenabled = false\n[load]\nbase = \"free\"\n"
                                         "gravity = true\n[friction]\nenabled = true\nmu_static = 0.01\n"
                                         "mu_kinetic = 0.008\n";
  }
  const std::string scene = (d / "incline.toml").string();
  // cot(80 deg) = 0.176
  for (const char* k : {"dynamic", "newton"}) {
    const std::string kind = k;
    INFO(kind);
    const std::string set = " --set solver.kind=" + kind + " --quiet --out ";
    for (const char* f : {"friction.enabled=true", "friction.enabled=false"}) {
      const std::string friction = f;
      INFO(friction);
      const Result r = run("run " + scene + " --set " + friction + set + (d / (kind + friction)).string());
      CHECK(r.code == 1);
      CHECK(std::regex_search(r.out, std::regex(R"(node \d+ slides: no static equilibrium)")));
      CHECK(r.out.find("did not reach equilibrium in") == std::string::npos);  // the slide check, not the cap
    }
    const Result s = run("run " + scene + " --set friction.mu_static=0.5 --set friction.mu_kinetic=0.4" + set +
                         (d / kind).string());
    CHECK(s.code == 0);
    CHECK(fs::exists(d / kind / "summary.json"));
  }
  fs::remove_all(d);
}

TEST_CASE("usage errors: CLI11's errors and unknown commands are one rootsim: error line naming the flag or command") {
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {"fly", "rootsim: error: unknown command fly (did you mean fit?); the commands: run, check, render"},
      {"rnu x.toml", "rootsim: error: unknown command rnu (did you mean run?)"},
      {"", "rootsim: error: a command is required: run, check, render"},
      {"render RUN --atH 3", "rootsim: error: unknown flag --atH for render (did you mean --at-h?)"},
      {"render RUN --zzz", "rootsim: error: unknown flag --zzz for render (rootsim render --help)"},
      {"compare RUN T.rsml --at-h abc", "rootsim: error: --at-h abc: expected a number"},
      {"render RUN --frame 1.5", "rootsim: error: --frame 1.5: expected an integer"},
      {"render RUN --fps 0", "rootsim: error: render: --fps: Value 0 not in range 1 to 240"},
      {"render", "rootsim: error: render: run_dir is required"},
  };
  for (const Case& c : cases) {
    const Result r = run(c.args);
    CHECK_MESSAGE(r.code == 2, c.args);
    CHECK_MESSAGE(r.out.find(c.expect) == 0, c.args << " -> " << r.out);
    CHECK_MESSAGE(lines(r.out) == 1, c.args << " -> " << r.out);
  }
  // help and the version stay exit 0
  CHECK(run("render --help").code == 0);
}

TEST_CASE("figure: --dpi and --width-mm are finite and in range and a panel too large is refused before anything is written") {
  const fs::path d = scratch("figure_numbers");
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {"--dpi nan", "rootsim: error: --dpi nan: expected a finite number in [10, 2400] dpi"},
      {"--width-mm nan", "rootsim: error: --width-mm nan: expected a finite number in [10, 1000] mm"},
      {"--width-mm inf", "rootsim: error: figure: --width-mm: Value inf not in range"},
      {"--dpi 2400 --width-mm 1000",
       "rootsim: error: --width-mm 1000 at --dpi 2400: a panel's PNG: would make 94489 pixels wide, more than the cap of 20000"},
  };
  for (const Case& c : cases) {
    const Result r = run("figure fig2a --quick --quiet " + c.args + " --out " + (d / "f").string());
    CHECK_MESSAGE(r.code == 2, c.args);
    CHECK_MESSAGE(r.out.find(c.expect) == 0, c.args << " -> " << r.out);
    CHECK_MESSAGE(lines(r.out) == 1, c.args);
    CHECK_MESSAGE(!fs::exists(d / "f"), c.args);
  }
}

TEST_CASE("every shipped scene and a plate with laterals run short are read back by every reading command") {
  if (run("render --help").out.find("--png") == std::string::npos) {
    rootsim::test::skipCase("rootsim built without the renderer: no render or export");
    return;
  }
  const fs::path d = scratch("readback");
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(std::string(ROOTSIM_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".toml") scenes.push_back(e.path());
  std::sort(scenes.begin(), scenes.end());
  // a plate whose laterals emerge within the short run
  {
    std::ofstream f(d / "plate_laterals.toml");
    f << "[root]\nradius_mm = 0.1\ninitial_length_mm = 1.1\n[growth]\nsteps = 60\n[tropism]\nbeta = 0.2\n[plane]\n"
         "alpha_deg = 40\n[output]\nevery_steps = 20\nvtk = false\n[plate]\nwidth_mm = 60\nlength_mm = 40\n"
         "[laterals]\nenabled = true\nfirst_mm = 0.5\nspacing_mm = 0.5\napical_unbranched_mm = 0.5\n"
         "[[seedling]]\nname = \"a\"\nposition_mm = [20, 5]\n[[seedling]]\nname = \"b\"\nposition_mm = [40, 5]\n";
  }
  scenes.push_back(d / "plate_laterals.toml");
  for (const fs::path& scene : scenes) {
    const std::string name = scene.stem().string();
    const fs::path out = d / name;
    const bool ours = name == "plate_laterals";
    const Result r = run("run " + scene.string() + (ours ? "" : " --set growth.steps=4 --set output.every_steps=2") +
                         " --set output.vtk=false --quiet --out " + out.string());
    REQUIRE_MESSAGE(r.code == 0, name << ": " << r.out);
    // the run's folders: the run, or each root of a plate
    std::vector<fs::path> dirs;
    if (fs::is_directory(out / "roots")) {
      for (const auto& e : fs::directory_iterator(out / "roots")) dirs.push_back(e.path());
      const Result plate = run("render " + out.string() + " --plate-view --png " + (d / (name + "_plate.png")).string() + " --frame 0 --quiet");
      CHECK_MESSAGE(plate.code == 0, name << ": " << plate.out);
      const Result rsml = run("export " + out.string() + " --rsml " + (d / (name + "_plate.rsml")).string() + " --quiet");
      CHECK_MESSAGE(rsml.code == 0, name << ": " << rsml.out);
    } else {
      dirs.push_back(out);
    }
    if (ours) CHECK(dirs.size() > 2);  // laterals emerged
    for (const fs::path& dir : dirs) {
      const std::string tag = name + "_" + dir.filename().string();
      for (const std::string& cmd :
           {"render " + dir.string() + " --png " + (d / (tag + ".png")).string() + " --frame 0",
            "export " + dir.string() + " --rsml " + (d / (tag + ".rsml")).string(),
            "export " + dir.string() + " --gltf " + (d / (tag + ".glb")).string()}) {
        const Result c = run(cmd + " --quiet");
        CHECK_MESSAGE(c.code == 0, cmd << ": " << c.out);
      }
    }
  }
}
