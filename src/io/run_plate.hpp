#pragma once
// internal: the files a plate run writes of itself beside its roots' folders (docs/plate.md, Outputs):
// plate_timeseries.csv, and at the end plate.csv, plate.pvd and the plate's summary.json. A scene of one
// root writes none of them: its root's files are the run directory's (runSceneToDir)
#include <string>

#include "rootsim/checkpoint.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/scene.hpp"
#include "run_outputs.hpp"

namespace rootsim::detail {

// plate_timeseries.csv: its header, and the row of a growth step
std::string plateSeriesHeader();
std::string plateSeriesRow(const PlateStepRecord& r);

// the end of a plate run after its steps (RunOutputs::endSteps): every root's folder finished as a run
// directory of that root alone, then plate.csv, plate.pvd and the plate's summary.json (acc: the summary's
// extremes over the steps; wall: the run's wall time [s])
void finishPlate(RunOutputs& run, const Scene& sc, const PlateSimulation& plate, const RunAccumulators& acc,
                 double wall);

}  // namespace rootsim::detail
