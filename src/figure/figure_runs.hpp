#pragma once
// Running the cases of a panel (resumably, in parallel, through the sweep runner) and reading what the
// runs wrote: the typed result, the time series, the trajectory.
#include <map>
#include <string>
#include <vector>

#include "figure_cases.hpp"
#include "rootsim/results.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::fig {

// runs every case not yet complete (in parallel); throws RunError if one fails
void runCases(const Ctx& c, const std::vector<Case>& cases);

// a CSV file as rows of column name -> text
using Row = std::map<std::string, std::string>;
std::vector<Row> readCsv(const std::filesystem::path& p);
// a number of a row or result by column name (NaN when empty or absent)
double val(const Row& r, const std::string& k);
double val(const RunResult& r, const std::string& k);

// the measured and theory values of a case's run, typed (result.csv read through the one column table)
RunResult result(const Ctx& c, const Case& k);
std::vector<Row> series(const Ctx& c, const Case& k);
std::vector<Snapshot> trajectory(const Ctx& c, const Case& k);

}  // namespace rootsim::fig
