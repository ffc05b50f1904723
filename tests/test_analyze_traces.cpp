// `rootsim analyze` (src/analysis/analyze_traces.cpp, docs/experiments.md) end to end: a run exported to RSML
// gives the numbers of its own summary.json; a SmartRoot-style plate with laterals (orders, parents,
// lengths, insertion angles in closed form); pixel units; growth rates across files; --downhill; bad
// input (exit 2, nothing written); the write rule
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <set>
#include <numbers>
#include <string>
#include <vector>

#include "rootsim/csv.hpp"
#include "rootsim/rsml.hpp"
#include "test_support.hpp"

using rootsim::test::kRoundoff;

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
  for (const char* k : {"max_kappa_per_mm", "theta_min_deg", "theta_max_deg"})
    CHECK_MESSAGE(number(row, k) == doctest::Approx(summaryNumber(sj, k)).epsilon(1e-9), k);
  const double skew = summaryNumber(sj, "skew_deg");
  CHECK(number(row, "skew_deg") == doctest::Approx(skew).epsilon(1e-9).scale(1.0));
  // a trace's waves are taken about its own axis (its direction over whole waves), a run's summary across
  // downhill: the two differ by the rotation through the skew alone, 1 - cos(skew) in each distance (this
  // root's skew is 0.5 deg: 4e-5); a root that does not skew gives them to the bit
  const double turn = 2.0 * (1.0 - std::cos(skew * std::numbers::pi / 180.0)) + 1e-9;
  CHECK(std::abs(skew) < 2.0);
  for (const char* k : {"wavelength_mm", "amplitude_mm", "amplitude_half_mm"})
    CHECK_MESSAGE(number(row, k) == doctest::Approx(summaryNumber(sj, k)).epsilon(turn), k);
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
  ROOTSIM_CHECK_CLOSE(number(rows[0], "skew_base_tip_deg"), 0.0, kRoundoff);
  // the diameter function (in pixels: 4.0, 4.0, 3.5, 3.0, 2.5) sets the radius: half the median, in mm
  CHECK(rows[0].at("radius_source") == "diameter");
  ROOTSIM_CHECK_CLOSE(number(rows[0], "radius_mm"), 0.5 * 3.5 * u, kRoundoff);
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
  CHECK(bad.out.find("up.rsml:3: its unit is pixel") != std::string::npos);
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

namespace {

// a pixel RSML file of two plants traced as a tracer would (24 px/mm, a point every 4 px, 1 px of
// Gaussian jitter per coordinate, whole pixels; a deterministic generator): plant "s" a straight root
// 20 mm long heading 3 degrees towards +x from downhill (+y), plant "w" a wave of half excursion 0.5 mm
// and wavelength 3 mm
void writeTracedPlate(const fs::path& file) {
  constexpr double pxPerMm = 24, stepPx = 4, jitterPx = 1;
  unsigned long long state = 12345;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(state >> 11) + 0.5) / 9007199254740992.0;
  };
  auto normal = [&] { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * std::numbers::pi * uniform()); };
  std::ofstream f(file);
  f << "<?xml version=\"1.0\"?>\n<rsml>\n<metadata><version>1</version><unit>pixel</unit><resolution>1</resolution></metadata>\n<scene>\n";
  for (const char* plant : {"s", "w"}) {
    f << "<plant id=\"" << plant << "\"><root id=\"1\"><geometry><polyline>\n";
    const bool wave = plant[0] == 'w';
    // points every stepPx of arc length along the true curve (a fine polyline walked in arc length)
    double u = 0, w = 0, walked = 0;
    const double dw = 0.0005;  // [mm]
    for (double next = 0; w <= 20.0;) {
      if (walked >= next) {
        f << "<point x=\"" << std::round(300 + u * pxPerMm + jitterPx * normal()) << "\" y=\""
          << std::round(100 + w * pxPerMm + jitterPx * normal()) << "\"/>\n";
        next += stepPx / pxPerMm;
      }
      const double u2 = wave ? 0.5 * std::sin(2 * std::numbers::pi * (w + dw) / 3.0) : (w + dw) * std::tan(3.0 * std::numbers::pi / 180);
      walked += std::hypot(u2 - u, dw);
      u = u2;
      w += dw;
    }
    f << "</polyline></geometry></root></plant>\n";
  }
  f << "</scene>\n</rsml>\n";
}

}  // namespace

TEST_CASE("analyze: a root traced at 1 px of jitter - the straight one is straight below the noise, the wave keeps lambda and A") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("noise");
  writeTracedPlate(d / "plate.rsml");
  const auto r = run("analyze " + (d / "plate.rsml").string() + " --px-per-mm 24 --out " + (d / "an").string());
  REQUIRE(r.code == 0);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 2);
  const double injectedMm = std::sqrt(1.0 + 1.0 / 12.0) / 24;  // jitter and whole-pixel rounding
  for (const auto& row : rows) {
    CAPTURE(row.at("plant"));
    CHECK(number(row, "noise_mm") == doctest::Approx(injectedMm).epsilon(0.25));
    CHECK(number(row, "smoothing_mm") > 0);
    // the tracing limit: one root diameter and 3 sqrt(2) sigma of the smoothed curve, a fraction of the points'
    CHECK(number(row, "peak_threshold_mm") > 0.2);
    CHECK(number(row, "peak_threshold_mm") < 0.2 + 3 * std::sqrt(2.0) * number(row, "noise_mm"));
  }
  const auto& s = rows[0];
  CHECK(s.at("pattern") == "straight");
  CHECK(s.at("wavelength_mm").empty());
  CHECK(s.at("amplitude_mm").empty());
  CHECK(s.at("waves_note").find("below the ") == 0);
  CHECK(number(s, "straightness") > 0.995);
  CHECK(number(s, "hgi") == doctest::Approx(std::sin(3.0 * std::numbers::pi / 180)).epsilon(0.2));
  CHECK(number(s, "vgi") == doctest::Approx(std::cos(3.0 * std::numbers::pi / 180)).epsilon(0.005));
  // the tip angle: the slope of a one-sided quadratic fit at the tip, over the smoothing's ~3 mm of ~18
  // points with sigma 0.045 mm, has a standard error of about 4 degrees; pixel steps would give multiples
  // of atan(1/4) = 14 degrees
  CHECK(std::abs(number(s, "theta_tip_deg") - 3.0) < 12.0);
  CHECK(number(s, "max_kappa_per_mm") < 0.5);  // the raw trace's turns of whole pixels gave ~10 /mm
  const auto& w = rows[1];
  CHECK(w.at("pattern") == "waving");
  CHECK(w.at("waves_note").empty());
  CHECK(number(w, "wavelength_mm") == doctest::Approx(3.0).epsilon(0.10));
  CHECK(number(w, "amplitude_mm") == doctest::Approx(1.0).epsilon(0.15));
  CHECK(number(w, "amplitude_half_mm") == doctest::Approx(0.5).epsilon(0.15));
  // curves.csv: the file's points and the measured curve with its counted peaks
  const std::string curves = slurp(d / "an" / "curves.csv");
  CHECK(curves.rfind("file,plant,root,kind,point,lateral_mm,downhill_mm,mature,peak\n", 0) == 0);
  std::size_t peaks = 0;
  for (std::size_t at = curves.find(",w,1,measured,"); at != std::string::npos; at = curves.find(",w,1,measured,", at + 1))
    if (curves.compare(curves.find('\n', at) - 2, 2, ",1") == 0) ++peaks;
  CHECK(static_cast<double>(peaks) == number(w, "lateral_peaks"));
  CHECK(curves.find(",s,1,trace,0,") != std::string::npos);
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

TEST_CASE("analyze: work sized by a trace is counted against its cap before it is done - and numbers and hints are checked") {
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

// ---- dialects, plants, time-lapse ----

namespace {

// the rows of a CSV whose key column equals value
std::vector<std::map<std::string, std::string>> rowsWhere(const std::vector<std::map<std::string, std::string>>& rows, const std::string& key,
                                                          const std::string& value) {
  std::vector<std::map<std::string, std::string>> out;
  for (const auto& r : rows)
    if (r.at(key) == value) out.push_back(r);
  return out;
}

// the real files in the shared data folder beside the source tree (data/rsml, its README), or "" with the case reported skipped
fs::path sharedData() {
  const fs::path d = fs::path(ROOTSIM_SOURCE_DIR).parent_path() / "shared" / "data" / "rsml";
  if (!fs::is_directory(d)) {
    test::skipCase("no shared data folder with the real RSML files (data/rsml) beside the source tree");
    return {};
  }
  return d;
}

// an openalea-style plate in pixels (lowercase ids, unit pixel): seedlings 12 px apart, each a primary
// down the image and laterals across, whole-pixel coordinates with a tracer's jitter of -1, 0 or 1 px
struct TracedSeedling {
  std::string plantId, rootId, label;  // label: the root's identity in the other file, for the test's check
  int x0 = 0, primaryPx = 0;
  struct Lateral {
    std::string id, label;
    int atPx = 0, lengthPx = 0, side = 1;
  };
  std::vector<Lateral> laterals;
};
std::string openaleaPlate(const std::vector<TracedSeedling>& seedlings, int jitterSeed) {
  auto jitter = [&](int k, int s) { return (k * (5 + 2 * jitterSeed) + s + jitterSeed) % 3 - 1; };
  std::string o = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<rsml>\n  <metadata><version>1.0</version><unit>pixel</unit><resolution>1</resolution>"
                  "<software>openalea</software></metadata>\n  <scene>\n";
  int s = 0;
  for (const TracedSeedling& sd : seedlings) {
    o += "    <plant id=\"" + sd.plantId + "\" label=\"P\">\n      <root id=\"" + sd.rootId + "\" label=\"" + sd.label + "\"><geometry><polyline>\n";
    for (int k = 0; 5 * k <= sd.primaryPx; ++k)
      o += "        <point x=\"" + std::to_string(sd.x0 + jitter(k, s)) + "\" y=\"" + std::to_string(100 + 5 * k) + "\" z=\"0\"/>\n";
    o += "      </polyline></geometry>\n";
    for (const auto& l : sd.laterals) {
      o += "        <root id=\"" + l.id + "\" label=\"" + l.label + "\"><geometry><polyline>\n";
      for (int k = 0; 5 * k <= l.lengthPx; ++k)
        o += "          <point x=\"" + std::to_string(sd.x0 + l.side * 5 * k) + "\" y=\"" + std::to_string(100 + l.atPx + (k > 0 ? jitter(k, s) : 0)) +
             "\" z=\"0\"/>\n";
      o += "        </polyline></geometry></root>\n";
    }
    o += "      </root>\n    </plant>\n";
    ++s;
  }
  return o + "  </scene>\n</rsml>\n";
}

}  // namespace

TEST_CASE("analyze: a RootSystemTracker 2D+t file / its scale with no flag / every root at every observation / rates / plants") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("rst");
  const std::string in = kData + "rst_2dt.rsml";
  const auto r = run("analyze " + in + " --out " + (d / "an").string());
  REQUIRE(r.code == 0);
  CHECK(r.out.find("warning") == std::string::npos);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 4);
  // 50 um pixels: the primary's 120 px are 6 mm; its diameter of 6 px gives R = 0.15 mm
  ROOTSIM_CHECK_CLOSE(number(rows[0], "length_mm"), 6.0, kRoundoff);
  CHECK(number(rows[0], "time_h") == 18);
  ROOTSIM_CHECK_CLOSE(number(rows[0], "radius_mm"), 0.15, kRoundoff);
  CHECK(rows[0].at("radius_source") == "diameter");
  CHECK(rows[1].at("radius_source") == "default");  // its diameters are 0: not measured
  // growth over the last interval each root grew in: 2 mm in 6 h, 1 mm in 6 h; one observation: none
  ROOTSIM_CHECK_CLOSE(number(rows[0], "growth_rate_mm_per_h"), 2.0 / 6, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(rows[1], "growth_rate_mm_per_h"), 1.0 / 6, kRoundoff);
  CHECK(std::isnan(number(rows[2], "growth_rate_mm_per_h")));
  ROOTSIM_CHECK_CLOSE(number(rows[3], "growth_rate_mm_per_h"), 1.0 / 6, kRoundoff);
  // growth.csv: the root at observation k is the polyline up to coord_t = k
  const auto g = readRows(d / "an" / "growth.csv");
  const auto primary = rowsWhere(g, "root", "1.1");
  REQUIRE(primary.size() == 4);
  const double len[] = {1, 2, 4, 6}, hours[] = {0, 6, 12, 18};
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(number(primary[k], "time_h") == hours[k]);
    ROOTSIM_CHECK_CLOSE(number(primary[k], "length_mm"), len[k], kRoundoff);
    ROOTSIM_CHECK_CLOSE(number(primary[k], "tip_downhill_mm"), len[k], kRoundoff);
    CHECK(number(primary[k], "tip_lateral_mm") == doctest::Approx(0).epsilon(1e-12));
    ROOTSIM_CHECK_CLOSE(number(primary[k], "theta_tip_deg"), 0, kRoundoff);
    CHECK(primary[k].at("track") == "rst_2dt.rsml:1/1.1");
  }
  // the laterals: towards +x (+lateral) is +90 deg, as the base-to-tip skew; a root not yet started has no row
  const auto l1 = rowsWhere(g, "root", "1.1.1");
  REQUIRE(l1.size() == 2);
  CHECK(number(l1[0], "time_h") == 12);
  ROOTSIM_CHECK_CLOSE(number(l1[1], "length_mm"), 2.0, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(l1[1], "theta_tip_deg"), 90, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(rows[1], "skew_base_tip_deg"), 90, kRoundoff);
  const auto l2 = rowsWhere(g, "root", "1.1.2");
  REQUIRE(l2.size() == 1);
  ROOTSIM_CHECK_CLOSE(number(l2[0], "theta_tip_deg"), -90, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(l2[0], "tip_lateral_mm"), -1, kRoundoff);
  CHECK(rowsWhere(g, "root", "2.1").size() == 3);  // two points at coord_t 0 and 3: no length at 0 h
  // plants.csv: the seedling's lengths, laterals, branched zone (2 to 5 mm along the primary), extent
  const auto p = readRows(d / "an" / "plants.csv");
  REQUIRE(p.size() == 2);
  ROOTSIM_CHECK_CLOSE(number(p[0], "primary_length_mm"), 6, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(p[0], "total_length_mm"), 9, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(p[0], "lateral_length_mm"), 3, kRoundoff);
  CHECK(number(p[0], "lateral_count") == 2);
  ROOTSIM_CHECK_CLOSE(number(p[0], "branched_zone_mm"), 3, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(p[0], "lateral_density_per_mm"), 2.0 / 3, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(p[0], "laterals_per_primary_mm"), 2.0 / 6, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(p[0], "depth_mm"), 6, kRoundoff);
  ROOTSIM_CHECK_CLOSE(number(p[0], "width_mm"), 3, kRoundoff);
  CHECK(std::isnan(number(p[1], "lateral_density_per_mm")));  // no lateral: no branched zone
  // its scale is the file's: --px-per-mm is refused; --times too (the file has its own times)
  const auto px = run("analyze " + in + " --px-per-mm 20 --out " + (d / "x").string());
  CHECK(px.code == 2);
  CHECK(px.out.find("is in pixel(um), not pixels (its scale is known)") != std::string::npos);
  const auto t = run("analyze " + in + " --times 5 --out " + (d / "x").string());
  CHECK(t.code == 2);
  CHECK(t.out.find("is a time-lapse (RSML 2D+t") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "x"));
}

TEST_CASE("analyze: a SmartRoot file in inches reads with no flag / a scale giving an implausible seedling is a warning naming it") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("smartroot");
  const std::string in = kData + "smartroot_inch.rsml";
  const auto r = run("analyze " + in + " --out " + (d / "an").string());
  REQUIRE(r.code == 0);
  CHECK(r.out.find("warning") == std::string::npos);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].at("root") == "r1");  // uppercase ID
  CHECK(rows[2].at("parent") == "r2");
  ROOTSIM_CHECK_CLOSE(number(rows[0], "length_mm"), 10, kRoundoff);  // 100 px at 254 dpi
  ROOTSIM_CHECK_CLOSE(number(rows[0], "radius_mm"), 0.1, kRoundoff);
  // SmartRoot puts every root of an image in one plant: one plants.csv row per seedling (base root)
  const auto p = readRows(d / "an" / "plants.csv");
  REQUIRE(p.size() == 2);
  CHECK(p[1].at("root") == "r2");
  CHECK(number(p[1], "lateral_count") == 1);
  ROOTSIM_CHECK_CLOSE(number(p[1], "total_length_mm"), 7, kRoundoff);
  // the same file at 1 dpi: 2.5 m roots, written with a warning that names the scale to check
  std::string text = slurp(in);
  text.replace(text.find("<resolution>254.0</resolution>"), 30, "<resolution>1</resolution>");
  { std::ofstream(d / "dpi1.rsml") << text; }
  const auto w = run("analyze " + (d / "dpi1.rsml").string() + " --out " + (d / "an1").string());
  CHECK(w.code == 0);
  CHECK(w.out.find("rootsim: warning: " + (d / "dpi1.rsml").string() + ":17: primary root #0/r1 is 2540 mm long, implausible for a seedling "
                   "(0.2 to 200 mm): check the scale, <unit>inch</unit> and <resolution>1</resolution> in the file") != std::string::npos);
  // a pixel file read at 0.1 px/mm: the flag to check; --quiet keeps the warning
  text.replace(text.find("<unit>inch</unit>"), 17, "<unit>pixel</unit>");
  { std::ofstream(d / "px.rsml") << text; }
  const auto px = run("analyze " + (d / "px.rsml").string() + " --px-per-mm 0.1 --quiet --out " + (d / "an3").string());
  CHECK(px.code == 0);
  CHECK(px.out.find("primary root #0/r1 is 1000 mm long, implausible for a seedling (0.2 to 200 mm): check --px-per-mm 0.1") != std::string::npos);
}

TEST_CASE("analyze: dated files / roots matched by geometry, not id / renumbered, reordered, extended / laterals / new roots") {
  if (!analyzeBuilt()) return;
  const fs::path d = scratch("dated");
  // the earlier date: three seedlings 12 px (0.5 mm) apart, each with one lateral
  std::vector<TracedSeedling> a, b;
  for (int s = 0; s < 3; ++s) {
    TracedSeedling e;
    e.plantId = std::to_string(s + 1);
    e.rootId = std::to_string(6 + 100 * s);
    e.x0 = 100 + 12 * s;
    e.primaryPx = 200 + 20 * s;
    e.laterals.push_back({std::to_string(600 + s), "", 60, 30, s % 2 ? -1 : 1});
    a.push_back(e);
    // the later date: renumbered, longer, the lateral longer, a new lateral lower down
    TracedSeedling l = e;
    l.plantId = std::to_string(9 - s);
    l.rootId = std::to_string(1000 + 37 * s);
    l.label = e.plantId + "/" + e.rootId;
    l.primaryPx = e.primaryPx + 100 + 10 * s;
    l.laterals = {{std::to_string(2000 + s), e.plantId + "/" + e.laterals[0].id, 60, 60, s % 2 ? -1 : 1},
                  {std::to_string(3000 + s), "", 150, 20, s % 2 ? 1 : -1}};
    b.insert(b.begin(), l);  // plants in the reverse order
  }
  { std::ofstream(d / "day1.rsml") << openaleaPlate(a, 0); }
  { std::ofstream(d / "day2.rsml") << openaleaPlate(b, 1); }
  REQUIRE(run("analyze " + (d / "day2.rsml").string() + " " + (d / "day1.rsml").string() + " --px-per-mm 24 --times 48,24 --out " +
              (d / "an").string())
              .code == 0);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 9 + 6);
  const auto g = readRows(d / "an" / "growth.csv");
  REQUIRE(g.size() == 15);
  int rated = 0;
  for (std::size_t i = 0; i < 9; ++i) {  // day 2's roots
    const auto& row = rows[i];
    CAPTURE(row.at("root"));
    const std::string earlier = row.at("root_label");
    if (earlier.empty()) {
      // a lateral that was not there on day 1: seen once, no rate
      CHECK(std::isnan(number(row, "growth_rate_mm_per_h")));
      continue;
    }
    // the root it extends, found by geometry: its track is day 1's id, its rate the length gained per hour
    const auto then = rowsWhere(rows, "root", earlier.substr(earlier.find('/') + 1));
    REQUIRE(then.size() == 1);
    CHECK(number(row, "growth_rate_mm_per_h") == doctest::Approx((number(row, "length_mm") - number(then[0], "length_mm")) / 24).epsilon(1e-12));
    CHECK(number(row, "growth_rate_mm_per_h") > 0);
    const auto series = rowsWhere(g, "track", "day1.rsml:" + earlier);
    REQUIRE(series.size() == 2);
    CHECK(number(series[0], "time_h") == 24);
    CHECK(number(series[1], "time_h") == 48);
    CHECK(series[1].at("root") == row.at("root"));
    ++rated;
  }
  CHECK(rated == 6);  // every root seen at both dates
}

TEST_CASE("analyze: the real files of the shared data folder / what each says with and without a scale") {
  if (!analyzeBuilt()) return;
  const fs::path data = sharedData();
  if (data.empty()) return;
  const fs::path d = scratch("real");
  // RootSystemTracker 2D+t: read with no flag (76 um pixels), every root at every observation
  const auto r = run("analyze " + (data / "synthetic_2dt_plate.rsml").string() + " --out " + (d / "rst").string());
  REQUIRE(r.code == 0);
  CHECK(r.out.find("warning") == std::string::npos);
  const auto rows = readRows(d / "rst" / "analysis.csv");
  REQUIRE(rows.size() == 21);
  const auto plants = readRows(d / "rst" / "plants.csv");
  REQUIRE(plants.size() == 3);
  for (const auto& p : plants) {
    CHECK(number(p, "lateral_count") == 6);
    // 96 h at 0.3 mm/h after the first hour's 1.2 mm: about 30 mm deep, the tracer's steps make the length longer
    CHECK(number(p, "depth_mm") == doctest::Approx(30).epsilon(0.02));
  }
  const auto g = readRows(d / "rst" / "growth.csv");
  for (const auto& row : rows) {
    CAPTURE(row.at("root"));
    const auto series = rowsWhere(g, "root", row.at("root"));
    REQUIRE_FALSE(series.empty());
    CHECK(number(series.back(), "time_h") == 96);
    CHECK(number(series.back(), "length_mm") == doctest::Approx(number(row, "length_mm")).epsilon(1e-12));
    // every root seen at two observations has a rate
    CHECK(std::isfinite(number(row, "growth_rate_mm_per_h")) == (series.size() >= 2));
  }
  // openalea's and SmartRoot's example files are in pixels with no scale: the flag is named, nothing written
  for (const char* f : {"2012_11_19_18h00_chl110_1_1.rsml", "arabidopsis-simple.rsml"}) {
    const auto e = run("analyze " + (data / f).string() + " --out " + (d / "x").string());
    CHECK(e.code == 2);
    CHECK(e.out.find((data / f).string() + ":5: its unit is pixel with no physical scale (no resolution or size in the file); give --px-per-mm R") !=
          std::string::npos);
    CHECK_FALSE(fs::exists(d / "x"));
  }
  REQUIRE(run("analyze " + (data / "2012_11_19_18h00_chl110_1_1.rsml").string() + " --px-per-mm 24 --out " + (d / "oa").string()).code == 0);
  CHECK(readRows(d / "oa" / "plants.csv").size() == 5);
  CHECK(readRows(d / "oa" / "analysis.csv").size() == 25);
}

TEST_CASE("analyze: the openalea plate and a renumbered, reordered, extended copy / every root matched to its own") {
  if (!analyzeBuilt()) return;
  const fs::path data = sharedData();
  if (data.empty()) return;
  const fs::path d = scratch("openalea");
  const fs::path orig = data / "2012_11_19_18h00_chl110_1_1.rsml";
  rsml::Document doc = rsml::readRsml(orig);  // in pixels
  rsml::Document later = doc;
  std::reverse(later.plants.begin(), later.plants.end());
  int n = 0;
  for (rsml::Plant& p : later.plants) {
    const std::string plantId = p.id;
    p.id = "p" + std::to_string(90 - n);
    for (rsml::Root& r : p.roots) {
      r.label = plantId + "/" + r.id;
      r.id = std::to_string(5000 + 7 * n++);
      // a day's growth: 4 more points, 5 px apart, along the tip's direction, in whole pixels; the
      // retraced points a pixel to the side every other point
      const std::size_t m = r.x.size() - 1, from = m >= 3 ? m - 3 : 0;
      const double dx = r.x[m] - r.x[from], dy = r.y[m] - r.y[from], norm = std::hypot(dx, dy);
      for (std::size_t k = 0; k <= m; k += 2) r.x[k] += 1;
      for (int k = 1; k <= 4; ++k) {
        r.x.push_back(std::round(r.x[m] + 5 * k * dx / norm));
        r.y.push_back(std::round(r.y[m] + 5 * k * dy / norm));
        r.z.push_back(0);
      }
    }
  }
  std::string text = rsml::writeRsml(later);
  text.replace(text.find("<unit>mm</unit>"), 15, "<unit>pixel</unit>");
  { std::ofstream(d / "later.rsml") << text; }
  REQUIRE(run("analyze " + orig.string() + " " + (d / "later.rsml").string() + " --px-per-mm 24 --times 0,24 --out " + (d / "an").string()).code ==
          0);
  const auto rows = readRows(d / "an" / "analysis.csv");
  REQUIRE(rows.size() == 50);
  const auto g = readRows(d / "an" / "growth.csv");
  for (std::size_t i = 25; i < 50; ++i) {
    const auto& row = rows[i];
    CAPTURE(row.at("root_label"));
    const std::string id = row.at("root_label").substr(row.at("root_label").find('/') + 1);
    const auto then = rowsWhere(std::vector<std::map<std::string, std::string>>(rows.begin(), rows.begin() + 25), "root", id);
    REQUIRE(then.size() == 1);
    CHECK(number(row, "growth_rate_mm_per_h") == doctest::Approx((number(row, "length_mm") - number(then[0], "length_mm")) / 24).epsilon(1e-12));
    const auto series = rowsWhere(g, "track", orig.filename().string() + ":" + row.at("root_label"));
    REQUIRE(series.size() == 2);
    CHECK(series[1].at("root") == row.at("root"));
  }
}

TEST_CASE("analyze: the synthetic 2D+t plate cut into dated files gives the time-lapse's own lengths and matches every root") {
  if (!analyzeBuilt()) return;
  const fs::path data = sharedData();
  if (data.empty()) return;
  const fs::path d = scratch("cut");
  const fs::path lapse = data / "synthetic_2dt_plate.rsml";
  const rsml::Document doc = rsml::readRsml(lapse);
  std::string files, times;
  for (int k : {4, 8, 12, 16}) {
    // the plate at observation k: each root up to coord_t = k (interpolated), renumbered, plants reversed
    rsml::Document cut = doc;
    cut.plants.clear();
    cut.observationTimesH.clear();
    for (auto p = doc.plants.rbegin(); p != doc.plants.rend(); ++p) {
      rsml::Plant q = *p;
      q.id = "d" + std::to_string(k) + "-" + p->id;
      q.roots.clear();
      std::vector<int> index(p->roots.size(), -1);
      for (std::size_t i = 0; i < p->roots.size(); ++i) {
        const rsml::Root& r = p->roots[i];
        rsml::Root c;
        c.id = std::to_string(1000 * k + 100 * static_cast<int>(p - doc.plants.rbegin()) + static_cast<int>(i));
        c.label = r.id;
        c.parent = r.parent >= 0 ? index[static_cast<std::size_t>(r.parent)] : -1;
        for (std::size_t j = 0; j < r.x.size() && r.timeIndex[j] <= k; ++j) {
          c.x.push_back(r.x[j]);
          c.y.push_back(r.y[j]);
          c.z.push_back(0);
        }
        const std::size_t j = c.x.size();
        if (j > 0 && j < r.x.size()) {
          const double f = (k - r.timeIndex[j - 1]) / (r.timeIndex[j] - r.timeIndex[j - 1]);
          c.x.push_back(r.x[j - 1] + f * (r.x[j] - r.x[j - 1]));
          c.y.push_back(r.y[j - 1] + f * (r.y[j] - r.y[j - 1]));
          c.z.push_back(0);
        }
        double len = 0;
        for (std::size_t m = 1; m < c.x.size(); ++m) len += std::hypot(c.x[m] - c.x[m - 1], c.y[m] - c.y[m - 1]);
        if (len == 0 || (r.parent >= 0 && c.parent < 0)) continue;
        index[i] = static_cast<int>(q.roots.size());
        q.roots.push_back(c);
      }
      cut.plants.push_back(q);
    }
    const fs::path f = d / ("plate_t" + std::to_string(6 * k) + "h.rsml");
    { std::ofstream(f) << rsml::writeRsml(cut); }
    files += " " + f.string();
    times += (times.empty() ? "" : ",") + std::to_string(6 * k);
  }
  REQUIRE(run("analyze" + files + " --times " + times + " --out " + (d / "dated").string()).code == 0);
  REQUIRE(run("analyze " + lapse.string() + " --out " + (d / "lapse").string()).code == 0);
  const auto rows = readRows(d / "dated" / "analysis.csv");
  const auto g = readRows(d / "dated" / "growth.csv");
  const auto lapseG = readRows(d / "lapse" / "growth.csv");
  std::map<std::string, std::string> labelOf;  // dated root id -> the time-lapse's id
  for (const auto& r : rows) labelOf[r.at("root")] = r.at("root_label");
  std::map<std::string, std::set<std::string>> tracks;  // track -> the time-lapse ids in it
  for (const auto& row : g) {
    const std::string id = labelOf.at(row.at("root"));
    tracks[row.at("track")].insert(id);
    // the dated root's length is the time-lapse's at the same time
    bool found = false;
    for (const auto& l : lapseG)
      if (l.at("root") == id && number(l, "time_h") == number(row, "time_h")) {
        CHECK(number(row, "length_mm") == doctest::Approx(number(l, "length_mm")).epsilon(1e-9));
        found = true;
      }
    CHECK_MESSAGE(found, id << " at " << row.at("time_h"));
  }
  // one track per root of the plate, each holding that root alone: every root matched at every date
  std::set<std::string> ids;
  for (const auto& entry : tracks) {
    const std::string& track = entry.first;  // CAPTURE is a lambda: clang rejects capturing a binding
    CAPTURE(track);
    CHECK(entry.second.size() == 1);
    ids.insert(*entry.second.begin());
  }
  CHECK(ids.size() == tracks.size());
  CHECK(ids.size() == 21);
}

TEST_CASE("analyze: the real files' noise and no tracing called waving / the openalea primaries' meanders / the 2D+t plate's faint waves") {
  if (!analyzeBuilt()) return;
  const fs::path data = sharedData();
  if (data.empty()) return;
  const fs::path d = scratch("realnoise");
  // openalea: whole pixels every 5 px down the image, read at 24 px/mm. The primaries' noise is the
  // rounding's 1/sqrt(12) = 0.29 px; their smoothed curves bend at most ~2 /mm (the raw pixel steps
  // turned by 5-10 /mm) and their tip angles are no longer arctangents of pixel steps only
  REQUIRE(run("analyze " + (data / "2012_11_19_18h00_chl110_1_1.rsml").string() + " --px-per-mm 24 --out " + (d / "oa").string()).code == 0);
  int primaries = 0;
  for (const auto& row : readRows(d / "oa" / "analysis.csv")) {
    CHECK(row.at("pattern") != "waving");  // no root of the plate: laterals are short and skew
    if (row.at("order") != "0") continue;
    ++primaries;
    CAPTURE(row.at("root"));
    const double sigmaPx = number(row, "noise_mm") * 24;
    CHECK(sigmaPx > 0.2);
    CHECK(sigmaPx < 0.35);
    CHECK(number(row, "max_kappa_per_mm") < 2.5);
    CHECK(number(row, "smoothing_mm") > 0.5);
    // no tracing called a phenotype: the meanders are under one root diameter (0.2 mm, no diameter in the
    // file) and 3 sqrt(2) sigma of the smoothed curve
    CHECK(number(row, "peak_threshold_mm") > 0.2);
    CHECK(number(row, "peak_threshold_mm") < 0.2 + 3 * std::sqrt(2.0) * number(row, "noise_mm"));
    CHECK(row.at("pattern") != "waving");
    CHECK(row.at("wavelength_mm").empty());
    CHECK(row.at("amplitude_mm").empty());
    const std::string note = row.at("waves_note");
    CHECK((note.find("below the tracing limit ") == 0 || note.find("not a wave train: ") == 0));
  }
  CHECK(primaries == 5);
  // the 2D+t plate: 0.6 px of jitter on 76 um pixels, rounded: sqrt(0.36 + 1/12) px = 0.0506 mm
  REQUIRE(run("analyze " + (data / "synthetic_2dt_plate.rsml").string() + " --out " + (d / "rst").string()).code == 0);
  // its seedlings wave faintly (alpha 10 deg at the straight-to-waving transition), 0.1-0.2 mm peak to
  // peak: under one root diameter, at the noise; no root of the plate is called waving
  for (const auto& row : readRows(d / "rst" / "analysis.csv")) {
    CAPTURE(row.at("root"));
    CHECK(row.at("pattern") != "waving");
    if (row.at("order") == "0") {
      CHECK(number(row, "noise_mm") == doctest::Approx(0.0506).epsilon(0.2));
      CHECK(row.at("pattern") == "straight");
      CHECK(row.at("waves_note").find("below the ") == 0);
    }
  }
}
