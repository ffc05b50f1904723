#pragma once
// What a run writes (a scene's [output] keys, docs/outputs.md): io's, held by the Scene beside the
// physics' Model, which never needs it.
namespace rootsim {

// how the trajectory is written (docs/outputs.md)
enum class TrajectoryFormat {
  Binary,  // trajectory.bin: raw little-endian doubles, about half the CSV (docs/outputs.md), read back exactly
  Csv,     // trajectory.csv: one text row per node and snapshot
  Both     // both files
};

struct OutputParams {
  int everySteps = 10;             // snapshot and time-series row every this many growth steps
  bool trajectory = true;          // write the trajectory (needed by `rootsim render`)
  TrajectoryFormat trajectoryFormat = TrajectoryFormat::Binary;
  bool vtk = true;                 // write ParaView .vtp snapshots and trajectory.pvd
  double checkpointEvery = 60.0;   // a growing run writes DIR.partial/checkpoint.bin after the first growth
                                   // step at least this much wall time after the last one [s] (0: every step)
};

}  // namespace rootsim
