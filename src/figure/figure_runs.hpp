#pragma once
// Running the cases of a panel (resumably, in parallel, through the sweep runner, each as the typed
// scene of its model) and reading what the runs wrote: the typed result, the time series, the trajectory.
#include <string>
#include <vector>

#include "figure_cases.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/results.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::fig {

// runs every case not yet complete (in parallel); throws RunError if one fails
void runCases(const Ctx& c, const std::vector<Case>& cases);

// a number of a result by column name (NaN when empty or absent)
double val(const RunResult& r, const std::string& k);

// the measured and theory values of a case's run, typed (result.csv read through the one column table)
RunResult result(const Ctx& c, const Case& k);
// a case's timeseries.csv, column by column (the doubles the run wrote)
CsvColumns series(const Ctx& c, const Case& k);
// one column of a time series by name; throws RunError naming the column when it is absent
const std::vector<double>& column(const CsvColumns& t, const std::string& name);
std::vector<Snapshot> trajectory(const Ctx& c, const Case& k);

}  // namespace rootsim::fig
