// result.csv through its one column table (src/io/results.cpp): header and row always agree, and what is
// written reads back to the same values
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "rootsim/errors.hpp"
#include "rootsim/results.hpp"
#include "test_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
int cells(const std::string& line) {
  int n = 1;
  for (char c : line) n += c == ',';
  return n;
}
}  // namespace

TEST_CASE("result.csv: header and row have the same columns, and a written result reads back") {
  Model m = rootsim::test::coarseModel();
  m.name = "t";
  Simulation sim(m);
  for (int k = 0; k < 10; ++k) sim.growthStep();
  const ShapeAnalysis a = analyseShape(m, sim.state());
  const RunResult r = makeResult(m, sim, &a, 0.25);
  const std::string csv = resultCsv(r);
  std::istringstream in(csv);
  std::string head, row;
  std::getline(in, head);
  std::getline(in, row);
  CHECK(head == resultHeader(true));
  CHECK(cells(head) == cells(row));
  CHECK(cells(head) == static_cast<int>(resultColumns().size()));
  const fs::path p = rootsim::test::scratchDir("result", "round_trip") / "result.csv";
  { std::ofstream(p) << csv; }
  const RunResult b = readResult(p);
  CHECK(b.grows);
  CHECK(b.scene == "t");
  CHECK(b.pattern == r.pattern);
  CHECK(b.steps == 10);
  CHECK(b.lengthMm == doctest::Approx(r.lengthMm).epsilon(1e-9));
  CHECK(b.T0h == doctest::Approx(r.T0h).epsilon(1e-9));
  ROOTSIM_CHECK_CLOSE(b.snapOrTurningH, 0.25, kRoundoff);
  CHECK(std::isnan(b.wavelengthMm) == std::isnan(r.wavelengthMm));
  ROOTSIM_CHECK_CLOSE(b.number("alpha_deg"), 40, kRoundoff);
  // mechanics-only runs have only the first columns
  RunResult mech = r;
  mech.grows = false;
  CHECK(cells(resultHeader(false)) == 8);
  { std::ofstream(p) << resultCsv(mech); }
  CHECK_FALSE(readResult(p).grows);
  // another header is refused by name
  { std::ofstream(p) << "scene,status\nx,complete\n"; }
  CHECK_THROWS_AS(readResult(p), RunError);
  fs::remove(p);
}
