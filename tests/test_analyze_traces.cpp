// `rootsim analyze` (src/app/analyze_traces.cpp, docs/experiments.md) end to end: a run exported to RSML
// gives the numbers of its own summary.json; a SmartRoot-style plate with laterals (orders, parents,
// lengths, insertion angles in closed form); pixel units; growth rates across files; --downhill; bad
// input (exit 2, nothing written); the write rule
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "rootsim/csv.hpp"
#include "rootsim/rsml.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace rootsim;
using rootsim::test::run;
using rootsim::test::slurp;

namespace {

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("analyze", name); }
const std::string kData = std::string(ROOTSIM_SOURCE_DIR) + "/tests/data/rsml/";

// one short fig2b run (300 growth steps: 3 lateral peaks), made once
const fs::path& shortRun() {
  static const fs::path dir = [] {
    const fs::path d = scratch("run") / "wave";
    const auto r = run("run " + test::kScene + " --set growth.steps=600 --out " + d.string() + " --quiet");
    REQUIRE(r.code == 0);
    return d;
  }();
  return dir;
}

bool analyzeBuilt() {
  const auto r = run("analyze " + kData + "smartroot_pixels.rsml --out /nonexistent-folder/x");
  if (r.out.find("built without") != std::string::npos) {
    test::skipCase("rootsim built without the app library: no analyze command");
    return false;
  }
  return true;
}

// analysis.csv as rows of name -> cell text
std::vector<std::map<std::string, std::string>> readRows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> names = splitCommas(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = splitCommas(line);
    REQUIRE(cells.size() == names.size());
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < names.size(); ++i) row[names[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}
double number(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  REQUIRE(it != row.end());
  return it->second.empty() ? std::nan("") : std::stod(it->second);
}

// a summary.json number (the file's "key": value lines)
double summaryNumber(const fs::path& json, const std::string& key) {
  const std::string s = slurp(json);
  const auto at = s.find("\"" + key + "\": ");
  REQUIRE(at != std::string::npos);
  return std::stod(s.substr(at + key.size() + 4));
}
std::string summaryText(const fs::path& json, const std::string& key) {
  const std::string s = slurp(json);
  const auto at = s.find("\"" + key + "\": \"");
  REQUIRE(at != std::string::npos);
  const auto b = at + key.size() + 5;
  return s.substr(b, s.find('"', b) - b);
}

double deg(double rad) { return rad * 180.0 / std::numbers::pi; }

}  // namespace

TEST_CASE("analyze: a run exported to RSML gives the observables of the run's summary.json") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("own");
  REQUIRE(run("export " + shortRun().string() + " --rsml " + (d / "wave.rsml").string() + " --quiet").code == 0);
  const auto r = run("analyze " + (d / "wave.rsml").string() + " --out " + (d / "an").string());
  REQUIRE(r.code == 0);
  CHECK(r.out.find("wave.rsml 1/1: waving") != std::string::npos);  // the summary line on stdout
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 1);
  const auto& row = rows[0];
  const fs::path sj = shortRun() / "summary.json";
  CHECK(row.at("pattern") == summaryText(sj, "pattern"));
  CHECK(number(row, "lateral_peaks") == summaryNumber(sj, "lateral_peaks"));
  CHECK(number(row, "lateral_peaks") >= 3);
  for (const char* k : {"wavelength_mm", "amplitude_mm", "amplitude_half_mm", "max_kappa_per_mm", "theta_min_deg", "theta_max_deg"})
    CHECK_MESSAGE(number(row, k) == doctest::Approx(summaryNumber(sj, k)).epsilon(1e-9), k);
  CHECK(number(row, "skew_deg") == doctest::Approx(summaryNumber(sj, "skew_deg")).epsilon(1e-9).scale(1.0));
  CHECK(number(row, "time_h") == 30);
  CHECK(number(row, "ds_mm") == 0);           // a rootsim file: the run's own nodes
  CHECK(number(row, "exclude_tip_mm") == 1);  // its growth.growth_zone_mm
  CHECK(row.at("radius_source") == "root.radius_mm");
  // the length is the current arc length of the centreline (the run's length_mm is its rest length)
  CHECK(number(row, "length_mm") == doctest::Approx(summaryNumber(sj, "length_mm")).epsilon(1e-4));
  // analysis.json holds the same row
  const std::string js = slurp(d / "an" / "analysis.json");
  CHECK(js.find("\"roots\": [") != std::string::npos);
  CHECK(js.find("\"pattern\": \"waving\"") != std::string::npos);
  CHECK(js.find("rootsim-output") != std::string::npos);
}

TEST_CASE("analyze: a SmartRoot-style plate / orders, parents, lengths and insertion angles in closed form") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("smartroot");
  const auto r = run("analyze " + kData + "smartroot_pixels.rsml --out " + (d / "an").string());
  REQUIRE(r.code == 0);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 4);
  // unit cm at 100 px/cm: 1 file unit = 0.1 mm
  const double u = 0.1;
  CHECK(rows[0].at("root") == "r1");
  CHECK(rows[0].at("parent").empty());
  CHECK(number(rows[0], "order") == 0);
  const double primary = (std::hypot(2, 100) + std::hypot(4, 100) + std::hypot(7, 100) + std::hypot(5, 100)) * u;
  CHECK(number(rows[0], "length_mm") == doctest::Approx(primary).epsilon(1e-12));
  CHECK(number(rows[0], "chord_mm") == doctest::Approx(400 * u).epsilon(1e-12));
  CHECK(number(rows[0], "tortuosity") == doctest::Approx(primary / (400 * u)).epsilon(1e-12));
  CHECK(number(rows[0], "skew_base_tip_deg") == doctest::Approx(0.0));
  // the diameter function (in pixels: 4.0, 4.0, 3.5, 3.0, 2.5) sets the radius: half the median, in mm
  CHECK(rows[0].at("radius_source") == "diameter");
  CHECK(number(rows[0], "radius_mm") == doctest::Approx(0.5 * 3.5 * u));
  CHECK(rows[1].at("root") == "r1.1");
  CHECK(rows[1].at("parent") == "r1");
  CHECK(number(rows[1], "order") == 1);
  CHECK(rows[2].at("root") == "r1.1.1");
  CHECK(rows[2].at("parent") == "r1.1");
  CHECK(number(rows[2], "order") == 2);
  CHECK(rows[3].at("parent") == "r1");
  // lat_2 leaves the parent's vertex (505, 400) towards (440, 430); the parent's direction there over
  // +-0.5 mm (5 px) runs from 5 px back on the segment from (498, 300) to 5 px on towards (500, 500)
  auto unit = [](double x, double y) { const double l = std::hypot(x, y); return std::array<double, 2>{x / l, y / l}; };
  const auto inA = unit(7, 100), outA = unit(-5, 100);
  const double px0 = 505 - 5 * inA[0], py0 = 400 - 5 * inA[1], px1 = 505 + 5 * outA[0], py1 = 400 + 5 * outA[1];
  // the lateral over its first 0.5 mm (5 px) keeps the direction of its first segment
  const auto pd = unit(px1 - px0, py1 - py0), ld = unit(-65, 30);
  CHECK(number(rows[3], "insertion_deg") == doctest::Approx(deg(std::acos(pd[0] * ld[0] + pd[1] * ld[1]))).epsilon(1e-9));
  // the lateral heads towards -x, the primary's lateral direction (+x): a negative skew from downhill...
  // as theta (counter-clockwise seen from the plate's normal, the viewer of the scan)
  CHECK(number(rows[3], "skew_base_tip_deg") < -45);
  CHECK(number(rows[1], "skew_base_tip_deg") > 45);
  // no time in the file: no growth rate
  CHECK(rows[0].at("time_h").empty());
  CHECK(rows[0].at("growth_rate_mm_per_h").empty());
}

TEST_CASE("analyze: pixel units need --px-per-mm - and --downhill -y reads a plate scanned upside down") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("pixels");
  auto file = [&](const std::string& name, double sign) {
    std::ofstream f(d / name);
    f << "<?xml version=\"1.0\"?>\n<rsml>\n<metadata><version>1</version><unit>pixel</unit><resolution>1</resolution></metadata>\n"
         "<scene><plant id=\"a\"><root id=\"r\"><geometry><polyline>\n";
    for (int i = 0; i <= 40; ++i)  // 20 px/mm: 2 mm down, drifting 0.5 mm to +x
      f << "<point x=\"" << sign * (100 + 0.25 * i) << "\" y=\"" << sign * (50 + i) << "\"/>\n";
    f << "</polyline></geometry></root></plant></scene>\n</rsml>\n";
  };
  file("up.rsml", 1);
  file("down.rsml", -1);
  const auto bad = run("analyze " + (d / "up.rsml").string() + " --out " + (d / "x").string());
  CHECK(bad.code == 2);
  CHECK(bad.out.find("up.rsml: its unit is pixel") != std::string::npos);
  CHECK(bad.out.find("--px-per-mm") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "x"));
  REQUIRE(run("analyze " + (d / "up.rsml").string() + " --px-per-mm 20 --out " + (d / "up").string()).code == 0);
  REQUIRE(run("analyze " + (d / "down.rsml").string() + " --px-per-mm 20 --downhill -y --out " + (d / "down").string()).code == 0);
  const auto up = readRows(d / "up" / "analysis.csv"), down = readRows(d / "down" / "analysis.csv");
  CHECK(number(up[0], "length_mm") == doctest::Approx(std::hypot(10, 40) / 20).epsilon(1e-12));
  CHECK(std::abs(number(up[0], "skew_base_tip_deg")) == doctest::Approx(deg(std::atan(0.25))).epsilon(1e-12));
  CHECK(number(down[0], "skew_base_tip_deg") == doctest::Approx(number(up[0], "skew_base_tip_deg")).epsilon(1e-12));
  CHECK(number(down[0], "length_mm") == doctest::Approx(number(up[0], "length_mm")).epsilon(1e-12));
  // downhill along +x (90 degrees from +y): the same trace now heads mostly sideways
  REQUIRE(run("analyze " + (d / "up.rsml").string() + " --px-per-mm 20 --downhill 90 --out " + (d / "side").string()).code == 0);
  const auto side = readRows(d / "side" / "analysis.csv");
  CHECK(std::abs(number(side[0], "skew_base_tip_deg")) == doctest::Approx(90 - deg(std::atan(0.25))).epsilon(1e-9));
  // --px-per-mm on a file in millimetres is an error, not a silent rescale
  const auto mm = run("analyze " + kData + "openalea_micrometer.rsml --px-per-mm 20 --out " + (d / "y").string());
  CHECK(mm.code == 2);
  CHECK(mm.out.find("not pixels") != std::string::npos);
}

TEST_CASE("analyze: growth rates from exports of one run at two times, and from --times") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("rates");
  REQUIRE(run("export " + shortRun().string() + " --rsml " + (d / "t10.rsml").string() + " --at-h 10 --quiet").code == 0);
  REQUIRE(run("export " + shortRun().string() + " --rsml " + (d / "t20.rsml").string() + " --at-h 20 --quiet").code == 0);
  REQUIRE(run("analyze " + (d / "t20.rsml").string() + " " + (d / "t10.rsml").string() + " --out " + (d / "an").string()).code == 0);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 2);
  CHECK(number(rows[0], "time_h") == 20);
  CHECK(number(rows[1], "time_h") == 10);
  CHECK(std::isnan(number(rows[1], "growth_rate_mm_per_h")));
  const double rate = (number(rows[0], "length_mm") - number(rows[1], "length_mm")) / 10;
  CHECK(number(rows[0], "growth_rate_mm_per_h") == doctest::Approx(rate).epsilon(1e-12));
  // the model's growth: rate_per_h * Lgz = 0.2 mm/h once the zone is full (stretch aside)
  CHECK(rate == doctest::Approx(0.2).epsilon(1e-3));
  // --times overrides the files' own times
  REQUIRE(run("analyze " + (d / "t10.rsml").string() + " " + (d / "t20.rsml").string() + " --times 0,5 --out " + (d / "an2").string()).code == 0);
  const auto r2 = readRows(d / "an2" / "analysis.csv");
  CHECK(number(r2[1], "growth_rate_mm_per_h") == doctest::Approx(2 * rate).epsilon(1e-12));
  const auto bad = run("analyze " + (d / "t10.rsml").string() + " --times 1,2 --out " + (d / "an3").string());
  CHECK(bad.code == 2);
  CHECK(bad.out.find("--times 1,2: 2 time(s) for 1 file(s)") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "an3"));
}

TEST_CASE("analyze: bad input exits 2 naming the file and line or the flag, and writes nothing") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("bad");
  {
    std::ofstream f(d / "empty.rsml");
    f << "<?xml version=\"1.0\"?>\n<rsml>\n<metadata><unit>mm</unit></metadata>\n<scene>\n<plant id=\"1\"/>\n</scene>\n</rsml>\n";
  }
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {(d / "empty.rsml").string(), "empty.rsml:1: no root in the file"},
      {kData + "bad/one_point.rsml", "one_point.rsml:"},
      {kData + "bad/unknown_unit.rsml", "unknown_unit.rsml:"},
      {kData + "bad/malformed.rsml", "malformed.rsml:"},
      {(d / "missing.rsml").string(), "missing.rsml: RSML file not found"},
      {kData + "smartroot_pixels.rsml --downhill sideways", "--downhill sideways"},
      {kData + "smartroot_pixels.rsml --ds-mm -1", "--ds-mm -1: expected a finite number in [0, 10] mm"},
      {kData + "smartroot_pixels.rsml --radius-mm 0", "--radius-mm 0: expected a finite number in (0, 100] mm"},
      {kData + "smartroot_pixels.rsml --exclude-tip-mm -2", "--exclude-tip-mm -2"},
  };
  for (const Case& c : cases) {
    const auto r = run("analyze " + c.args + " --out " + (d / "out").string());
    CHECK_MESSAGE(r.code == 2, c.args);
    CHECK_MESSAGE(r.out.find(c.expect) != std::string::npos, c.args << " -> " << r.out);
    CHECK_MESSAGE(!fs::exists(d / "out"), c.args);
  }
}

TEST_CASE("analyze: the write rule / a user's folder is never replaced, rootsim's own only with --force") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("rule");
  fs::create_directories(d / "mine");
  { std::ofstream(d / "mine" / "notes.txt") << "a user's notes"; }
  const std::string in = kData + "smartroot_pixels.rsml";
  for (const char* force : {"", " --force"}) {
    const auto r = run("analyze " + in + " --out " + (d / "mine").string() + force);
    CHECK(r.code == 2);
    CHECK(slurp(d / "mine" / "notes.txt") == "a user's notes");
  }
  REQUIRE(run("analyze " + in + " --out " + (d / "an").string()).code == 0);
  const auto again = run("analyze " + in + " --out " + (d / "an").string());
  CHECK(again.code == 2);
  CHECK(again.out.find("--force") != std::string::npos);
  const std::string before = slurp(d / "an" / "analysis.csv");
  REQUIRE(run("analyze " + in + " --out " + (d / "an").string() + " --force").code == 0);
  CHECK(slurp(d / "an" / "analysis.csv") == before);   // same input, same bytes
  // the input is never an output
  CHECK(run("analyze " + in + " --out " + in).code == 2);
}

TEST_CASE("analyze: work sized by a trace is counted against its cap before it is done; numbers and hints are checked") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("bounds");
  auto write = [&](const std::string& name, const std::string& unit, const std::string& props, const std::string& points) {
    std::ofstream(d / name) << "<?xml version=\"1.0\"?>\n<rsml><metadata><version>1</version><unit>" << unit
                            << "</unit><resolution>1</resolution></metadata>\n<scene>" << props
                            << "<plant id=\"p\"><root id=\"r\"><geometry><polyline>" << points
                            << "</polyline></geometry></root></plant></scene></rsml>\n";
  };
  // a 300-byte file of one root 999 999 mm long: 2e7 points at 0.05 mm
  write("long.rsml", "mm", "", "<point x=\"0\" y=\"0\"/><point x=\"0\" y=\"999999\"/>");
  const std::string bend = "<point x=\"0\" y=\"0\"/><point x=\"0\" y=\"50\"/><point x=\"10\" y=\"90\"/>";
  write("px.rsml", "pixel", "", bend);
  write("radius.rsml", "mm", "<properties><root.radius_mm value=\"-1\"/></properties>", bend);
  write("zone.rsml", "mm", "<properties><growth.growth_zone_mm value=\"1e300\"/></properties>", bend);
  struct Case {
    std::string args, expect;
  };
  const std::string px = (d / "px.rsml").string();
  const std::vector<Case> cases = {
      {(d / "long.rsml").string(),
       "long.rsml:3: root r (999999 mm long, resampled every 0.05 mm): would make 19999980 points, more than the cap of 1000000"},
      {px + " --px-per-mm 1 --ds-mm 1e-12", "--ds-mm 1e-12: "},
      {px + " --px-per-mm 1e-300", "--px-per-mm 1e-300: expected a finite number in [0.01, 1e+05] px/mm"},
      {px + " --px-per-mm 1e-4", "--px-per-mm 1e-04: expected a finite number in [0.01, 1e+05] px/mm"},
      {px + " --px-per-mm nan", "--px-per-mm nan: expected a finite number"},
      {px + " --px-per-mm 1 --radius-mm inf", "--radius-mm inf: expected a finite number in (0, 100] mm"},
      {px + " --px-per-mm 1 --exclude-tip-mm nan", "--exclude-tip-mm nan: expected a finite number in [0, 1000] mm"},
      {(d / "radius.rsml").string(), "radius.rsml: property root.radius_mm = -1: the scene key must be in (0, 100] (got -1); give --radius-mm"},
      {(d / "zone.rsml").string(), "zone.rsml: property growth.growth_zone_mm = 1e300: the scene key must be in (0, 1000]"},
  };
  for (const Case& c : cases) {
    const auto r = run("analyze " + c.args + " --out " + (d / "out").string());
    CHECK_MESSAGE(r.code == 2, c.args);
    CHECK_MESSAGE(r.out.find("rootsim: error: ") == 0, c.args << " -> " << r.out);
    CHECK_MESSAGE(r.out.find(c.expect) != std::string::npos, c.args << " -> " << r.out);
    CHECK_MESSAGE(test::oneLine(r.out.substr(0, r.out.size() - 1)), c.args);
    CHECK_MESSAGE(!fs::exists(d / "out"), c.args);
  }
  // a flag replaces a bad hint: the file's radius is not used when --radius-mm is given
  CHECK(run("analyze " + (d / "radius.rsml").string() + " --radius-mm 0.1 --out " + (d / "given").string() + " --quiet").code == 0);
  // compare reads the trace through the same check (the long root: refused before its resampling)
  const auto c = run("compare " + shortRun().string() + " " + (d / "long.rsml").string() + " --out " + (d / "cmp").string());
  CHECK(c.code == 2);
  CHECK(c.out.find("more than the cap of 1000000") != std::string::npos);
  CHECK(!fs::exists(d / "cmp"));
  const auto at = run("compare " + shortRun().string() + " " + px + " --px-per-mm 20 --at-h nan --out " + (d / "cmp").string());
  CHECK(at.code == 2);
  CHECK(at.out.find("rootsim: error: --at-h nan: expected a finite number in [0, 1e+06] h") == 0);
  CHECK(!fs::exists(d / "cmp"));
}
