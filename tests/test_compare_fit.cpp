// `rootsim compare` and `rootsim fit` (src/analysis/compare_trace.cpp, src/analysis/fit_trace.cpp,
// docs/experiments.md) end to end: a run against its own export is at distance 0 with every residual 0;
// a fit's files, its determinism, and its resumption; bad input (exit 2, nothing written); the write rule.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

using rootsim::test::kRoundoff;

namespace fs = std::filesystem;
using namespace rootsim;
using rootsim::test::run;
using rootsim::test::slurp;

namespace {

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("compare_fit", name); }
const std::string kData = std::string(ROOTSIM_SOURCE_DIR) + "/tests/data/rsml/";
// a quick waving root: 0.1 mm elements and 0.1 h steps (the figures' --quick resolution), 7.1 mm long
const std::string kQuick = " --set root.element_length_mm=0.1 --set growth.step_h=0.1 --set output.vtk=false";

// the quick run and its RSML export, made once
struct Quick {
  fs::path run, rsml, scene;
};
const Quick& quick() {
  static const Quick q = [] {
    Quick r;
    const fs::path d = scratch("quick");
    r.run = d / "run";
    r.rsml = d / "run.rsml";
    r.scene = d / "quick.toml";
    const auto a = run("run " + test::kScene + kQuick + " --set growth.steps=300 --out " + r.run.string() + " --quiet");
    REQUIRE(a.code == 0);
    REQUIRE(run("export " + r.run.string() + " --rsml " + r.rsml.string() + " --quiet").code == 0);
    // the fit's base scene: the same scene with the quick resolution (the fit sets growth.steps)
    std::ofstream(r.scene) << slurp(test::kScene) << "\n";
    std::string text = slurp(r.scene);
    text.replace(text.find("element_length_mm = 0.05"), 24, "element_length_mm = 0.1");
    text.replace(text.find("step_h = 0.05"), 13, "step_h = 0.1");
    std::ofstream(r.scene) << text;
    return r;
  }();
  return q;
}

bool built() {
  const auto r = run("compare /nonexistent-run " + kData + "smartroot_pixels.rsml --out /nonexistent-folder/x");
  if (r.out.find("built without") != std::string::npos) {
    test::skipCase("rootsim built without the app library: no compare or fit command");
    return false;
  }
  return true;
}

// a number of a JSON text's "key": value
double jsonNumber(const std::string& s, const std::string& key, std::size_t from = 0) {
  const auto at = s.find("\"" + key + "\": ", from);
  REQUIRE_MESSAGE(at != std::string::npos, key);
  return std::stod(s.substr(at + key.size() + 4));
}

// a string of a JSON text's "key": "value"
std::string jsonString(const std::string& s, const std::string& key, std::size_t from = 0) {
  const auto at = s.find("\"" + key + "\": \"", from);
  REQUIRE_MESSAGE(at != std::string::npos, key);
  const auto start = at + key.size() + 5;
  return s.substr(start, s.find('"', start) - start);
}

// the text of a JSON text's object "key": {...}
std::string jsonObject(const std::string& s, const std::string& key) {
  const auto at = s.find("\"" + key + "\": {");
  REQUIRE_MESSAGE(at != std::string::npos, key);
  const auto open = s.find('{', at);
  int depth = 0;
  for (std::size_t i = open; i < s.size(); ++i) {
    depth += s[i] == '{' ? 1 : s[i] == '}' ? -1 : 0;
    if (depth == 0) return s.substr(open, i + 1 - open);
  }
  return s.substr(open);
}

// the smallest value of a CSV file's column (empty cells skipped)
double columnMin(const std::string& csv, const std::string& column) {
  std::vector<std::string> lines;
  std::stringstream in(csv);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  auto cells = [](const std::string& l) {
    std::vector<std::string> c;
    std::stringstream ls(l);
    for (std::string x; std::getline(ls, x, ',');) c.push_back(x);
    return c;
  };
  const std::vector<std::string> head = cells(lines.at(0));
  const auto col = static_cast<std::size_t>(std::find(head.begin(), head.end(), column) - head.begin());
  REQUIRE_MESSAGE(col < head.size(), column);
  double m = INFINITY;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> c = cells(lines[i]);
    if (col < c.size() && !c[col].empty()) m = std::min(m, std::stod(c[col]));
  }
  return m;
}

// the points (x, y) [mm] of an RSML file rootsim exported (one root)
std::vector<std::pair<double, double>> exportedPoints(const fs::path& rsml) {
  const std::string text = slurp(rsml);
  std::vector<std::pair<double, double>> p;
  for (std::size_t at = text.find("<point x=\""); at != std::string::npos; at = text.find("<point x=\"", at + 1)) {
    const double x = std::stod(text.substr(at + 10));
    const double y = std::stod(text.substr(text.find(" y=\"", at) + 4));
    p.emplace_back(x, y);
  }
  return p;
}

double lengthOf(const std::vector<std::pair<double, double>>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += std::hypot(p[i].first - p[i - 1].first, p[i].second - p[i - 1].second);
  return l;
}

// a 2D+t trace (RootSystemTracker's dialect) of the quick run as a time-lapse tracer records it: its root at
// the last observation, every third node, in whole pixels of 50 um; each point's coord_t from the run's
// length at the observations (every 5 h, from `export --every-h 5`) that its arc length lies between
fs::path lapseTrace(const fs::path& d) {
  REQUIRE(run("export " + quick().run.string() + " --rsml " + (d / "t.rsml").string() + " --every-h 5 --quiet").code == 0);
  std::vector<double> hours, lengths;
  std::vector<std::pair<double, double>> last;
  for (int h = 0; h <= 30; h += 5) {
    char name[32];
    std::snprintf(name, sizeof name, "t_t%06.2fh.rsml", static_cast<double>(h));
    last = exportedPoints(d / name);
    REQUIRE(last.size() > 2);
    hours.push_back(h);
    lengths.push_back(lengthOf(last));
  }
  std::ofstream f(d / "lapse.rsml");
  f << "<?xml version=\"1.0\"?>\n<rsml><metadata><version>1.4</version><unit>pixel(um)</unit><size>50.0</size><observation-hours>";
  for (std::size_t k = 1; k < hours.size(); ++k) f << (k > 1 ? "," : "") << hours[k];
  f << "</observation-hours></metadata><scene><plant ID=\"1\"><root ID=\"1.1\"><geometry><polyline>\n";
  double s = 0;
  for (std::size_t i = 0; i < last.size(); ++i) {
    if (i > 0) s += std::hypot(last[i].first - last[i - 1].first, last[i].second - last[i - 1].second);
    if (i % 3 != 0 && i + 1 != last.size()) continue;
    double k = 0;
    for (std::size_t j = 1; j < lengths.size(); ++j)
      if (s > lengths[j - 1]) k = static_cast<double>(j - 1) + std::min(1.0, (s - lengths[j - 1]) / (lengths[j] - lengths[j - 1]));
    f << "<point coord_t=\"" << k << "\" coord_th=\"" << 5 * k << "\" coord_x=\"" << std::round(100 + 20 * last[i].first)
      << "\" coord_y=\"" << std::round(100 + 20 * last[i].second) << "\" diameter=\"0\" vx=\"0\" vy=\"0\"/>\n";
  }
  f << "</polyline></geometry></root></plant></scene></rsml>\n";
  return d / "lapse.rsml";
}

// the quick run's root as a plate scan's tracer gives it (examples/synthetic_trace.py): at 20 px/mm a point
// every 4 px along the root, each moved by Gaussian noise of 0.5 px (seeded), rounded to 0.1 px, in pixels
fs::path degradedTrace(const fs::path& d, unsigned seed) {
  const std::vector<std::pair<double, double>> p = exportedPoints(quick().rsml);
  std::vector<double> s(1, 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) s.push_back(s.back() + std::hypot(p[i].first - p[i - 1].first, p[i].second - p[i - 1].second));
  const int n = static_cast<int>(std::lround(s.back() / 0.2));
  std::mt19937 gen(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  const fs::path out = d / ("degraded_" + std::to_string(seed) + ".rsml");
  std::ofstream f(out);
  f << "<?xml version=\"1.0\"?>\n<rsml><metadata><unit>pixel</unit><resolution>1</resolution></metadata><scene><plant id=\"1\">"
       "<root id=\"1\"><geometry><polyline>\n";
  std::size_t j = 1;
  for (int k = 0; k <= n; ++k) {
    const double at = s.back() * k / n;
    while (j + 1 < s.size() && s[j] < at) ++j;
    const double w = (at - s[j - 1]) / (s[j] - s[j - 1]);
    const double x = p[j - 1].first + w * (p[j].first - p[j - 1].first), y = p[j - 1].second + w * (p[j].second - p[j - 1].second);
    f << "<point x=\"" << std::round(10 * (200 + 20 * x + noise(gen))) / 10 << "\" y=\"" << std::round(10 * (200 + 20 * y + noise(gen))) / 10
      << "\"/>\n";
  }
  f << "</polyline></geometry></root></plant></scene></rsml>\n";
  return out;
}

std::map<std::string, fs::file_time_type> runTimes(const fs::path& runs) {
  std::map<std::string, fs::file_time_type> t;
  for (const auto& e : fs::directory_iterator(runs))
    if (fs::exists(e.path() / "summary.json")) t[e.path().filename().string()] = fs::last_write_time(e.path() / "summary.json");
  return t;
}

}  // namespace

TEST_CASE("compare: a run against its own export / distance 0, every residual 0, the picture and the table") {
  if (!built()) return;
  const fs::path d = scratch("own");
  const auto r = run("compare " + quick().run.string() + " " + quick().rsml.string() + " --out " + (d / "c").string());
  REQUIRE(r.code == 0);
  const std::string js = slurp(d / "c" / "compare.json");
  CHECK(jsonNumber(js, "distance_mm") < 1e-9);
  CHECK(jsonNumber(js, "frechet_mm") < 1e-9);
  CHECK(jsonNumber(js, "chi2") < 1e-12);
  CHECK(jsonNumber(js, "observables_used") >= 2);  // it waves: the skew, lambda and A
  CHECK(jsonNumber(js, "smoothing_mm") == 0.0);    // an export is measured as it is, and its run alike
  CHECK(js.find("\"snapshot\": \"the snapshot as long as the trace on the plate (the nearest)\"") != std::string::npos);
  // the table on stdout and in compare.csv
  CHECK(r.out.find("wavelength_mm") != std::string::npos);
  const std::string csv = slurp(d / "c" / "compare.csv");
  CHECK(csv.rfind("observable,unit,trace,sim,sigma,residual,used,how\n", 0) == 0);
  CHECK(csv.find("\nwavelength_mm,mm,") != std::string::npos);
  for (const char* f : {"compare.pdf", "compare.svg", "compare.png"}) CHECK(fs::file_size(d / "c" / f) > 1000);
  // replaced only with --force, with the same bytes
  CHECK(run("compare " + quick().run.string() + " " + quick().rsml.string() + " --out " + (d / "c").string()).code == 2);
  const std::string before = slurp(d / "c" / "compare.json");
  REQUIRE(run("compare " + quick().run.string() + " " + quick().rsml.string() + " --out " + (d / "c").string() + " --force --quiet").code == 0);
  CHECK(slurp(d / "c" / "compare.json") == before);
  // an earlier snapshot is another root: a distance and residuals
  const auto early = run("compare " + quick().run.string() + " " + quick().rsml.string() + " --at-h 15 --out " + (d / "e").string());
  REQUIRE(early.code == 0);
  CHECK(jsonNumber(slurp(d / "e" / "compare.json"), "distance_mm") > 0.05);
}

TEST_CASE("compare: a 2D+t trace against the run at each observation time / timelapse.csv and compare.json's time_lapse") {
  if (!built()) return;
  const fs::path d = scratch("lapse");
  // RootSystemTracker's 2D+t test file (0, 6, 12, 18 h): its primary is 1, 2, 4, 6 mm long then
  const auto r = run("compare " + quick().run.string() + " " + kData + "rst_2dt.rsml --root 1/1.1 --quiet --out " + (d / "c").string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  std::ifstream in(d / "c" / "timelapse.csv");
  std::string line;
  std::getline(in, line);
  CHECK(line.rfind("time_h,snapshot_h,trace_length_mm,run_length_mm,", 0) == 0);
  const double hours[] = {0, 6, 12, 18}, lengths[] = {1, 2, 4, 6};
  double previous = 0;
  for (int k = 0; k < 4; ++k) {
    REQUIRE(std::getline(in, line));
    std::vector<double> v;
    std::size_t from = 0;
    while (from <= line.size()) {
      const std::size_t comma = std::min(line.find(',', from), line.size());
      v.push_back(std::stod(line.substr(from, comma - from)));
      from = comma + 1;
    }
    REQUIRE(v.size() == 11);
    CHECK(v[0] == hours[k]);
    CHECK(std::abs(v[1] - hours[k]) <= 0.5);              // the run's snapshot nearest that time
    ROOTSIM_CHECK_CLOSE(v[2], lengths[k], kRoundoff);            // the trace as it was then
    // the run's root then: 0.2 mm/h from about 1 mm (fig2b: rate_per_h 0.2, growth zone 1 mm)
    CHECK(v[3] == doctest::Approx(1.0 + 0.2 * v[1]).epsilon(0.1));
    CHECK(v[3] > previous);
    previous = v[3];
    CHECK(v[10] >= 0);
  }
  CHECK_FALSE(std::getline(in, line));
  const std::string json = slurp(d / "c" / "compare.json");
  CHECK(json.find("\"time_lapse\": [") != std::string::npos);
  // a trace of one time has none
  REQUIRE(run("compare " + quick().run.string() + " " + quick().rsml.string() + " --quiet --out " + (d / "one").string()).code == 0);
  CHECK_FALSE(fs::exists(d / "one" / "timelapse.csv"));
  CHECK(slurp(d / "one" / "compare.json").find("time_lapse") == std::string::npos);
}

TEST_CASE("fit: bad input exits 2 naming the flag, key or file, and writes nothing") {
  if (!built()) return;
  const fs::path d = scratch("bad");
  {
    std::ofstream f(d / "empty.rsml");
    f << "<?xml version=\"1.0\"?>\n<rsml>\n<metadata><unit>mm</unit></metadata>\n<scene>\n<plant id=\"1\"/>\n</scene>\n</rsml>\n";
  }
  {
    std::ofstream f(d / "pixels.rsml");
    f << "<?xml version=\"1.0\"?>\n<rsml>\n<metadata><unit>pixel</unit><resolution>1</resolution></metadata>\n<scene>\n"
         "<plant id=\"1\"><root id=\"1\"><geometry><polyline><point x=\"0\" y=\"0\"/><point x=\"0\" y=\"300\"/>"
         "</polyline></geometry></root></plant>\n</scene>\n</rsml>\n";
  }
  const std::string trace = quick().rsml.string(), scene = " --scene " + quick().scene.string();
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {trace + scene + " --free tropism.betta=0.1:0.3", "tropism.betta"},
      {trace + scene + " --free tropism.beta=-1:0.3", "outside the key's range"},
      {trace + scene + " --free tropism.beta=0.3:0.1", "LO must be below HI"},
      {trace + scene + " --free tropism.beta=0.1", "expected KEY=LO:HI"},
      {trace + scene + " --free tropism.beta=a:0.3", "is not a number"},
      {trace + scene + " --free tropism.sensing=0:1", "not a real number"},
      {trace + scene + " --free growth.rate_per_h=0.1:0.3", "changes how far the root grows"},
      {trace + scene + " --free tropism.beta=0.1:0.3,tropism.beta=0.1:0.2", "given twice"},
      {trace + scene + " --free tropism.beta=0.1:0.3 --budget 0", "--budget 0"},
      {trace + scene + " --free tropism.beta=0.1:0.3 --budget 5", "--budget 5: too small"},
      {trace + scene + " --free tropism.beta=0.1:0.3 --objective nice", "--objective nice"},
      {trace + scene + " --free tropism.beta=0.1:0.3 -j 0", "-j 0"},
      {(d / "empty.rsml").string() + scene + " --free tropism.beta=0.1:0.3", "empty.rsml:1: no root in the file"},
      {kData + "bad/one_point.rsml" + scene + " --free tropism.beta=0.1:0.3", "one_point.rsml:"},
      {kData + "bad/unknown_unit.rsml" + scene + " --free tropism.beta=0.1:0.3", "unknown_unit.rsml:"},
      {(d / "pixels.rsml").string() + scene + " --free tropism.beta=0.1:0.3", "give --px-per-mm"},
      {kData + "openalea_micrometer.rsml" + scene + " --free tropism.beta=0.1:0.3", "2 primary roots"},
      {kData + "openalea_micrometer.rsml --root nope" + scene + " --free tropism.beta=0.1:0.3", "--root nope: no such root"},
      {trace + " --sigma-mm 0" + scene + " --free tropism.beta=0.1:0.3", "--sigma-mm 0"},
      {(d / "missing.rsml").string() + scene + " --free tropism.beta=0.1:0.3", "missing.rsml: RSML file not found"},
  };
  for (const Case& c : cases) {
    const auto r = run("fit " + c.args + " --out " + (d / "out").string());
    CHECK_MESSAGE(r.code == 2, c.args << " -> " << r.out);
    CHECK_MESSAGE(r.out.find(c.expect) != std::string::npos, c.args << " -> " << r.out);
    CHECK_MESSAGE(!fs::exists(d / "out"), c.args);
  }
  // compare's own: a folder that is not a run, a trace of another root count
  const auto notRun = run("compare " + d.string() + " " + trace + " --out " + (d / "out").string());
  CHECK(notRun.code == 2);
  CHECK(notRun.out.find("not a run directory") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
}

TEST_CASE("fit: the files, the same bytes from a fresh fit, and a second call that reruns nothing") {
  if (!built()) return;
  const fs::path d = scratch("fit");
  // the quick root's own trace, fitted in beta and the intrinsic twist: the truth is (0.2, 0)
  const std::string args = "fit " + quick().rsml.string() + " --scene " + quick().scene.string() +
                           " --free tropism.beta=0.1:0.3,tropism.twist_r_tau=-0.2:0.2 --budget 60 -j 2 --quiet";
  const auto a = run(args + " --out " + (d / "a").string());
  REQUIRE_MESSAGE(a.code == 0, a.out);
  for (const char* f : {"fit.json", "evaluations.csv", "best.toml", "base.toml", "design.toml", "compare.png", "compare.pdf",
                        "landscape.png", "landscape.svg"})
    CHECK_MESSAGE(fs::exists(d / "a" / f), f);
  const std::string js = slurp(d / "a" / "fit.json");
  CHECK(js.find("\"tropism.beta\": {") != std::string::npos);
  CHECK(jsonNumber(js, "evaluations") <= 60);
  // the trace is the run itself: the fit finds it within its own uncertainty
  const double beta = jsonNumber(js, "value", js.find("\"tropism.beta\": {")), sb = jsonNumber(js, "sigma", js.find("\"tropism.beta\": {"));
  CHECK(std::abs(beta - 0.2) < 0.02);
  CHECK(std::abs(beta - 0.2) < 3 * sb);
  // the answer is never worse, by the objective, than any run the fit made
  const double answer = jsonNumber(js, "best_run_objective");
  CHECK(answer <= columnMin(slurp(d / "a" / "evaluations.csv"), "objective") * (1 + 1e-8) + 1e-12);
  // its goodness: the trace is a run of the model, so the model reproduces it
  const auto g = js.find("\"goodness\": {");
  REQUIRE(g != std::string::npos);
  CHECK(jsonString(js, "verdict", g) == "consistent");
  CHECK(jsonNumber(js, "p_value", g) >= 1e-3);
  CHECK(js.find("\"misfit\"") == std::string::npos);
  CHECK(a.out.find("goodness: chi2 ") != std::string::npos);
  // the fixed keys that shape the answer, the tilt first, in fit.json and beside the answer
  const std::string fixed = jsonObject(js, "scene_fixed");
  CHECK(fixed.find("\"plane.alpha_deg\": {") < fixed.find("\"growth.rate_per_h\": {"));
  CHECK(jsonString(fixed, "value") == "40.0");
  CHECK(jsonString(fixed, "source") == "scene");
  CHECK(fixed.find("\"tip_speed_mm_per_h\": {") != std::string::npos);
  CHECK(fixed.find("\"tropism.gamma\": {") != std::string::npos);
  CHECK(fixed.find("\"tropism.beta\"") == std::string::npos);  // a free key is not fixed
  // a key the scene file leaves out is the default's
  const auto cn = fixed.find("\"tropism.circumnutation_gain\": {");
  REQUIRE(cn != std::string::npos);
  CHECK(jsonString(fixed, "source", cn) == "default");
  CHECK(a.out.find("fixed: plane.alpha_deg = 40.0 (scene), growth.rate_per_h = ") != std::string::npos);
  // a fresh fit elsewhere: the same files, byte for byte
  REQUIRE(run(args + " --out " + (d / "b").string()).code == 0);
  CHECK(slurp(d / "b" / "fit.json") == js);
  CHECK(slurp(d / "b" / "evaluations.csv") == slurp(d / "a" / "evaluations.csv"));
  // a second call into a: every run is found complete, none runs again, the same result
  const auto before = runTimes(d / "a" / "runs");
  REQUIRE(run(args + " --out " + (d / "a").string()).code == 0);
  CHECK(runTimes(d / "a" / "runs") == before);
  CHECK(slurp(d / "a" / "fit.json") == js);
  // the same fit with any setting changed: refused before any work, the earlier fit left as it was
  std::string budget61 = args;
  budget61.replace(budget61.find("--budget 60"), 11, "--budget 61");
  for (const std::string& changed : {budget61, args + " --objective shape", args + " --sigma-mm 0.1"}) {
    INFO(changed);
    const auto differs = run(changed + " --out " + (d / "a").string());
    CHECK(differs.code == 2);
    CHECK(differs.out.find("holds a fit of another scene, trace or settings") != std::string::npos);
    CHECK(differs.out.find("pass --force") != std::string::npos);
    CHECK(slurp(d / "a" / "fit.json") == js);
  }
  {
    const std::string bounds = "fit " + quick().rsml.string() + " --scene " + quick().scene.string() +
                               " --free tropism.beta=0.1:0.35,tropism.twist_r_tau=-0.2:0.2 --budget 60 -j 2 --quiet";
    const std::string keys = "fit " + quick().rsml.string() + " --scene " + quick().scene.string() +
                             " --free tropism.beta=0.1:0.3 --budget 60 -j 2 --quiet";
    for (const std::string& other : {bounds, keys}) {
      const auto differs = run(other + " --out " + (d / "a").string());
      CHECK(differs.code == 2);
      CHECK(differs.out.find("holds a fit of another scene, trace or settings") != std::string::npos);
      CHECK(slurp(d / "a" / "fit.json") == js);
    }
  }
  // the start design is a sweep file: `rootsim sweep` finds every point complete
  const auto sw = run("sweep " + (d / "a" / "design.toml").string() + " --out " + (d / "a" / "runs").string());
  CHECK(sw.code == 0);
  CHECK(sw.out.find("sweep done: 0 ran") != std::string::npos);
  // another base scene in the same folder: refused, and started again with --force
  std::string other = slurp(quick().scene);
  other.replace(other.find("alpha_deg = 40"), 14, "alpha_deg = 30");
  std::ofstream(d / "other.toml") << other;
  const std::string otherArgs = "fit " + quick().rsml.string() + " --scene " + (d / "other.toml").string() +
                                " --free tropism.beta=0.1:0.3,tropism.twist_r_tau=-0.2:0.2 --budget 60 -j 2 --quiet --out " + (d / "a").string();
  const auto refused = run(otherArgs);
  CHECK(refused.code == 2);
  CHECK(refused.out.find("holds a fit of another scene, trace or settings") != std::string::npos);
  CHECK(slurp(d / "a" / "fit.json") == js);
  REQUIRE(run(otherArgs + " --force").code == 0);
  CHECK(slurp(d / "a" / "base.toml").find("alpha_deg = 30") != std::string::npos);
  CHECK(slurp(d / "a" / "fit.json") != js);
}

TEST_CASE("fit: a straight trace fitted by a waving model is poor and says what the model could not reproduce") {
  if (!built()) return;
  const fs::path d = scratch("straight");
  // a straight root 7 mm downhill, a point every 0.2 mm, in millimetres
  {
    std::ofstream f(d / "straight.rsml");
    f << "<?xml version=\"1.0\"?>\n<rsml>\n<metadata><unit>mm</unit><resolution>1</resolution></metadata>\n<scene>\n"
         "<plant id=\"1\"><root id=\"1\"><geometry><polyline>";
    for (int i = 0; i <= 35; ++i) f << "<point x=\"10\" y=\"" << 0.2 * i << "\"/>";
    f << "</polyline></geometry></root></plant>\n</scene>\n</rsml>\n";
  }
  // the quick waving scene (alpha 40): every run in the box waves
  const auto r = run("fit " + (d / "straight.rsml").string() + " --scene " + quick().scene.string() +
                     " --free tropism.beta=0.15:0.3 --objective shape --budget 40 -j 2 --quiet --out " + (d / "fit").string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  const std::string js = slurp(d / "fit" / "fit.json");
  const auto g = js.find("\"goodness\": {");
  REQUIRE(g != std::string::npos);
  CHECK(jsonString(js, "verdict", g) == "poor");
  CHECK(jsonNumber(js, "p_value", g) < 1e-3);
  CHECK(jsonNumber(js, "dof", g) == 15);  // 16 shape outputs, 1 free key
  // one line saying what differs and which fixed key to check
  const std::string said = "poor fit: the model with these free keys and this scene does not reproduce the trace: the trace is straight, every run waves";
  CHECK_MESSAGE(r.out.find(said) != std::string::npos, r.out);
  CHECK(r.out.find("check plane.alpha_deg (40.0, from the scene) against the plate's tilt, or free it") != std::string::npos);
  CHECK(jsonString(js, "misfit").find("the trace is straight, every run waves") != std::string::npos);
  // the answer is never worse than a run the fit made
  CHECK(jsonNumber(js, "best_run_objective") <= columnMin(slurp(d / "fit" / "evaluations.csv"), "objective") * (1 + 1e-8) + 1e-12);
}

TEST_CASE("fit: a tracer-degraded trace of a run fitted with beta free is consistent and covers beta") {
  if (!built()) return;
  const fs::path d = scratch("degraded");
  const fs::path trace = degradedTrace(d, 3);
  const auto r = run("fit " + trace.string() + " --px-per-mm 20 --scene " + quick().scene.string() +
                     " --free tropism.beta=0.15:0.3 --objective shape --budget 40 -j 2 --quiet --out " + (d / "fit").string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  const std::string js = slurp(d / "fit" / "fit.json");
  // the trace's uncertainty is its estimated noise (0.5 px of 0.05 mm, with the 0.1 px rounding), not a pixel
  CHECK(jsonString(js, "sigma_source") == "noise_mm");
  CHECK(jsonNumber(js, "sigma_mm") == doctest::Approx(0.025).epsilon(0.25));
  // the trace's smoothing, at which its runs were measured too
  CHECK(jsonNumber(js, "smoothing_mm") > 0.2);
  // the runs grow to the root's length, not to the noisy trace's (longer by the noise's zigzag): the run's own
  const double runMm = lengthOf(exportedPoints(quick().rsml));
  CHECK(jsonNumber(js, "trace_length_mm") - runMm > 0.05);
  CHECK(std::abs(jsonNumber(js, "root_length_mm") - runMm) < 0.02);
  const std::string best = jsonObject(jsonObject(js, "best"), "tropism.beta");
  const double beta = jsonNumber(best, "value"), sigma = jsonNumber(best, "sigma");
  CHECK_MESSAGE(std::abs(beta - 0.2) <= 2 * sigma, beta << " +- " << sigma);
  CHECK(std::abs(beta - 0.2) < 0.02);
  const auto g = js.find("\"goodness\": {");
  REQUIRE(g != std::string::npos);
  CHECK_MESSAGE(jsonString(js, "verdict", g) == "consistent", r.out);
  CHECK(jsonNumber(js, "dof", g) == 15);
  CHECK(js.find("\"misfit\"") == std::string::npos);
}

TEST_CASE("fit: a 2D+t trace is fitted at every observation time / beta and the growth rate recovered, a mismatched tip speed named") {
  if (!built()) return;
  const fs::path d = scratch("timelapse");
  const std::string trace = lapseTrace(d).string();
  // beta free (the run's 0.2): the default objective of a trace with times
  {
    const auto r = run("fit " + trace + " --scene " + quick().scene.string() + " --free tropism.beta=0.15:0.3 --budget 40 -j 2 --quiet --out " +
                       (d / "beta").string());
    REQUIRE_MESSAGE(r.code == 0, r.out);
    const std::string js = slurp(d / "beta" / "fit.json");
    CHECK(jsonString(js, "objective") == "timelapse");
    const std::string best = jsonObject(js, "best");
    const double beta = jsonNumber(best, "value"), sigma = jsonNumber(best, "sigma");
    CHECK_MESSAGE(std::abs(beta - 0.2) <= 2 * sigma, beta << " +- " << sigma);
    CHECK(sigma < 0.02);
    const auto g = js.find("\"goodness\": {");
    REQUIRE(g != std::string::npos);
    CHECK(jsonString(js, "verdict", g) == "consistent");
    // 7 observations (0 .. 30 h): length, tip lateral and downhill at each, the tip angle at the 6 where
    // the root is at least twice its span long (max(0.5 mm, 10 px of 0.05 mm) = 0.5 mm): from 5 h on (at
    // 0 h the root's 1 mm, its trace's every third node, falls just short); the last time's strongest wave
    CHECK(jsonNumber(js, "dof", g) == 7 * 3 + 6 + 2 - 1);
    CHECK(js.find("\"name\": \"wave_lambda_mm@30h\"") != std::string::npos);
    // the fixed growth beside the trace's own dL/dt: 0.2 mm/h both
    const std::string fixed = jsonObject(js, "scene_fixed");
    CHECK(jsonString(jsonObject(fixed, "tip_speed_mm_per_h"), "value") == "0.2");
    CHECK(std::stod(jsonString(jsonObject(fixed, "trace_growth_mm_per_h"), "value")) == doctest::Approx(0.2).epsilon(0.02));
    CHECK(js.find("growth_mismatch") == std::string::npos);
    // never worse than a run it made
    CHECK(jsonNumber(js, "best_run_objective") <= columnMin(slurp(d / "beta" / "evaluations.csv"), "objective") * (1 + 1e-8) + 1e-12);
  }
  // the growth rate free (the run's 0.2 per h): the time-lapse fixes it
  {
    const auto r = run("fit " + trace + " --scene " + quick().scene.string() + " --free growth.rate_per_h=0.12:0.3 --budget 40 -j 2 --quiet --out " +
                       (d / "rate").string());
    REQUIRE_MESSAGE(r.code == 0, r.out);
    const std::string best = jsonObject(jsonObject(slurp(d / "rate" / "fit.json"), "best"), "growth.rate_per_h");
    const double rate = jsonNumber(best, "value"), sigma = jsonNumber(best, "sigma");
    CHECK_MESSAGE(std::abs(rate - 0.2) <= 2 * sigma, rate << " +- " << sigma);
    CHECK(rate == doctest::Approx(0.2).epsilon(0.05));
    CHECK(jsonObject(slurp(d / "rate" / "fit.json"), "scene_fixed").find("trace_growth_mm_per_h") == std::string::npos);
  }
  // a scene whose tip speed is 1.5 times the trace's: named beside the verdict
  {
    std::string text = slurp(quick().scene);
    text.replace(text.find("rate_per_h = 0.2"), 16, "rate_per_h = 0.3");
    std::ofstream(d / "fast.toml") << text;
    const auto r = run("fit " + trace + " --scene " + (d / "fast.toml").string() + " --free tropism.beta=0.15:0.3 --budget 40 -j 2 --quiet --out " +
                       (d / "fast").string());
    REQUIRE_MESSAGE(r.code == 0, r.out);
    const auto said = r.out.find("the trace grows at ");
    REQUIRE_MESSAGE(said != std::string::npos, r.out);
    CHECK(std::stod(r.out.substr(said + 19)) == doctest::Approx(0.2).epsilon(0.03));
    CHECK_MESSAGE(r.out.find(" mm/h, the scene's tip speed is 0.3 mm/h (3", said) != std::string::npos, r.out);
    CHECK_MESSAGE(r.out.find(" % apart): check growth.rate_per_h or free it", said) != std::string::npos, r.out);
    CHECK(jsonString(slurp(d / "fast" / "fit.json"), "growth_mismatch").find("% apart") != std::string::npos);
  }
  // bad input: a trace of one time asked for a time-lapse; the rate free without one; steps free with one
  struct Case {
    std::string args, expect;
  };
  const std::string scene = " --scene " + quick().scene.string();
  const std::vector<Case> cases = {
      {quick().rsml.string() + scene + " --free tropism.beta=0.1:0.3 --objective timelapse", "--objective timelapse: "},
      {quick().rsml.string() + scene + " --free growth.rate_per_h=0.1:0.3", "(growth.rate_per_h can with --objective timelapse)"},
      {trace + scene + " --free growth.step_h=0.05:0.2", "growth.step_h changes the run's time steps"},
  };
  for (const Case& c : cases) {
    const auto r = run("fit " + c.args + " --out " + (d / "bad").string());
    CHECK_MESSAGE(r.code == 2, c.args << " -> " << r.out);
    CHECK_MESSAGE(r.out.find(c.expect) != std::string::npos, c.args << " -> " << r.out);
    CHECK_MESSAGE(!fs::exists(d / "bad"), c.args);
  }
  const auto one = run("fit " + quick().rsml.string() + scene + " --free tropism.beta=0.1:0.3 --objective timelapse --out " + (d / "bad").string());
  CHECK(one.out.find("has no observation times (a trace of one time)") != std::string::npos);
}

TEST_CASE("compare of a plate: each seedling paired with its nearest traced plant or by a sample sheet, one row per pair") {
  if (!built()) return;
  const fs::path d = scratch("plate");
  // two seedlings of different gains: a traced plant paired with the wrong seedling is another root
  {
    std::ofstream(d / "plate.toml") << "[root]\nelement_length_mm = 0.1\n[growth]\nsteps = 60\nstep_h = 0.1\n[tropism]\nbeta = 0.1\n"
                                       "[output]\nvtk = false\nevery_steps = 10\n[plate]\nwidth_mm = 40\nlength_mm = 30\n"
                                       "[[seedling]]\nname = \"a\"\nposition_mm = [10, 5]\n"
                                       "[[seedling]]\nname = \"b\"\nposition_mm = [30, 5]\nangle_deg = 20\n"
                                       "set = { \"tropism.beta\" = 0.4 }\n";
  }
  REQUIRE(run("run " + (d / "plate.toml").string() + " --out " + (d / "run").string() + " --quiet").code == 0);
  REQUIRE(run("export " + (d / "run").string() + " --rsml " + (d / "plate.rsml").string() + " --quiet").code == 0);
  // against its own export: each seedling with its own plant (the nearest seed), every distance 0
  const auto own = run("compare " + (d / "run").string() + " " + (d / "plate.rsml").string() + " --out " + (d / "c").string());
  REQUIRE_MESSAGE(own.code == 0, own.out);
  const std::string pairs = slurp(d / "c" / "pairs.csv");
  INFO(pairs);
  CHECK(pairs.rfind("seedling,plant,root,time_h,step,snapshot,distance_mm,frechet_mm,chi2,observables_used\n", 0) == 0);
  CHECK(pairs.find("\na,1 (a),") != std::string::npos);
  CHECK(pairs.find("\nb,2 (b),") != std::string::npos);
  const std::string js = slurp(d / "c" / "compare.json");
  for (std::size_t at = js.find("\"distance_mm\": "); at != std::string::npos; at = js.find("\"distance_mm\": ", at + 1))
    CHECK(std::stod(js.substr(at + 15)) < 1e-9);
  CHECK(jsonString(js, "paired_by").rfind("nearest seed", 0) == 0);
  const std::string csv = slurp(d / "c" / "compare.csv");
  CHECK(csv.rfind("seedling,plant,observable,unit,trace,sim,sigma,residual,used,how\n", 0) == 0);
  CHECK(csv.find("\nb,2 (b),length_mm,") != std::string::npos);
  for (const char* f : {"compare.pdf", "compare.svg", "compare.png"}) CHECK(fs::file_size(d / "c" / f) > 1000);
  // a sample sheet swapping them: each plant against the other seedling, a distance of millimetres
  std::ofstream(d / "swap.csv") << "plant,seedling,note\nb,a,x\n1,b,y\n";
  const auto swapped = run("compare " + (d / "run").string() + " " + (d / "plate.rsml").string() + " --groups " + (d / "swap.csv").string() +
                           " --out " + (d / "s").string() + " --quiet");
  REQUIRE_MESSAGE(swapped.code == 0, swapped.out);
  const std::string sp = slurp(d / "s" / "pairs.csv");
  CHECK(sp.find("\na,2 (b),") != std::string::npos);
  CHECK(sp.find("\nb,1 (a),") != std::string::npos);
  CHECK(jsonNumber(slurp(d / "s" / "compare.json"), "distance_mm") > 0.1);
  // a sheet naming a plant twice, or a seedling the run does not have: exit 2 naming the sheet's line
  std::ofstream(d / "twice.csv") << "plant,seedling\na,a\na,b\n";
  const auto twice = run("compare " + (d / "run").string() + " " + (d / "plate.rsml").string() + " --groups " + (d / "twice.csv").string() +
                         " --out " + (d / "t").string());
  CHECK(twice.code == 2);
  CHECK(twice.out.find("twice.csv:3: plant a named twice (first on line 2)") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "t"));
  std::ofstream(d / "none.csv") << "plant,seedling\na,zz\n";
  const auto none = run("compare " + (d / "run").string() + " " + (d / "plate.rsml").string() + " --groups " + (d / "none.csv").string() +
                        " --out " + (d / "n").string());
  CHECK(none.code == 2);
  CHECK(none.out.find("none.csv:2: seedling zz: not a seedling of the run (its seedlings: a, b)") != std::string::npos);
  // --groups of a run of one root
  const auto single = run("compare " + quick().run.string() + " " + quick().rsml.string() + " --groups " + (d / "swap.csv").string() +
                          " --out " + (d / "one").string());
  CHECK(single.code == 2);
  CHECK(single.out.find("--groups") != std::string::npos);
}
