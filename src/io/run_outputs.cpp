// A run's outputs from start to end (run_outputs.hpp)
#include "run_outputs.hpp"

#include <exception>
#include <system_error>

#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/run_seams.hpp"
#include "run_resume.hpp"

namespace fs = std::filesystem;

namespace rootsim::detail {

RunOutputs::RunOutputs(const Scene& scene, const std::string& outDir, const RunDirOptions& o, std::string what,
                       const std::function<CheckpointSeen(const fs::path&)>& load)
    : what_(std::move(what)), output_(scene.output), dir_(outDir, o, plan(scene, outDir, o, load)) {
  noteResume(o, dir_, partial_, seen_.step, scene.model.growth.steps);
  t0_ = now();
}

PartialRun RunOutputs::plan(const Scene& scene, const std::string& outDir, const RunDirOptions& o,
                            const std::function<CheckpointSeen(const fs::path&)>& load) {
  partial_ = o.resume ? resumePlan(scene, outDir, o.force, [&](const fs::path& file) { seen_ = load(file); })
                      : PartialRun::Refuse;
  resumed_ = partial_ == PartialRun::Continue;
  if (!resumed_) seen_ = CheckpointSeen{};
  return partial_;
}

double RunOutputs::runMarkingFailure(const std::function<double()>& body) {
  // the writers go before the directory is marked, as they would if the run's body held them: a stream
  // that was not closed leaves no temporary file behind
  try {
    return body();
  } catch (const RunInterrupted&) {
    dropWriters();
    throw;  // stopped on purpose (a progress callback threw it): DIR.partial stays, like a killed run
  } catch (const std::exception& e) {
    dropWriters();
    dir_.fail(failureText(e, what_ + " into " + dir_.work().string()));
    throw;
  }
}

fs::path RunOutputs::rootFolder(const std::string& name, const std::string& sceneToml) {
  const fs::path d = dir_.work() / "roots" / name;
  std::error_code ec;
  fs::create_directories(d, ec);
  if (ec) throw RunError(d.string() + ": cannot create the root's folder: " + ec.message());
  markRunFolder(d);  // first, as every run directory's (again when it finishes, with its files listed)
  writeFileAtomic(d / "scene.toml", sceneToml);
  return d;
}

RootOutputs& RunOutputs::addRoot(const fs::path& dir, const Model& m, const Vec3& vtkOffset, const PlateRootRun* at) {
  const bool own = dir != dir_.work();
  roots_.push_back(std::make_unique<RootOutputs>(dir, m, output_, own, vtkOffset, at));
  return *roots_.back();
}

AtomicFile& RunOutputs::addStream(const std::string& name, std::uint64_t resumeBytes) {
  if (resumed_) {
    removeStaleTemps(dir_.work(), {name});
    streams_.push_back(std::make_unique<AtomicFile>(dir_.work() / name, resumeBytes));
  } else {
    streams_.push_back(std::make_unique<AtomicFile>(dir_.work() / name));
  }
  return *streams_.back();
}

void RunOutputs::growthSteps(int steps, double checkpointEvery, const RunSteps& f) {
  const StepSeams seams = stepSeams();
  double lastCheckpoint = now();
  // A run that fails keeps what its writers hold, closed so that the files are whole and readable: the
  // time series and trajectory up to the last output step before the failure, the ParaView series. The
  // directory becomes DIR.incomplete with ERROR.txt (runMarkingFailure), which marks it. (A stop on
  // purpose leaves DIR.partial as a kill does, its files where the checkpoint expects them.)
  try {
    for (int k = firstStep(); k <= steps; ++k) {
      f.grow(k);
      try {
        f.write(k);
        const bool due = seams.checkpointAfter ? seams.checkpointAfter(k) : now() - lastCheckpoint >= checkpointEvery;
        if (k < steps && due) {
          f.checkpoint(k);
          lastCheckpoint = now();
        }
      } catch (const RunError& e) {
        throw RunError(std::string(e.what()) + " (at growth step " + std::to_string(k) + " of " + std::to_string(steps) + ")");
      }
      if (seams.afterStep) seams.afterStep(k);
      f.progress(k);
    }
  } catch (const RunInterrupted&) {
    throw;
  } catch (const std::exception&) {
    closeQuietly();
    throw;
  }
}

void RunOutputs::dropWriters() {
  roots_.clear();
  streams_.clear();
}

void RunOutputs::closeQuietly() {
  for (auto& r : roots_) r->closeQuietly();
  for (auto& s : streams_) {
    try {
      s->close();
    } catch (const std::exception&) {
      // a stream that cannot close (the disk that failed the run) keeps nothing; the others still do
    }
  }
}

double RunOutputs::endSteps() {
  for (auto& r : roots_) r->close();
  for (auto& s : streams_) s->close();
  std::error_code ec;
  fs::remove(checkpointFile(), ec);
  return wall();
}

}  // namespace rootsim::detail
