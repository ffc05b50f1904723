// summary.json (src/io/json.cpp, the JSON writer; a run's summary): its numbers read back exactly, NaN
// as null, strings escaped, and a run's summary agreeing with its time series. The other files of a
// run directory have their own tests: test_csv.cpp, test_trajectory.cpp, test_vtk.cpp.
#include <doctest/doctest.h>

#include <filesystem>
#include <limits>
#include <string>

#include "rootsim/outputs.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::kScene;
using rootsim::test::slurp;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("outputs", name); }
}  // namespace

TEST_CASE("summary.json: the JSON writer's numbers read back exactly, NaN is null, strings are escaped, and a run's summary agrees with its time series") {
  Json inner;
  inner.num("nan", std::numeric_limits<double>::quiet_NaN()).num("inf", std::numeric_limits<double>::infinity());
  Json j;
  j.num("x", 0.1 + 0.2).integer("n", -9007199254740991LL).str("s", "a\"b\\c\nd").boolean("t", true).object("o", inner);
  const std::string text = j.dump();
  CAPTURE(text);
  CHECK(text.front() == '{');
  CHECK(text.back() == '}');
  auto valueOf = [&](const std::string& key) {
    const auto at = text.find("\"" + key + "\": ");
    REQUIRE(at != std::string::npos);
    const auto from = at + key.size() + 4;
    return text.substr(from, text.find_first_of(",\n", from) - from);
  };
  CHECK(std::stod(valueOf("x")) == 0.1 + 0.2);
  CHECK(valueOf("n") == "-9007199254740991");
  CHECK(valueOf("t") == "true");
  CHECK(valueOf("nan") == "null");
  CHECK(valueOf("inf") == "null");
  CHECK(text.find(R"("s": "a\"b\\c\nd")") != std::string::npos);
  // a run's summary.json: its final step and length are the time series' last row
  const fs::path d = scratch("summary");
  const Scene sc = loadScene(kScene, {"growth.steps=30", "root.element_length_mm=0.1", "output.vtk=false"});
  runSceneToDir(sc, (d / "run").string(), {}, [](const StepRecord&, int) {});
  const std::string summary = slurp(d / "run" / "summary.json");
  const CsvColumns t = readCsvColumns(d / "run" / "timeseries.csv");
  REQUIRE(t.names[2] == "length_mm");
  const double lastLength = t.values[2].back();
  const auto at = summary.find("\"length_mm\": ");
  REQUIRE_MESSAGE(at != std::string::npos, summary);
  CHECK(std::stod(summary.substr(at + 13)) == lastLength);
  CHECK(summary.find("\"steps\": 30,") != std::string::npos);
  CHECK(t.values[0].back() == 30);
  fs::remove_all(d);
}
