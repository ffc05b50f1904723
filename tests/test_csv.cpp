// The one CSV reader (src/io/csv.cpp, RFC 4180): cells of a record, records over several lines, the
// numeric column reader on quoted headers, the writer's quoting read back, malformed records named by
// file and line.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "test_support.hpp"

using namespace rootsim;
using Cells = std::vector<std::string>;
namespace fs = std::filesystem;

namespace {
using rootsim::test::kScene;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("csv", name); }
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("csv: a record's cells - plain and quoted fields with commas and doubled quotes") {
  CHECK(csvCells("a,b,c") == Cells{"a", "b", "c"});
  CHECK(csvCells("") == Cells{""});
  CHECK(csvCells("a,") == Cells{"a", ""});
  CHECK(csvCells(",") == Cells{"", ""});
  CHECK(csvCells("\"x,y\",2") == Cells{"x,y", "2"});
  CHECK(csvCells("\"say \"\"hi\"\"\",\"\"") == Cells{"say \"hi\"", ""});
  CHECK(csvCells("\"line\none\",3") == Cells{"line\none", "3"});
  // a quote inside an unquoted field is an ordinary character (as spreadsheets read it)
  CHECK(csvCells("5\" pot,1") == Cells{"5\" pot", "1"});
}

TEST_CASE("csv: a malformed record - an open quote or text after a closing quote") {
  CHECK_THROWS_WITH_AS(csvCells("\"open,1"), doctest::Contains("not closed"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(csvCells("\"a\"b,1"), doctest::Contains("text after a quoted field's closing quote (cell 1)"),
                       std::invalid_argument);
}

TEST_CASE("csv: what csvField and csvQuoted write reads back as the same text") {
  const std::vector<std::string> texts = {"plain", "with,comma", "with \"quote\"", "two\nlines", "", "\"", ",,"};
  std::string row;
  for (const std::string& t : texts) row += (row.empty() ? "" : ",") + csvField(t);
  CHECK(csvCells(row) == texts);
  row.clear();
  for (const std::string& t : texts) row += (row.empty() ? "" : ",") + csvQuoted(t);
  CHECK(csvCells(row) == texts);
  CHECK(csvField("plain") == "plain");
  CHECK(csvQuoted("plain") == "\"plain\"");
  CHECK(csvQuoted("a\"b") == "\"a\"\"b\"");
}

TEST_CASE("csv: records over several lines - line numbers and CRLF and an unclosed quote at the end") {
  std::istringstream in("name,note\r\nA,\"two\nlines\"\r\nB,plain\n");
  Cells f;
  int line = 0;
  REQUIRE(readCsvRecord(in, f, line, "t.csv"));
  CHECK(f == Cells{"name", "note"});
  CHECK(line == 1);
  REQUIRE(readCsvRecord(in, f, line, "t.csv"));
  CHECK(f == Cells{"A", "two\nlines"});
  CHECK(line == 3);
  REQUIRE(readCsvRecord(in, f, line, "t.csv"));
  CHECK(f == Cells{"B", "plain"});
  CHECK(line == 4);
  CHECK_FALSE(readCsvRecord(in, f, line, "t.csv"));

  std::istringstream open("a,b\n1,\"never\nclosed\n");
  line = 0;
  REQUIRE(readCsvRecord(open, f, line, "open.csv"));
  CHECK_THROWS_WITH_AS(readCsvRecord(open, f, line, "open.csv"),
                       doctest::Contains("open.csv:2: a quoted field is not closed before the end of the file"), SceneError);
  std::istringstream after("a,b\n\"x\"y,1\n");
  line = 0;
  REQUIRE(readCsvRecord(after, f, line, "after.csv"));
  CHECK_THROWS_WITH_AS(readCsvRecord(after, f, line, "after.csv"), doctest::Contains("after.csv:2: text after"), SceneError);
}

TEST_CASE("csv: readCsvColumns reads a quoted header and names a bad cell by file and line") {
  const auto d = test::scratchDir("csv", "columns");
  {
    std::ofstream f(d / "q.csv");
    f << "\"a,1\",\"b \"\"x\"\"\"\r\n1,2\r\n\r\n3.5,-4\r\n";
  }
  const CsvColumns c = readCsvColumns(d / "q.csv");
  CHECK(c.names == Cells{"a,1", "b \"x\""});
  REQUIRE(c.values.size() == 2);
  CHECK(c.values[0] == std::vector<double>{1, 3.5});
  CHECK(c.values[1] == std::vector<double>{2, -4});
  {
    std::ofstream f(d / "bad.csv");
    f << "a,b\n1,\"2\n\"x\n";
  }
  CHECK_THROWS_WITH_AS(readCsvColumns(d / "bad.csv"), doctest::Contains("bad.csv:3: text after"), SceneError);
}

TEST_CASE("timeseries.csv reads back as the very doubles of the run's step records") {
  const fs::path d = scratch("csv");
  const Scene sc = loadScene(kScene, {"growth.steps=60"});
  std::vector<StepRecord> seen;
  runSceneToDir(sc, (d / "run").string(), {}, [&](const StepRecord& r, int) { seen.push_back(r); });
  const CsvColumns t = readCsvColumns(d / "run" / "timeseries.csv");
  REQUIRE(t.names.size() > 20);
  CHECK(t.names[0] == "step");
  CHECK(t.names[2] == "length_mm");
  REQUIRE(t.values[0].size() == 7);  // step 0 and every 10th
  for (size_t row = 1; row < t.values[0].size(); ++row) {
    const StepRecord& r = seen[static_cast<size_t>(t.values[0][row]) - 1];
    CHECK(sameBits(t.values[2][row], r.length / units::mm));
    CHECK(sameBits(t.values[4][row], r.thetaTip / units::deg));
  }
  // a malformed cell is named with file and line
  { std::ofstream(d / "bad.csv") << "a,b\n1,2\n3,x4\n"; }
  CHECK_THROWS_WITH_AS(readCsvColumns(d / "bad.csv"), doctest::Contains("bad.csv:3: b: expected a number (got \"x4\")"),
                       SceneError);
  fs::remove_all(d);
}


TEST_CASE("shape.csv reads back (readCsvColumns) as the very doubles of the state's arc length and positions") {
  const fs::path d = scratch("shape");
  const rootsim::test::GrownRoot g;
  const RodState& s = g.sim.state();
  { std::ofstream(d / "shape.csv", std::ios::binary) << shapeCsv(g.m, s, g.k); }
  const CsvColumns c = readCsvColumns(d / "shape.csv");
  REQUIRE(c.names.size() == 21);
  CHECK(c.names[0] == "s_mm");
  CHECK(c.names[1] == "x_mm");
  CHECK(c.names[17] == "radius_mm");
  CHECK(c.names[18] == "lateral_mm");
  CHECK(c.names[19] == "downhill_mm");
  CHECK(c.names[20] == "height_mm");
  // the plate coordinates: the lab position in the plate's frame (lateral, downhill, height)
  const PlateFrame plate = g.m.env.plane.frame();
  REQUIRE(c.values[0].size() == static_cast<size_t>(s.nodes()));
  for (int i = 0; i < s.nodes(); ++i) {
    CAPTURE(i);
    const auto row = static_cast<size_t>(i);
    CHECK(sameBits(c.values[0][row], s.S[i] / units::mm));
    for (int a = 0; a < 3; ++a) CHECK(sameBits(c.values[static_cast<size_t>(1 + a)][row], s.x(a, i) / units::mm));
    const Vec3 onPlate = plate.coords(s.x.col(i)) / units::mm;
    for (int a = 0; a < 3; ++a) CHECK(sameBits(c.values[static_cast<size_t>(18 + a)][row], onPlate[a]));
    // the node frame: unit directors
    for (int v = 0; v < 3; ++v) {
      const Vec3 dv(c.values[static_cast<size_t>(4 + 3 * v)][row], c.values[static_cast<size_t>(5 + 3 * v)][row],
                    c.values[static_cast<size_t>(6 + 3 * v)][row]);
      CHECK(dv.norm() == doctest::Approx(1.0).epsilon(1e-12));
    }
  }
  // curvature: the Voronoi value per current length at interior nodes [1/mm], 0 at the two ends
  for (int a = 0; a < 3; ++a) {
    CHECK(c.values[static_cast<size_t>(13 + a)].front() == 0.0);
    CHECK(c.values[static_cast<size_t>(13 + a)].back() == 0.0);
    const int i = s.nodes() / 2;
    CHECK(sameBits(c.values[static_cast<size_t>(13 + a)][static_cast<size_t>(i)],
                   g.k.kappa(a, i - 1) / g.k.ev[i - 1] * units::mm));
  }
  fs::remove_all(d);
}
