#pragma once
// internal: what a resumed run (RunOutputs, --resume) checks and cleans before it continues an interrupted
// run directory DIR.partial: the plan (continue, discard, refuse), the checkpoint's scene and its streams'
// lengths, and the leftovers of atomic writes a kill interrupted
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rootsim/checkpoint.hpp"
#include "rootsim/output_params.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"

namespace rootsim::detail {

// what to do with an interrupted run DIR.partial when resuming: continue it from its
// checkpoint (load(checkpoint file) read it: it throws SceneError when the checkpoint cannot be used),
// discard it, or refuse. The same for a run of one root and a plate.
PartialRun resumePlan(const Scene& sc, const std::string& outDir, bool force,
                      const std::function<void(const std::filesystem::path&)>& load);
// what a resumed run says it does (RunDirOptions::note)
void noteResume(const RunDirOptions& o, const RunDir& rd, PartialRun partial, int step, int steps);
// the streams of a root's folder hold at least what its checkpoint saw (before anything is touched);
// throws SceneError naming the file
void checkStreamLengths(const std::filesystem::path& dir, const OutputParams& o, const WriterPositions& w);
void checkStreamLength(const std::filesystem::path& file, std::uint64_t bytes);
// a checkpoint of this scene (its hash: sceneHash of the resolved scene); throws SceneError naming the file
void checkSceneHash(const std::filesystem::path& file, std::uint64_t found, std::uint64_t expected);
// "FILE:LINE: KEY is A there, B in SCENE" for the first key where two resolved scenes differ (file: where
// `written` was read)
std::string sceneDifference(const std::string& file, const std::string& written, const std::string& current,
                            const std::string& scenePath);
// removes the leftovers of atomic writes a kill interrupted in dir and dir/vtk, but the streams being
// continued (names: their final names)
void removeStaleTemps(const std::filesystem::path& dir, const std::vector<std::string>& streams);
// the streams a root continues (RootStreams)
inline const std::vector<std::string> kRootStreams = {"timeseries.csv", "trajectory.csv", "trajectory.bin"};

}  // namespace rootsim::detail
