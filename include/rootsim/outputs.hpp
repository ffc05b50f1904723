#pragma once
// The files of a run directory (docs/cli.md, "Run directory"; docs/outputs.md), one header per format:
// csv.hpp (shape.csv, timeseries.csv, modes.csv and their reader), trajectory.hpp (trajectory.csv / .bin),
// vtk.hpp (ParaView), json.hpp (summary.json).
#include "rootsim/csv.hpp"
#include "rootsim/json.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/paraview.hpp"
#include "rootsim/vtk.hpp"
