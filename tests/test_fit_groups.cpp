// `rootsim fit PLATE.rsml --groups SHEET.csv` (src/analysis/fit_groups.cpp, docs/experiments.md "A plate by
// group") end to end: a synthetic plate of two genotypes traced as a scan (whole pixels, jitter) whose
// twist differs and whose beta does not; bad input (exit 2 naming the sheet's line, nothing written).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <algorithm>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace rootsim;
using rootsim::test::run;
using rootsim::test::slurp;

namespace {

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("fit_groups", name); }

// the base scene of every group's runs: a waving root at the quick resolution (0.1 mm elements, 0.1 h steps)
const char* const kBase =
    "[root]\nradius_mm = 0.1\ninitial_length_mm = 1.1\nelement_length_mm = 0.1\n"
    "[growth]\ngrowth_zone_mm = 1.0\nrate_per_h = 0.2\nstep_h = 0.1\n"
    "[tropism]\nbeta = 0.2\ngamma = 0.1\nsensing = \"local\"\n[plane]\nalpha_deg = 40\n[output]\nevery_steps = 50\n";

// a plate of three wild-type seedlings (twist 0) and three mutants (twist 0.05), beta 0.2 in both, each
// sown at its own angle (the seedling-to-seedling spread), grown to 15 mm
std::string plateScene() {
  std::string s = kBase;
  s.replace(s.find("step_h = 0.1\n"), 13, "step_h = 0.1\nsteps = 700\n");
  s += "vtk = false\n[plate]\nwidth_mm = 80\nlength_mm = 30\n";
  const char* names[] = {"w1", "w2", "w3", "m1", "m2", "m3"};
  const int angles[] = {-3, 2, 4, 3, -2, -4};
  for (int i = 0; i < 6; ++i) {
    s += "[[seedling]]\nname = \"" + std::string(names[i]) + "\"\nposition_mm = [" + std::to_string(5 + 11 * i) + ", 5]\nangle_deg = " +
         std::to_string(angles[i]) + "\n";
    if (i >= 3) s += "set = { \"tropism.twist_r_tau\" = 0.05 }\n";
  }
  return s;
}

// each plant's primary root of a plate's RSML export as a scan's tracer gives it: at 20 px/mm a point every
// 4 px along the root, each moved by Gaussian jitter of 0.5 px (seeded), snapped to whole pixels; the
// plants keep their ids and labels
void traceLikeAScan(const fs::path& exported, const fs::path& out, unsigned seed) {
  const std::string text = slurp(exported);
  std::mt19937 gen(seed);
  std::normal_distribution<double> jitter(0.0, 0.5);
  std::ofstream f(out);
  f << "<?xml version=\"1.0\"?>\n<rsml><metadata><unit>pixel</unit><resolution>1</resolution></metadata><scene>\n";
  for (std::size_t at = text.find("<plant id=\""); at != std::string::npos; at = text.find("<plant id=\"", at + 1)) {
    const std::size_t end = text.find("</plant>", at);
    const std::string head = text.substr(at, text.find('>', at) - at);
    const std::string id = head.substr(11, head.find('"', 11) - 11);
    const auto lab = head.find("label=\"");
    const std::string label = lab == std::string::npos ? "" : head.substr(lab + 7, head.find('"', lab + 7) - lab - 7);
    // the primary's points: the first polyline of the plant
    const std::size_t polyEnd = text.find("</polyline>", at);
    std::vector<std::pair<double, double>> p;
    for (std::size_t q = text.find("<point x=\"", at); q != std::string::npos && q < std::min(end, polyEnd); q = text.find("<point x=\"", q + 1))
      p.emplace_back(std::stod(text.substr(q + 10)), std::stod(text.substr(text.find(" y=\"", q) + 4)));
    REQUIRE(p.size() > 10);
    std::vector<double> s(1, 0.0);
    for (std::size_t i = 1; i < p.size(); ++i) s.push_back(s.back() + std::hypot(p[i].first - p[i - 1].first, p[i].second - p[i - 1].second));
    const int n = static_cast<int>(std::lround(s.back() / 0.2));
    f << "<plant id=\"" << id << "\" label=\"" << label << "\"><root id=\"" << id << ".1\"><geometry><polyline>\n";
    std::size_t j = 1;
    for (int k = 0; k <= n; ++k) {
      const double a = s.back() * k / n;
      while (j + 1 < s.size() && s[j] < a) ++j;
      const double w = (a - s[j - 1]) / (s[j] - s[j - 1]);
      const double x = p[j - 1].first + w * (p[j].first - p[j - 1].first), y = p[j - 1].second + w * (p[j].second - p[j - 1].second);
      f << "<point x=\"" << std::round(20 * x + jitter(gen)) << "\" y=\"" << std::round(20 * y + jitter(gen)) << "\"/>\n";
    }
    f << "</polyline></geometry></root></plant>\n";
  }
  f << "</scene></rsml>\n";
}

struct Plate {
  fs::path traced, base, sheet;
};
const Plate& plate() {
  static const Plate p = [] {
    Plate r;
    const fs::path d = scratch("plate");
    std::ofstream(d / "plate.toml") << plateScene();
    REQUIRE(run("run " + (d / "plate.toml").string() + " --out " + (d / "run").string() + " --quiet").code == 0);
    REQUIRE(run("export " + (d / "run").string() + " --rsml " + (d / "plate.rsml").string() + " --quiet").code == 0);
    r.traced = d / "traced.rsml";
    traceLikeAScan(d / "plate.rsml", r.traced, 1);
    r.base = d / "base.toml";
    std::ofstream(r.base) << kBase;
    r.sheet = d / "sheet.csv";
    // the mutants' sowing angles given (the sheet's angle_deg), the wild type's left to their traces' starts
    std::ofstream(r.sheet) << "plant,group,angle_deg\nw1,WT,\nw2,WT,\nw3,WT,\nm1,mut,3\nm2,mut,-2\nm3,mut,-4\n";
    return r;
  }();
  return p;
}

bool built() {
  const auto r = run("export /nonexistent-run --rsml /nonexistent-folder/x.rsml");
  if (r.out.find("built without") != std::string::npos) {
    test::skipCase("rootsim built without the app library: no export to make the plate's RSML");
    return false;
  }
  return true;
}

// the number after "key": from position `from`
double jsonNumber(const std::string& s, const std::string& key, std::size_t from = 0) {
  const auto at = s.find("\"" + key + "\": ", from);
  REQUIRE_MESSAGE(at != std::string::npos, key);
  return std::stod(s.substr(at + key.size() + 4));
}

}  // namespace

TEST_CASE("fit by group: bad input exits 2 naming the sheet's line or the flag, and writes nothing") {
  if (!built()) return;
  const fs::path d = scratch("bad");
  const std::string traced = plate().traced.string() + " --px-per-mm 20", scene = " --scene " + plate().base.string();
  const std::string free = " --free tropism.beta=0.1:0.3";
  auto sheet = [&](const std::string& name, const std::string& text) {
    std::ofstream(d / name) << text;
    return " --groups " + (d / name).string();
  };
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {traced + sheet("absent.csv", "plant,group\nw1,WT\nw2,WT\nw3,WT\nm1,mut\nm2,mut\nm3,mut\nm9,mut\n") + scene + free,
       "absent.csv:8: plant m9: not a plant of the trace (its plants: 1 (w1), 2 (w2)"},
      {traced + sheet("missing.csv", "plant,group\nw1,WT\nw2,WT\nm1,mut\nm2,mut\nm3,mut\n") + scene + free,
       "missing.csv: plant 3 (w3) of " + plate().traced.string() + " has no line; add \"3,GROUP\" for it"},
      {traced + sheet("one.csv", "plant,group\nw1,WT\nw2,WT\nw3,solo\nm1,mut\nm2,mut\nm3,mut\n") + scene + free,
       "one.csv:4: group solo has one seedling (w3); a group's fit needs at least two"},
      {traced + sheet("twice.csv", "plant,group\nw1,WT\nw1,WT\n") + scene + free, "twice.csv:3: plant w1 named twice (first on line 2)"},
      {traced + sheet("nocol.csv", "plant,genotype\nw1,WT\n") + scene + free, "nocol.csv:1: no column group"},
      {traced + sheet("empty.csv", "plant,group\nw1,\n") + scene + free, "empty.csv:2: plant w1: no group"},
      {traced + sheet("slash.csv", "plant,group\nw1,a/b\nw2,a/b\nw3,WT\nm1,WT\nm2,WT\nm3,WT\n") + scene + free, "slash.csv:2: group a/b: letters"},
      {traced + sheet("good.csv", "plant,group\nw1,WT\nw2,WT\nw3,WT\nm1,mut\nm2,mut\nm3,mut\n") + scene + " --free plate.width_mm=10:20",
       "--free plate.width_mm=10:20: plate.width_mm is a plate's key"},
      {traced + " --groups " + (d / "good.csv").string() + scene + " --free angle_deg=-5:5", "angle_deg is a plate's key"},
      {traced + " --groups " + (d / "good.csv").string() + scene + " --free set_point_drift_h=5:50",
       "set_point_drift_h is a plate's key"},
      {traced + " --groups " + (d / "good.csv").string() + scene + " --free plane.alpha_deg=30:50", "the plate's tilt, the same for every group"},
      {traced + " --groups " + (d / "good.csv").string() + scene + " --free root.initial_angle_deg=-5:5",
       "root.initial_angle_deg is each seedling's own"},
      {traced + sheet("angle.csv", "plant,group,angle_deg\nw1,WT,3\nw2,WT,north\nw3,WT,\nm1,mut,\nm2,mut,\nm3,mut,\n") + scene + free,
       "angle.csv:3: angle_deg north: expected the plant's sowing angle in degrees"},
      {traced + sheet("angle90.csv", "plant,group,angle_deg\nw1,WT,3\nw2,WT,95\nw3,WT,\nm1,mut,\nm2,mut,\nm3,mut,\n") + scene + free,
       "angle90.csv:3: angle_deg 95: expected"},
      {traced + " --groups " + (d / "good.csv").string() + scene + free + " --objective shape", "--objective shape: a fit by group"},
      {traced + " --groups " + (d / "nothere.csv").string() + scene + free, "nothere.csv: cannot be read"},
      {traced + " --groups " + (d / "good.csv").string() + scene + free + " --budget 5", "--budget 5: too small"},
      {traced + " " + plate().traced.string() + scene + free, "several files are a plate fitted by group; give --groups"},
  };
  for (const Case& c : cases) {
    const auto r = run("fit " + c.args + " --out " + (d / "out").string());
    CHECK_MESSAGE(r.code == 2, c.args << " -> " << r.out);
    CHECK_MESSAGE(r.out.find(c.expect) != std::string::npos, c.args << " -> " << r.out);
    CHECK_MESSAGE(r.out.find("rootsim: error: ") != std::string::npos, r.out);
    CHECK_MESSAGE(!fs::exists(d / "out"), c.args);
  }
}

TEST_CASE("fit by group: two genotypes differing in the twist / the difference recovered, the equal beta not called different") {
  if (!built()) return;
  const fs::path d = scratch("fit");
  const std::string args = "fit " + plate().traced.string() + " --px-per-mm 20 --groups " + plate().sheet.string() + " --scene " +
                           plate().base.string() + " --free tropism.beta=0.1:0.3,tropism.twist_r_tau=-0.05:0.1 --budget 40 -j 2 --quiet --out " +
                           (d / "g").string();
  const auto r = run(args);
  REQUIRE_MESSAGE(r.code == 0, r.out);
  INFO(r.out);
  for (const char* f : {"fit.json", "groups/WT/fit.json", "groups/mut/fit.json", "groups/WT/evaluations.csv", "groups/mut/best.toml",
                        "keys.png", "keys.svg", "keys.pdf", "compare_WT.png", "compare_mut.png", "compare_mut.pdf"})
    CHECK_MESSAGE(fs::exists(d / "g" / f), f);
  const std::string js = slurp(d / "g" / "fit.json");
  INFO(js);
  // each seedling's own answer (its best run of its group's): every mutant's twist above every wild type's;
  // its runs sown at the sheet's angle, else at its trace's start (within the few degrees a scan's pixels
  // and the bend of its growth zone allow)
  const std::map<std::string, double> sown = {{"w1", -3}, {"w2", 2}, {"w3", 4}, {"m1", 3}, {"m2", -2}, {"m3", -4}};
  double wtMax = -1, mutMin = 1;
  // (named, not a structured binding: doctest's assertion macros are lambdas, which clang does not let
  // capture a binding)
  for (const auto& sowing : sown) {
    const std::string& plant = sowing.first;
    const double angle = sowing.second;
    const auto at = js.find("\"plant\": \"" + plant + "\"");
    REQUIRE_MESSAGE(at != std::string::npos, plant);
    const double twistOwn = jsonNumber(js, "tropism.twist_r_tau", at);
    (plant[0] == 'm' ? mutMin : wtMax) = plant[0] == 'm' ? std::min(mutMin, twistOwn) : std::max(wtMax, twistOwn);
    const double deg = jsonNumber(js, "sowing_angle_deg", at);
    if (plant[0] == 'm')
      CHECK(deg == angle);
    else
      CHECK_MESSAGE(std::abs(deg - angle) < 6.0, plant << " " << deg);
  }
  CHECK(mutMin > wtMax);
  // a run per sowing angle: the design's sweep has the mutants' three angles
  CHECK(slurp(d / "g" / "groups" / "mut" / "design.toml").find("\"root.initial_angle_deg\" = [3, -2, -4]") != std::string::npos);
  // the contrasts: WT - mut, each key
  const auto twist = js.find("\"key\": \"tropism.twist_r_tau\"");
  const auto beta = js.find("\"key\": \"tropism.beta\"", js.find("\"contrasts\""));
  REQUIRE(twist != std::string::npos);
  REQUIRE(beta != std::string::npos);
  {
    // [A, B]: WT before mut (whatever the layout of the array)
    const auto open = js.find("\"groups\": [", twist);
    REQUIRE(open != std::string::npos);
    const std::string pair = js.substr(open, js.find(']', open) - open);
    CHECK(pair.find("\"WT\"") != std::string::npos);
    CHECK(pair.find("\"WT\"") < pair.find("\"mut\""));
  }
  // the truth: twist WT - mut = -0.05, found within 20 % and with p < 0.01
  const double diff = jsonNumber(js, "difference", twist), sigma = jsonNumber(js, "sigma", twist), p = jsonNumber(js, "p_value", twist);
  CHECK(std::abs(diff + 0.05) < 0.2 * 0.05);
  CHECK(sigma > 0);
  CHECK(p < 0.01);
  // beta equal in both: not called different
  CHECK(jsonNumber(js, "p_value", beta) > 0.05);
  // each group's answer and goodness: the model reproduces its seedlings
  for (const char* g : {"\"WT\": {", "\"mut\": {"}) {
    const auto at = js.find(g);
    REQUIRE(at != std::string::npos);
    CHECK(js.find("\"verdict\": \"consistent\"", at) != std::string::npos);
    CHECK(jsonNumber(js, "seedlings", at) == 3);
  }
  // the goodness names the covariance its chi-square was computed against: the group mean's, with the
  // seedlings' scatter, not a trace's uncertainty alone (on stdout, in fit.json and in each group's own)
  CHECK(r.out.find("dof against the group mean's covariance at the answer (its seedlings' residuals against a surface of their own runs' "
                   "outputs: their scatter / n") != std::string::npos);
  CHECK(r.out.find("uncertainty alone") == std::string::npos);
  CHECK(js.find("\"against\": \"the answer's own run against the group mean's covariance") != std::string::npos);
  CHECK(slurp(d / "g" / "groups" / "WT" / "fit.json").find("against the group mean's covariance") != std::string::npos);
  // the keys' picture: the groups on a categorical axis, named at their columns, no numeric ticks between them
  {
    const auto keysText = test::runBinary("pdftotext", "'" + (d / "g" / "keys.pdf").string() + "' -");
    REQUIRE_MESSAGE(keysText.code == 0, keysText.out);
    std::vector<std::string> lines;
    std::istringstream in(keysText.out);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    const auto has = [&lines](const std::string& l) { return std::find(lines.begin(), lines.end(), l) != lines.end(); };
    CHECK_MESSAGE(has("WT"), keysText.out);
    CHECK_MESSAGE(has("mut"), keysText.out);
    // the old numeric axis's ticks (the groups at 0 and 1 on -0.5 .. 1.5) and its key in the label
    for (const char* t : {"-0.5", "\u22120.5", "1.5"}) CHECK_MESSAGE(!has(t), t << ": " << keysText.out);
    CHECK(keysText.out.find("group (0") == std::string::npos);
  }
  // the table on stdout
  CHECK(r.out.find("WT - mut: tropism.beta ") != std::string::npos);
  CHECK(r.out.find("; tropism.twist_r_tau -0.0") != std::string::npos);
  CHECK(r.out.find(", p < 0.001") != std::string::npos);
  // a second call finds every run complete: the same answer, the same bytes
  const auto again = run(args);
  REQUIRE_MESSAGE(again.code == 0, again.out);
  CHECK(slurp(d / "g" / "fit.json") == js);
}

TEST_CASE("fit by group: --design-only writes each group's sweep file, rootsim sweep runs it in two shards, the fit finds those runs") {
  if (!built()) return;
  const fs::path d = scratch("shards");
  const fs::path out = d / "g";
  const std::string args = "fit " + plate().traced.string() + " --px-per-mm 20 --groups " + plate().sheet.string() + " --scene " +
                           plate().base.string() + " --free tropism.twist_r_tau=-0.05:0.1 --budget 17 -j 2 --quiet --out " + out.string();
  const auto design = run(args + " --design-only");
  REQUIRE_MESSAGE(design.code == 0, design.out);
  CHECK(design.out.find("rootsim sweep " + (out / "groups" / "WT" / "design.toml").string() + " --out " +
                        (out / "groups" / "WT" / "runs").string() + " [--shard K/N]") != std::string::npos);
  CHECK(design.out.find("then this fit again without --design-only") != std::string::npos);
  // nothing run, no answer
  CHECK_FALSE(fs::exists(out / "fit.json"));
  CHECK_FALSE(fs::exists(out / "groups" / "WT" / "runs"));
  // the cluster's part: each group's design in two shards
  for (const char* g : {"WT", "mut"})
    for (const char* shard : {"1/2", "2/2"}) {
      const auto s = run("sweep " + (out / "groups" / g / "design.toml").string() + " --out " + (out / "groups" / g / "runs").string() +
                         " --shard " + shard + " -j 2 --quiet");
      REQUIRE_MESSAGE(s.code == 0, g << " " << shard << ": " << s.out);
    }
  std::map<std::string, fs::file_time_type> made;
  for (const char* g : {"WT", "mut"})
    for (const auto& e : fs::directory_iterator(out / "groups" / g / "runs"))
      if (fs::exists(e.path() / "scene.toml")) made[e.path().string()] = fs::last_write_time(e.path() / "scene.toml");
  // the mutants' design: 3 sowing angles of each point of the twist's levels
  CHECK(made.size() >= 6);
  const auto fit = run(args);
  REQUIRE_MESSAGE(fit.code == 0, fit.out);
  CHECK(fs::exists(out / "fit.json"));
  CHECK(fs::exists(out / "keys.png"));
  // every run the shards made is the fit's: found complete, not run again
  for (const auto& m : made) CHECK_MESSAGE(fs::last_write_time(fs::path(m.first) / "scene.toml") == m.second, m.first);
  const std::string csv = slurp(out / "groups" / "mut" / "evaluations.csv");
  CHECK(csv.find(",design,") != std::string::npos);
}
