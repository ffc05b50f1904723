// RSML reader and writer (src/io/rsml.cpp, docs/rsml.md): the test files of tests/data/rsml/ (written
// from the format's description), every bad input with its file:line, the writer read back exactly
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/rsml.hpp"
#include "tolerance_support.hpp"

using rootsim::test::kRoundoff;

namespace fs = std::filesystem;
using namespace rootsim;

namespace {

const fs::path kData = fs::path(ROOTSIM_SOURCE_DIR) / "tests/data/rsml";

// bit for bit (the writer's numbers read back to the same doubles)
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// the message of the SceneError the file raises ("" when it reads)
std::string errorOf(const fs::path& f) {
  try {
    rsml::readRsml(f);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("RSML reader: a SmartRoot-style file in pixels / unit cm at 100 px/cm / nested laterals") {
  const rsml::Document d = rsml::readRsml(kData / "smartroot_pixels.rsml");
  CHECK(d.meta.unit == "cm");
  CHECK(d.meta.resolution == 100);
  CHECK(d.mmPerUnit == doctest::Approx(0.1).epsilon(1e-15));  // 10 mm per cm over 100 px per cm
  CHECK(d.meta.software == "smartroot");
  CHECK(d.meta.fileKey == "plate_07");
  REQUIRE(d.plants.size() == 1);
  const rsml::Plant& p = d.plants[0];
  CHECK(p.id == "p1");
  CHECK(p.label == "seedling");
  REQUIRE(p.roots.size() == 4);
  // document order, parents before their laterals
  const std::vector<std::string> ids = {"r1", "r1.1", "r1.1.1", "r1.2"};
  const std::vector<int> parents = {-1, 0, 1, 0}, orders = {0, 1, 2, 1};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(p.roots[i].id == ids[i]);
    CHECK(p.roots[i].parent == parents[i]);
    CHECK(p.roots[i].order == orders[i]);
    CHECK_FALSE(p.roots[i].hasZ);
  }
  const rsml::Root& r = p.roots[0];
  CHECK(r.line == 25);
  REQUIRE(r.points() == 5);
  ROOTSIM_CHECK_CLOSE(r.x[0], 50.0, kRoundoff);   // 500 px = 5 cm
  ROOTSIM_CHECK_CLOSE(r.y[4], 50.0, kRoundoff);
  ROOTSIM_CHECK_CLOSE(r.y[0], 10.0, kRoundoff);
  CHECK(r.z[2] == 0.0);
  // properties as element text
  REQUIRE(r.property("lateral-count") != nullptr);
  CHECK(r.property("lateral-count")->number == 2);
  CHECK(r.property("rulerAtOrigin")->text == "0.0");
  // the diameter function in pixels, to mm
  REQUIRE(r.diameterMm.size() == 5);
  ROOTSIM_CHECK_CLOSE(r.diameterMm[0], 0.4, kRoundoff);
  ROOTSIM_CHECK_CLOSE(r.diameterMm[4], 0.25, kRoundoff);
  CHECK(r.function("diameter")->samples[2] == 3.5);   // the samples as written
  CHECK(p.roots[1].diameterMm.size() == 3);
  CHECK(p.roots[2].diameterMm.empty());
  ROOTSIM_CHECK_CLOSE(p.roots[2].x[1], 57.0, kRoundoff);
}

TEST_CASE("RSML reader: an openalea-style file in micrometres / two plants / child-element points / radius") {
  const rsml::Document d = rsml::readRsml(kData / "openalea_micrometer.rsml");
  CHECK(d.mmPerUnit == doctest::Approx(1e-3).epsilon(1e-15));
  CHECK(d.meta.sequenceLabel == "series_a");
  CHECK(d.meta.sequenceIndex == 3);
  CHECK(d.meta.unified);
  CHECK(d.meta.observationHours == std::vector<double>{0, 24, 48.5});
  CHECK_FALSE(d.hasTime);
  REQUIRE(d.plants.size() == 2);
  REQUIRE(d.plants[0].roots.size() == 1);
  REQUIRE(d.plants[1].roots.size() == 1);
  CHECK(d.plants[0].properties.at(0).text == "Col-0");
  const rsml::Root& r = d.plants[0].roots[0];
  CHECK(r.hasZ);
  ROOTSIM_CHECK_CLOSE(r.x[1], 0.01, kRoundoff);
  ROOTSIM_CHECK_CLOSE(r.y[2], 2.5, kRoundoff);
  ROOTSIM_CHECK_CLOSE(r.z[2], -0.1505, kRoundoff);
  CHECK(r.property("length")->number == 2500.5);
  // radius 50 um: diameter 0.1 mm
  REQUIRE(r.diameterMm.size() == 3);
  ROOTSIM_CHECK_CLOSE(r.diameterMm[0], 0.1, kRoundoff);
  ROOTSIM_CHECK_CLOSE(r.diameterMm[2], 0.08, kRoundoff);
  ROOTSIM_CHECK_CLOSE(d.plants[1].roots[0].x[0], 5.0, kRoundoff);
}

TEST_CASE("RSML reader: RootSystemTracker's 2D+t dialect / pixel(um) with <size> / coord_t, coord_th / per-point diameter") {
  const rsml::Document d = rsml::readRsml(kData / "rst_2dt.rsml");
  CHECK(d.mmPerUnit == doctest::Approx(0.05).epsilon(1e-15));  // <size>50</size> um
  CHECK(d.pixelMm == doctest::Approx(0.05).epsilon(1e-15));
  CHECK(d.meta.size == 50);
  // RootSystemTracker lists observations 1..N; observation 0 is at 0 h
  REQUIRE(d.observationTimesH == std::vector<double>{0, 6, 12, 18});
  CHECK(d.timeLapse());
  REQUIRE(d.plants.size() == 2);
  CHECK(d.plants[0].id == "1");  // uppercase ID
  const rsml::Plant& p = d.plants[0];
  REQUIRE(p.roots.size() == 3);
  CHECK(p.roots[0].id == "1.1");
  CHECK(p.roots[1].id == "1.1.1");
  CHECK(p.roots[1].parent == 0);
  CHECK(p.roots[0].timeIndex == std::vector<double>{0, 0, 1, 1.5, 2, 2.5, 3});
  CHECK(p.roots[0].timeH == std::vector<double>{0, 0, 6, 9, 12, 15, 18});
  ROOTSIM_CHECK_CLOSE(p.roots[0].y[6], 11.0, kRoundoff);  // 220 px x 0.05 mm
  // the diameter in pixels, per point: 6 px = 0.3 mm; vx and vy kept as functions
  REQUIRE(p.roots[0].diameterMm.size() == 7);
  ROOTSIM_CHECK_CLOSE(p.roots[0].diameterMm[0], 0.3, kRoundoff);
  REQUIRE(p.roots[0].function("vy") != nullptr);
  ROOTSIM_CHECK_CLOSE(p.roots[0].function("vy")->samples[6], 3.3, kRoundoff);
}

TEST_CASE("RSML reader: SmartRoot's habits / uppercase ID / unit inch with the scan's dpi / one plant without an id") {
  const rsml::Document d = rsml::readRsml(kData / "smartroot_inch.rsml");
  ROOTSIM_CHECK_CLOSE(d.mmPerUnit, 0.1, kRoundoff);  // 25.4 mm / 254 dpi
  ROOTSIM_CHECK_CLOSE(d.pixelMm, 0.1, kRoundoff);
  CHECK_FALSE(d.timeLapse());
  REQUIRE(d.plants.size() == 1);
  CHECK(d.plants[0].id.empty());
  REQUIRE(d.plants[0].roots.size() == 3);
  CHECK(d.plants[0].roots[0].id == "r1");
  CHECK(d.plants[0].roots[2].id == "r2.1");
  CHECK(d.plants[0].roots[2].parent == 1);
  ROOTSIM_CHECK_CLOSE(d.plants[0].roots[0].y[2], 10.0, kRoundoff);
  ROOTSIM_CHECK_CLOSE(d.plants[0].roots[0].diameterMm[0], 0.2, kRoundoff);  // <sample>2.0</sample> px
  CHECK(d.plants[0].roots[0].property("length")->number == 1.0);
}

TEST_CASE("RSML reader: a 2D+t file's missing attributes, times going backwards, coord_t beyond the observations") {
  // a one-root 2D+t document with the metadata `meta` and the points `points`, one per line from line 6
  auto doc = [](const std::string& meta, const std::string& points) {
    return "<rsml>\n<metadata>" + meta + "</metadata>\n<scene>\n<plant ID=\"1\">\n<root ID=\"1.1\"><geometry><polyline>\n" + points +
           "</polyline></geometry></root>\n</plant></scene></rsml>\n";
  };
  const std::string meta = "<unit>pixel(um)</unit><size>76</size><observation-hours>6,12</observation-hours>";
  auto pt = [](const std::string& attrs) { return "<point coord_x=\"1\" coord_y=\"2\" " + attrs + "/>\n"; };
  struct Bad {
    std::string meta, points;
    const char* says;
  };
  const Bad bad[] = {
      {"<unit>pixel(um)</unit><observation-hours>6</observation-hours>", pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_t=\"1\" coord_th=\"6\""),
       "x.rsml:2: <unit>pixel(um)</unit> needs <size> in the metadata (the pixel size in um"},
      {"<unit>pixel(um)</unit><size>-1</size>", pt("") + pt(""), "x.rsml:2: <size> must be a positive number"},
      {"<unit>pixel(furlong)</unit><size>1</size>", pt("") + pt(""), "x.rsml:2: unknown unit \"furlong\" in <unit>pixel(furlong)</unit>"},
      {meta, pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_th=\"6\""), "x.rsml:7: <point> without coord_t where the root's first point has one"},
      {meta, pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_t=\"1\""), "x.rsml:7: <point> without coord_th"},
      {meta, pt("") + pt("coord_t=\"1\" coord_th=\"6\""), "x.rsml:7: <point> with coord_t where the root's first point has none"},
      {meta, pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_t=\"2.5\" coord_th=\"15\""),
       "x.rsml:7: coord_t 2.5 is outside the observations: expected 0 to 2 (<observation-hours> gives 3 observations, the first at 0 h)"},
      {meta, pt("coord_t=\"-0.5\" coord_th=\"0\"") + pt("coord_t=\"1\" coord_th=\"6\""), "x.rsml:6: coord_t -0.5 is outside the observations"},
      {meta, pt("coord_t=\"1\" coord_th=\"6\"") + pt("coord_t=\"0.5\" coord_th=\"7\""),
       "x.rsml:7: coord_t goes backwards along root 1.1: 0.5 after 1 (a root grows at its tip"},
      {meta, pt("coord_t=\"1\" coord_th=\"6\"") + pt("coord_t=\"1\" coord_th=\"5\""), "x.rsml:7: coord_th goes backwards along root 1.1: 5 h after 6 h"},
      {"<unit>pixel(um)</unit><size>76</size>", pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_t=\"1\" coord_th=\"6\""),
       "x.rsml:6: <point> has coord_t but the metadata has no <observation-hours>"},
      {"<unit>pixel(um)</unit><size>76</size><observation-hours>6,6</observation-hours>", pt("") + pt(""),
       "x.rsml:2: <observation-hours> must increase, found 6 h after 6 h"},
      {meta, pt("coord_t=\"0\" coord_th=\"0\" diameter=\"3\"") + pt("coord_t=\"1\" coord_th=\"6\""),
       "x.rsml:7: <point> without diameter where the root's first point has one"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.says);
    CHECK_THROWS_WITH_AS(rsml::parseRsml(doc(b.meta, b.points), "x.rsml"), doctest::Contains(b.says), SceneError);
  }
  // a root without times in a file whose other roots have them
  const std::string mixed = "<rsml>\n<metadata>" + meta + "</metadata>\n<scene>\n<plant ID=\"1\">\n<root ID=\"1.1\"><geometry><polyline>\n" +
                            pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_t=\"1\" coord_th=\"6\"") + "</polyline></geometry></root>\n" +
                            "<root ID=\"2.1\"><geometry><polyline>\n" + pt("") + pt("") + "</polyline></geometry></root>\n</plant></scene></rsml>\n";
  CHECK_THROWS_WITH_AS(rsml::parseRsml(mixed, "x.rsml"), doctest::Contains("x.rsml:9: a <root> without coord_t in a 2D+t file (its root at line 5 has them"),
                       SceneError);
  // an <observation-hours> that starts at 0 lists every observation
  const rsml::Document d = rsml::parseRsml(
      doc("<unit>pixel(um)</unit><size>76</size><observation-hours>0,6</observation-hours>", pt("coord_t=\"0\" coord_th=\"0\"") + pt("coord_t=\"1\" coord_th=\"6\"")),
      "x.rsml");
  CHECK(d.observationTimesH == std::vector<double>{0, 6});
}

TEST_CASE("RSML units: the names and spellings / the resolution in pixels per unit") {
  for (const char* mm : {"mm", "MM", "millimeter", "millimetre", " mm "}) CHECK(rsml::mmPerUnit(mm, 1) == 1);
  for (const char* cm : {"cm", "centimeter", "Centimetre"}) CHECK(rsml::mmPerUnit(cm, 1) == 10);
  for (const char* m : {"m", "meter", "metre"}) CHECK(rsml::mmPerUnit(m, 1) == 1000);
  for (const char* um : {"um", "\xc2\xb5m", "micrometer", "micrometre", "micron"})
    CHECK(rsml::mmPerUnit(um, 1) == doctest::Approx(1e-3).epsilon(1e-15));
  ROOTSIM_CHECK_CLOSE(rsml::mmPerUnit("inch", 300), 25.4 / 300, kRoundoff);  // a 300 dpi scan
  ROOTSIM_CHECK_CLOSE(rsml::mmPerUnit("cm", 118.11), 10 / 118.11, kRoundoff);
  for (const char* px : {"pixel", "px", "Pixels"}) CHECK(rsml::mmPerUnit(px, 1) == 1);
  CHECK(rsml::mmPerUnit("furlong", 1) == 0);
  CHECK(rsml::mmPerUnit("", 1) == 0);
  // RootSystemTracker's pixel(UNIT): the scale is <size>, not the unit
  CHECK(rsml::mmPerUnit("pixel(um)", 1) == 0);
  CHECK(rsml::pixelSizeUnit("pixel(um)") == "um");
  CHECK(rsml::pixelSizeUnit("Pixel( mm )") == "mm");
  CHECK(rsml::pixelSizeUnit("pixel").empty());
  CHECK(rsml::isPixelUnit(" PX "));
  CHECK_FALSE(rsml::isPixelUnit("pixel(um)"));
}

TEST_CASE("RSML reader: every bad file exits 2 naming file:line") {
  struct Bad {
    const char* file;
    int line;
    const char* says;
  };
  const Bad bad[] = {
      {"malformed.rsml", 12, "malformed XML"},
      {"not_rsml.rsml", 2, "not an <rsml>"},
      {"no_polyline.rsml", 10, "has no <geometry><polyline>"},
      {"one_point.rsml", 12, "at least two points, found 1"},
      {"nan_coordinate.rsml", 14, "point x is not finite"},
      {"absurd_coordinate.rsml", 14, "beyond 1000000 mm"},
      {"unknown_unit.rsml", 5, "unknown <unit> \"furlong\""},
      {"function_length.rsml", 19, "function diameter has 2 samples for the polyline's 3 points"},
      {"not_a_number.rsml", 14, "point x: expected a number, found \"1.5mm\""},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.file);
    const fs::path f = kData / "bad" / b.file;
    const std::string e = errorOf(f);
    CHECK(e.rfind(f.string() + ":" + std::to_string(b.line) + ": ", 0) == 0);
    CHECK(e.find(b.says) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
  }
  // no file, an empty one, no <scene>
  CHECK(errorOf(kData / "bad/missing.rsml").find("not found") != std::string::npos);
  CHECK_THROWS_WITH_AS(rsml::parseRsml("", "empty.rsml"), doctest::Contains("empty.rsml:1:"), SceneError);
  CHECK_THROWS_WITH_AS(rsml::parseRsml("<rsml>\n<metadata/>\n</rsml>", "x.rsml"),
                       doctest::Contains("x.rsml:1: <rsml> has no <scene>"), SceneError);
  // a resolution of zero would divide by zero
  CHECK_THROWS_WITH_AS(rsml::parseRsml("<rsml>\n<metadata>\n<unit>cm</unit>\n<resolution>0</resolution></metadata><scene/></rsml>", "r.rsml"),
                       doctest::Contains("r.rsml:4: <resolution> must be a positive number"), SceneError);
}

TEST_CASE("RSML writer: what it writes reads back bit for bit / nested roots / properties / metadata") {
  rsml::Document d;
  d.comment = "written by a test";
  d.meta.lastModified = "1970-01-01T00:00:00";
  d.meta.software = "rootsim";
  d.meta.fileKey = "key & <more>";
  d.meta.definitions = {{"diameter", "real", "mm"}, {"pattern", "string", ""}};
  d.meta.sequenceLabel = "seq";
  d.meta.sequenceIndex = 7;
  d.meta.unified = true;
  d.sceneProperties = {{"plane.alpha_deg", "", 40.0}, {"tropism.sensing", "local", NAN}};
  rsml::Plant p;
  p.id = "1";
  p.label = "a \"quoted\" label";
  // awkward numbers: tiny, huge, negative zero, sums that print long, a subnormal-free spread
  const std::vector<double> xs = {0.0, 1e-7, 0.1 + 0.2, -123456.789012345, 1.0 / 3.0, 999999.999999, -0.0};
  rsml::Root a;
  a.id = "main";
  a.hasZ = true;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    a.x.push_back(xs[i]);
    a.y.push_back(-xs[i] * 0.7);
    a.z.push_back(std::sqrt(static_cast<double>(i)) * 1e-3);
  }
  a.functions.push_back({"diameter", "polyline", std::vector<double>(xs.size(), 0.2), {}});
  a.functions.push_back({"curvature", "polyline", {0, 1e-9, 2.5, 3, 4, 5, 6}, {}});
  a.properties = {{"pattern", "waving", NAN}, {"wavelength_mm", "", 2.3456789}, {"skew_deg", "", NAN}};
  rsml::Root b;
  b.id = "lat";
  b.parent = 0;
  b.order = 1;
  b.x = {xs[2], 5};
  b.y = {0.5, 0.25};
  b.z = {0, 0};
  rsml::Root c = b;
  c.id = "lat.lat";
  c.parent = 1;
  c.order = 2;
  p.roots = {a, b, c};
  d.plants = {p};

  const std::string text = rsml::writeRsml(d);
  CHECK(text == rsml::writeRsml(d));  // same document, same bytes
  CHECK(text.find("<!-- written by a test -->") != std::string::npos);
  CHECK_FALSE(std::regex_search(text, std::regex("[0-9][eE][-+]?[0-9]")));  // xs:decimal: no exponents
  CHECK(text.find("skew_deg") == std::string::npos);  // NaN: left out
  const rsml::Document r = rsml::parseRsml(text, "written.rsml");
  CHECK(r.meta.unit == "mm");
  CHECK(r.mmPerUnit == 1);
  CHECK(r.meta.fileKey == "key & <more>");
  CHECK(r.meta.software == "rootsim");
  CHECK(r.meta.sequenceIndex == 7);
  CHECK(r.meta.unified);
  REQUIRE(r.meta.definitions.size() == 2);
  CHECK(r.meta.definitions[0].unit == "mm");
  CHECK(r.sceneProperty("plane.alpha_deg")->number == 40.0);
  CHECK(r.sceneProperty("tropism.sensing")->text == "local");
  REQUIRE(r.plants.size() == 1);
  CHECK(r.plants[0].label == "a \"quoted\" label");
  REQUIRE(r.plants[0].roots.size() == 3);
  CHECK(r.plants[0].roots[2].parent == 1);
  CHECK(r.plants[0].roots[2].order == 2);
  for (std::size_t k = 0; k < 3; ++k) {
    const rsml::Root& w = p.roots[k];
    const rsml::Root& g = r.plants[0].roots[k];
    CHECK(g.id == w.id);
    REQUIRE(g.points() == w.points());
    for (std::size_t i = 0; i < w.points(); ++i) {
      CHECK(same(g.x[i], w.x[i]));
      CHECK(same(g.y[i], w.y[i]));
      if (w.hasZ) CHECK(same(g.z[i], w.z[i]));
    }
  }
  const rsml::Root& g = r.plants[0].roots[0];
  REQUIRE(g.function("curvature") != nullptr);
  CHECK(g.function("curvature")->samples == a.functions[1].samples);
  CHECK(g.diameterMm == std::vector<double>(xs.size(), 0.2));
  CHECK(g.property("pattern")->text == "waving");
  CHECK(same(g.property("wavelength_mm")->number, 2.3456789));
  CHECK(g.property("skew_deg") == nullptr);
}

TEST_CASE("RSML writer: refuses what RSML cannot hold") {
  rsml::Document d;
  rsml::Plant p;
  rsml::Root a;
  a.x = {0, NAN};
  a.y = {0, 1};
  a.z = {0, 0};
  p.roots = {a};
  d.plants = {p};
  CHECK_THROWS_AS(rsml::writeRsml(d), SceneError);
  d.plants[0].roots[0].x[1] = 1;
  d.sceneProperties = {{"1bad name", "x", NAN}};
  CHECK_THROWS_AS(rsml::writeRsml(d), SceneError);
  d.sceneProperties.clear();
  d.comment = "a -- b";
  CHECK_THROWS_AS(rsml::writeRsml(d), SceneError);
}
