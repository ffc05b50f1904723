// rootsim._rootsim: the C++ side of the Python package. Thin: it calls the library the command
// line calls (loadScene, runSceneToDir, the run-directory readers, runSweep, the `render` command) and turns
// its results into numpy arrays and dicts, in the units of the run directory's files (lengths mm, time h,
// angles deg, forces N; docs/python.md, Units). The Python layer (rootsim/_api.py) adds the user-facing API.
//
// Threads: the GIL is released while simulating, sweeping and rendering; it is taken back between growth
// steps to poll Python's signal handlers (Ctrl-C -> KeyboardInterrupt) and to call progress callbacks.
// A _Simulation serialises calls from several threads with a mutex of its own (PySimulation).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>
#include <utility>

#include "commands.hpp"
#include "options.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/results.hpp"
#include "rootsim/rod_fields.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/units.hpp"
#include "rootsim/version.hpp"
#include "convert.hpp"

#include "rootsim/analyze_traces.hpp"
#include "rootsim/trace_growth.hpp"
#include "rootsim/compare_trace.hpp"
#include "rootsim/fit_trace.hpp"
#ifdef ROOTSIM_HAVE_RENDER
#include "rootsim/export_run.hpp"
#include "rootsim/render_run.hpp"
#endif

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace rootsim;

namespace {

// the Python exception classes (created once, alive as long as the interpreter: never released)
PyObject* gSceneError = nullptr;  // rootsim.SceneError(ValueError): bad scene, key, value, flag or path
PyObject* gRunError = nullptr;    // rootsim.RunError(RuntimeError): a run that started and failed

// ---- a command's keywords ----

// rootsim.<command>'s keywords (a dict, positionals included) into the command's options struct through
// its table (src/cli/options.hpp), as the command line's flags: None leaves the default; an unknown name or
// a value of the wrong type is a SceneError naming the command
template <class O>
O commandOptions(const std::string& name, const py::dict& options) {
  const cli::CommandSpec& spec = cli::command(name);
  const std::shared_ptr<O> o = spec.makeAs<O>();
  for (const auto& item : options) {
    const std::string key = py::str(item.first);
    const cli::OptionSpec* s = spec.find(key);
    if (s == nullptr) throw SceneError(name + ": unknown option " + key);
    const py::handle v = item.second;
    if (v.is_none()) continue;
    std::string refused;  // the table's range or choices, as the command line checks them
    try {
      switch (s->kind) {
        case cli::OptionKind::Text: {
          const std::string t = py::str(v);
          refused = cli::checkText(spec, *s, t);
          cli::setText(*s, o.get(), t);
          break;
        }
        case cli::OptionKind::Texts: cli::setTexts(*s, o.get(), v.cast<std::vector<std::string>>()); break;
        case cli::OptionKind::Int: {
          const int n = v.cast<int>();
          refused = cli::checkNumber(spec, *s, n);
          cli::setInt(*s, o.get(), n);
          break;
        }
        case cli::OptionKind::Real: {
          const double x = v.cast<double>();
          refused = cli::checkNumber(spec, *s, x);
          cli::setReal(*s, o.get(), x);
          break;
        }
        case cli::OptionKind::Flag: cli::setFlag(*s, o.get(), s->negated() != v.cast<bool>()); break;
      }
    } catch (const py::cast_error&) {
      throw SceneError(name + ": option " + key + " has the wrong type");
    }
    if (!refused.empty()) throw SceneError(refused);
    cli::markGiven(*s, o.get(), true);
  }
  return *o;
}

// every command's options as rootsim.<command>'s keywords: name -> list of (keyword, flag, kind, default,
// unit, help, required, positional)
py::dict commandTable() {
  static const char* kKind[] = {"text", "texts", "int", "real", "flag"};
  py::dict d;
  for (const cli::CommandSpec& c : cli::commands()) {
    py::list l;
    for (const cli::OptionSpec& o : c.options)
      l.append(py::make_tuple(o.pythonName(), o.displayName(), kKind[static_cast<int>(o.kind)], cli::defaultText(c, o),
                              o.unit, o.help, o.required, o.positional()));
    d[py::str(c.name)] = l;
  }
  return d;
}

// ---- numpy helpers ----

// a (cols x 3) float64 copy of a 3 x cols Eigen matrix (column-major: the same memory layout)
py::array_t<double> rows3(const Eigen::Matrix3Xd& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.cols()), py::ssize_t{3}});
  if (m.size() > 0) std::memcpy(a.mutable_data(), m.data(), sizeof(double) * static_cast<size_t>(m.size()));
  return a;
}
py::array_t<double> vec(const Eigen::VectorXd& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  if (v.size() > 0) std::memcpy(a.mutable_data(), v.data(), sizeof(double) * static_cast<size_t>(v.size()));
  return a;
}
// the units of the package (docs/python.md, Units): those of the run directory's files, named in the
// field (lengths mm, time h, forces N); SI values (Snapshot, RodState) are divided by units::* here only
// (the same operations as the writers: a length / units::mm, a curvature * units::mm)
py::array_t<double> rows3Mm(const Eigen::Matrix3Xd& m) { return rows3(Eigen::Matrix3Xd(m / units::mm)); }
py::array_t<double> vecMm(const Eigen::VectorXd& v) { return vec(Eigen::VectorXd(v / units::mm)); }

// plate coordinates (lateral, downhill, height above the plate) of lab points [m], in mm, by the core's
// PlateFrame::coords of the scene's plate (plane.alpha_deg; its origin the foot of the base node). Put in
// d as lateral_mm, downhill_mm, height_mm (one array of nodes each).
void putPlateCoords(py::dict& d, const PlateFrame& f, const Eigen::Matrix3Xd& labM) {
  Eigen::Matrix3Xd c(3, labM.cols());
  for (Eigen::Index i = 0; i < labM.cols(); ++i) c.col(i) = f.coords(labM.col(i)) / units::mm;
  d["lateral_mm"] = vec(c.row(0).transpose());
  d["downhill_mm"] = vec(c.row(1).transpose());
  d["height_mm"] = vec(c.row(2).transpose());
}

}  // namespace

// the converters the other binding files share (convert.hpp)
namespace rootsim::pyconv {

// one snapshot as a dict of numpy arrays, in the package's units (trajectory.csv's: x_mm, radius_mm,
// kappa0_per_mm, plate_force_n, ...), with the nodes' plate coordinates in the frame f
py::dict snapshotDict(const Snapshot& s, const PlateFrame& f) {
  py::dict d;
  d["step"] = s.step;
  d["time_h"] = s.timeH;
  d["positions_mm"] = rows3Mm(s.x);
  putPlateCoords(d, f, s.x);
  d["d1"] = rows3(s.d1);
  d["d3"] = rows3(s.d3);
  d["radius_mm"] = vecMm(s.radius);
  d["kappa0_per_mm"] = s.kappa0.size() ? py::object(vec(Eigen::VectorXd(s.kappa0 * units::mm))) : py::object(py::none());
  d["plate_force_n"] = s.plateForce.size() ? py::object(vec(s.plateForce)) : py::object(py::none());
  d["contact_force_n"] = s.contactForce.size() ? py::object(rows3(s.contactForce)) : py::object(py::none());
  return d;
}

// one time-series row: timeseries.csv's columns (timeseriesColumns: the writer's own), so the values are
// the doubles the file holds
py::dict recordDict(const StepRecord& r) {
  py::dict d;
  for (const RecordColumn& c : timeseriesColumns()) {
    if (c.real) d[c.name] = c.real(r);
    else d[c.name] = c.whole(r);
  }
  return d;
}

// one listed field of the rod state (rod_fields.hpp) as a copy in the package's units (its Unit); a 3x3 frame
// (rows d1 d2 d3) as frame[r] = d_{r+1}, a flag array as bool
template <class T>
py::object stateField(const T& v, Unit unit) {
  // the writers' operations: a length / units::mm, a time / units::hour, a curvature * units::mm
  auto scaled = [&](const auto& m) {
    using M = std::remove_cvref_t<decltype(m)>;
    if (unit == Unit::Length) return M(m / units::mm);
    if (unit == Unit::Time) return M(m / units::hour);
    if (unit == Unit::Curvature) return M(m * units::mm);
    return M(m);
  };
  static_assert(sizeof(Mat3) == 9 * sizeof(double), "directors must be packed 3x3 doubles");
  // Q is column-major: Q(r, c) at r + 3c; frame[r, c] = Q(r, c)
  auto frames = [](const Mat3* q, py::ssize_t count, std::vector<py::ssize_t> shape) {
    py::array_t<double> a(shape);
    double* out = a.mutable_data();
    for (py::ssize_t e = 0; e < count; ++e) {
      const double* Q = q[e].data();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out[9 * e + 3 * r + c] = Q[r + 3 * c];
    }
    return a;
  };
  if constexpr (std::is_same_v<T, Eigen::Matrix3Xd>) {
    return rows3(scaled(v));
  } else if constexpr (std::is_same_v<T, Eigen::VectorXd>) {
    return vec(scaled(v));
  } else if constexpr (std::is_same_v<T, std::vector<Mat3>>) {
    if (unit != Unit::None) throw std::logic_error("a frame has no unit");
    const auto n = static_cast<py::ssize_t>(v.size());
    return frames(v.data(), n, {n, 3, 3});
  } else if constexpr (std::is_same_v<T, Mat3>) {
    if (unit != Unit::None) throw std::logic_error("a frame has no unit");
    return frames(&v, 1, {3, 3});
  } else if constexpr (std::is_same_v<T, std::vector<std::uint8_t>>) {
    py::array_t<bool> a(static_cast<py::ssize_t>(v.size()));
    bool* out = a.mutable_data();
    for (size_t i = 0; i < v.size(); ++i) out[i] = v[i] != 0;
    return a;
  } else {
    static_assert(std::is_same_v<T, double>, "a rod state field Python cannot show");
    return py::float_(unit == Unit::Length ? v / units::mm
                      : unit == Unit::Time ? v / units::hour
                      : unit == Unit::Curvature ? v * units::mm
                                                : v);
  }
}

// the state as copies (owned, C-contiguous numpy arrays): they stay valid whatever the Simulation does
// next (growth reallocates its arrays when it splits elements). Every field of the rod state's list
// (rod_fields.hpp) under its Python name, the step, and the nodes' plate coordinates.
py::dict stateDict(const Simulation& sim, const PlateFrame& f) {
  const RodState& s = sim.state();
  py::dict d;
  d["step"] = sim.step();
  forEachField<RodState>([&](const auto& field) { d[field.python] = stateField(s.*field.member, field.unit); });
  putPlateCoords(d, f, s.x);
  return d;
}

// the names stateDict gives the rod state's fields, in the list's order, each with where it lives
// ("node", "element", "voronoi": one value per node, element or interior node; "rod": one)
const char* alongName(Along a) {
  return a == Along::Node ? "node" : a == Along::Element ? "element" : a == Along::Voronoi ? "voronoi" : "rod";
}
py::list stateFieldNames() {
  py::list l;
  forEachField<RodState>([&](const auto& field) { l.append(py::make_tuple(field.python, alongName(field.along))); });
  return l;
}

}  // namespace rootsim::pyconv

namespace {

using namespace rootsim::pyconv;

// ---- readers of a run directory (the library's; nothing parsed twice) ----

py::dict readCsv(const std::string& path) {
  CsvColumns t;
  {
    py::gil_scoped_release nogil;
    t = readCsvColumns(path);
  }
  py::dict d;
  for (size_t c = 0; c < t.names.size(); ++c) {
    py::array_t<double> a(static_cast<py::ssize_t>(t.values[c].size()));
    if (!t.values[c].empty()) std::memcpy(a.mutable_data(), t.values[c].data(), sizeof(double) * t.values[c].size());
    d[py::str(t.names[c])] = a;
  }
  return d;
}

py::list readFrames(const std::string& path, const Scene& sc) {
  const PlateFrame f = sc.model.env.plane.frame();
  std::vector<Snapshot> snaps;
  {
    py::gil_scoped_release nogil;
    snaps = readTrajectory(path);
  }
  py::list l;
  for (const Snapshot& s : snaps) l.append(snapshotDict(s, f));
  return l;
}

py::dict readResultDict(const std::string& path) {
  const RunResult r = readResult(path);
  py::dict d;
  for (const ResultColumn& c : resultColumns()) {
    if (c.growthOnly && !r.grows) continue;
    if (c.text) d[c.name] = r.*c.str;
    else d[c.name] = r.*c.num;
  }
  return d;
}

// ---- Ctrl-C and progress callbacks between growth steps ----

// the hook runSceneToDir calls after every growth step (GIL released while simulating): takes the GIL,
// runs Python's signal handlers and the user's callback; a Python exception is kept and the run stopped
// with RunInterrupted (DIR.partial stays), then raised again by rethrowIfKept
class StepHook {
 public:
  explicit StepHook(py::object progress) : progress_(std::move(progress)) {}
  void operator()(const StepRecord& r, int total) {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress_.is_none()) progress_(r.step, total);
    } catch (py::error_already_set& e) {
      kept_.emplace(std::move(e));
      throw RunInterrupted("stopped at growth step " + std::to_string(r.step) + " of " + std::to_string(total));
    }
  }
  void rethrowIfKept() {
    if (kept_) {
      py::error_already_set e = std::move(*kept_);
      kept_.reset();
      throw e;
    }
  }

 private:
  py::object progress_;
  std::optional<py::error_already_set> kept_;
};

// rootsim.run: the run command (cli::runLoaded) on the Python Scene, its other options (out, movie and the
// look, force, resume, quiet) by name through the command's table; returns the run directory
std::string runScene(const Scene& sc, const py::dict& options, py::object progress) {
  const cli::RunOptions o = commandOptions<cli::RunOptions>("run", options);
  StepHook hook(std::move(progress));
  try {
    py::gil_scoped_release nogil;
    cli::runLoaded(sc, o, [&](const StepRecord& r, int n) { hook(r, n); });
  } catch (const RunInterrupted&) {
    hook.rethrowIfKept();
    throw;
  }
  return normaliseOutDir(o.out.empty() ? (fs::path("runs") / sc.model.name).string() : o.out).string();
}

// ---- stepping ----

// One root per Python object, stepped as `rootsim run` steps it: a plate of one seedling (plateOfOne), used
// by one thread at a time (CallMutex: calls from several threads are serialised, a call from inside its own
// step() raises RuntimeError).
class PySimulation {
 public:
  explicit PySimulation(const Scene& sc) : scene_(sc) {
    // a plate's roots step together (their contacts, their laterals): a Simulation of its first root alone
    // would silently be another run
    if (scene_.isPlate())
      throw SceneError("rootsim.Simulation(" + scene_.path + "): the scene is a plate of " +
                       std::to_string(scene_.plate.seedlings.size()) + " seedling(s)" +
                       (scene_.plate.params.laterals.enabled ? " with laterals" : "") +
                       "; a _Simulation steps one root: step the plate with rootsim.Plate (docs/python.md)");
    py::gil_scoped_release nogil;
    const PlateSpec one = plateOfOne(scene_.model);
    plate_.emplace(one.params, one.seedlings);
  }
  // n growth steps; between steps the GIL is taken to poll Ctrl-C (KeyboardInterrupt after a whole step).
  // Refused (nothing run) beyond growth.steps: the scene's validation bounds the root's element count
  // (kMaxElements) only up to growth.steps; and before each step whose splits could pass kMaxElements.
  py::dict step(long long n) {
    Lock lock = acquire();
    if (n < 1) throw py::value_error("step(n): n must be a positive integer (got " + std::to_string(n) + ")");
    const GrowthParams& g = scene_.model.growth;
    if (!g.enabled) throw SceneError(scene_.model.name + ": growth.enabled = false: nothing to step");
    const long long left = static_cast<long long>(g.steps) - sim().step();
    if (n > left)
      throw py::value_error("step(" + std::to_string(n) + "): only " + std::to_string(std::max(left, 0LL)) +
                            " growth steps left of growth.steps = " + std::to_string(g.steps) + " (at step " +
                            std::to_string(sim().step()) + "; build a Simulation with a larger growth.steps)");
    for (long long k = 0; k < n; ++k) {
      checkElementCap(n, k);
      {
        py::gil_scoped_release nogil;
        plate_->growthStep();
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    return recordDict(sim().last());
  }
  // tropism.* keys between steps, validated by the scene schema (the same messages as --set)
  void set(const std::string& key, const std::string& value) {
    Lock lock = acquire();
    if (key.rfind("tropism.", 0) != 0)
      throw SceneError("Simulation.set " + key + ": only tropism.* keys can change between growth steps (the rest "
                       "of the model is constant; build a new Simulation)");
    overrides_.push_back(key + "=" + value);
    Scene changed;
    try {
      changed = parseScene(scene_.resolvedToml, scene_.path.empty() ? scene_.model.name : scene_.path, overrides_);
    } catch (...) {
      overrides_.pop_back();
      throw;
    }
    plate_->setTropism(0, changed.model.tropism);
  }
  // the state as copies (stateDict)
  py::dict state() {
    Lock lock = acquire();
    return stateDict(sim(), scene_.model.env.plane.frame());
  }
  py::dict record() {
    Lock lock = acquire();
    return recordDict(sim().last());
  }
  py::dict snapshot() {
    Lock lock = acquire();
    return snapshotDict(sim().snapshot(), scene_.model.env.plane.frame());
  }
  int stepCount() {
    Lock lock = acquire();
    return sim().step();
  }
  // growth steps left before growth.steps (0 for a mechanics-only scene)
  int stepsLeft() {
    Lock lock = acquire();
    return scene_.model.growth.enabled ? std::max(scene_.model.growth.steps - sim().step(), 0) : 0;
  }
  const Scene& scene() const { return scene_; }  // constant after construction: no lock

 private:
  using Lock = CallMutex::Lock;
  Lock acquire() { return mu_.acquire("Simulation"); }
  const Simulation& sim() const { return plate_->root(0); }
  // before growth step k (0-based) of step(n): an element splits at most once per step, and only when
  // its rest length, grown by at most the factor 1 + rate * dt, passes growth.split_factor * h
  void checkElementCap(long long n, long long k) const {
    const RodState& s = sim().state();
    const GrowthParams& g = scene_.model.growth;
    const double limit = g.splitFactor * scene_.model.initial.elementLength, grow = 1.0 + g.rate * g.stepTime;
    long long could = 0;
    for (int i = 0; i < s.elements(); ++i)
      if (s.l0[i] * grow > limit) ++could;
    if (static_cast<double>(s.elements() + could) > kMaxElements)
      throw std::runtime_error("step(" + std::to_string(n) + "): stopped after " + std::to_string(k) +
                               " of them, at growth step " + std::to_string(sim().step()) + ": the rod has " +
                               std::to_string(s.elements()) + " elements and the next step could split " +
                               std::to_string(could) + " more, past the cap of " +
                               std::to_string(static_cast<long long>(kMaxElements)) + " elements");
  }

  Scene scene_;
  std::vector<std::string> overrides_;
  std::optional<PlateSimulation> plate_;
  CallMutex mu_;
};

// ---- sweeps: runSweep on a thread of its own, results handed over as they finish ----

class SweepRunner {
 public:
  // rootsim.sweep's keywords (sweep_file, out, jobs, shard, force, quiet) through the sweep command's table
  explicit SweepRunner(const py::dict& options) {
    const cli::SweepCliOptions o = commandOptions<cli::SweepCliOptions>("sweep", options);
    plan_ = loadSweep(o.sweep);
    opt_.force = o.force;
    opt_.inputs = {o.sweep, plan_.scenePath};
    opt_.jobs = o.jobs;
    if (!o.shard.empty()) std::tie(opt_.shard, opt_.shards) = parseShard(o.shard);
    opt_.out = o.out.empty() ? (fs::path("runs") / fs::path(o.sweep).stem()).string() : o.out;
    opt_.quiet = true;  // no per-run progress; the sweep's own lines with quiet=False, as the command line's
    if (!o.quiet) log_ = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    opt_.cancelled = [this] { return cancel_.load(); };
    opt_.onPoint = [this](const SweepPointDone& d) {
      std::lock_guard<std::mutex> lock(mu_);
      done_.push_back(d);
      cv_.notify_all();
    };
    thread_ = std::thread([this] {
      try {
        result_ = runSweep(plan_, opt_, log_);
      } catch (...) {
        error_ = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mu_);
      finished_ = true;
      cv_.notify_all();
    });
  }
  ~SweepRunner() {
    cancel_ = true;
    if (thread_.joinable()) {
      py::gil_scoped_release nogil;
      thread_.join();
    }
  }
  // the next finished point as a dict, or None when the sweep is over; Ctrl-C raises KeyboardInterrupt
  py::object next() {
    for (;;) {
      std::optional<SweepPointDone> d;
      bool over = false;
      {
        py::gil_scoped_release nogil;
        std::unique_lock<std::mutex> lock(mu_);
        cv_.wait_for(lock, std::chrono::milliseconds(100), [this] { return !done_.empty() || finished_; });
        if (!done_.empty()) {
          d = done_.front();
          done_.pop_front();
        } else {
          over = finished_;
        }
      }
      if (d) {
        py::dict r;
        r["index"] = d->point->index;
        r["name"] = d->point->dirName;
        py::dict grid;
        for (const auto& [k, v] : d->point->grid) grid[py::str(k)] = v;
        r["grid"] = grid;
        r["dir"] = d->dir;
        r["error"] = d->error.empty() ? py::object(py::none()) : py::object(py::str(d->error));
        r["skipped"] = d->skipped;
        r["wall_s"] = d->wallS;
        return r;
      }
      if (over) {
        join();
        return py::none();
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }
  // stops the sweep (running points stop between growth steps and stay DIR.partial) and waits for it
  void cancel() {
    cancel_ = true;
    join();
  }
  py::dict summary() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (!finished_) throw std::runtime_error("the sweep is still running: its summary comes when it is over");
    }
    py::dict d;
    d["ran"] = result_.ran;
    d["skipped"] = result_.skipped;
    d["failed"] = result_.failed;
    d["interrupted"] = result_.interrupted;
    d["points"] = static_cast<int>(plan_.points.size());
    return d;
  }

 private:
  void join() {
    if (thread_.joinable()) {
      py::gil_scoped_release nogil;
      thread_.join();
    }
    if (error_) {
      std::exception_ptr e = error_;
      error_ = nullptr;
      std::rethrow_exception(e);
    }
  }
  SweepPlan plan_;
  SweepOptions opt_;
  std::function<void(const std::string&)> log_;
  SweepResult result_;
  std::exception_ptr error_;
  std::atomic<bool> cancel_{false};
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<SweepPointDone> done_;
  bool finished_ = false;
  std::thread thread_;
};

// rootsim.SceneError and rootsim.RunError, and the C++ exceptions translated to them
void registerErrors(py::module_& m) {
  gSceneError = PyErr_NewExceptionWithDoc(
      "rootsim.SceneError",
      "Bad input: a scene key or value, a sweep file, an output path, a render option. The message is the "
      "command line's: file:line (or the --set flag), the key, what was expected and what was found.",
      PyExc_ValueError, nullptr);
  gRunError = PyErr_NewExceptionWithDoc(
      "rootsim.RunError",
      "A run that started and failed (no equilibrium, divergence, I/O, rendering); the message names the "
      "growth step and the node or the failing call. The run directory is left as DIR.incomplete/.",
      PyExc_RuntimeError, nullptr);
  m.attr("SceneError") = py::handle(gSceneError);
  m.attr("RunError") = py::handle(gRunError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      PyErr_SetString(gSceneError, e.what());
    } catch (const RunInterrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const RunError& e) {
      PyErr_SetString(gRunError, e.what());
    } catch (const RelaxError& e) {
      PyErr_SetString(gRunError, e.what());
    }
  });
}

// scenes: loaded, parsed, their theory; a whole run
void registerScenes(py::module_& m) {
  py::class_<Scene>(m, "_Scene")
      .def_property_readonly("name", [](const Scene& s) { return s.model.name; })
      .def_property_readonly("path", [](const Scene& s) { return s.path; })
      .def_property_readonly("resolved_toml", [](const Scene& s) { return s.resolvedToml; })
      .def_property_readonly("grows", [](const Scene& s) { return s.model.growth.enabled; })
      .def_property_readonly("steps", [](const Scene& s) { return s.model.growth.enabled ? s.model.growth.steps : 0; })
      .def_property_readonly("trajectory", [](const Scene& s) { return s.output.trajectory; })
      .def_property_readonly("is_plate", [](const Scene& s) { return s.isPlate(); });
  m.def("load_scene", &loadScene, py::arg("path"), py::arg("overrides"));
  m.def("parse_scene", &parseScene, py::arg("text"), py::arg("source_name"), py::arg("overrides"));
  m.def("theory_json", [](const Scene& s) -> py::object {
    if (!s.model.growth.enabled) return py::none();
    return py::str(theoryJson(theoryFor(s.model)).dump());
  });

  m.def("run_scene", &runScene, py::arg("scene"), py::arg("options"), py::arg("progress"));
}

// the commands' option table, the state's fields; the commands check, modes and figure
void registerCommands(py::module_& m) {
  m.def("command_table", &commandTable);
  m.def("state_fields", &stateFieldNames);
  m.def("check_scene", [](const py::dict& options) {
    const cli::CheckOptions o = commandOptions<cli::CheckOptions>("check", options);
    const Scene sc = loadScene(o.scene, o.sets);
    py::dict d;
    d["resolved_toml"] = sc.resolvedToml;
    d["theory"] = sc.model.growth.enabled ? py::object(py::str(theoryJson(theoryFor(sc.model)).dump())) : py::object(py::none());
    return d;
  }, py::arg("options"));
  m.def("modes", [](const py::dict& options) {
    const cli::ModesOptions o = commandOptions<cli::ModesOptions>("modes", options);
    py::gil_scoped_release nogil;
    cli::modesCommand(o);
  }, py::arg("options"));
  m.def("figure", [](const py::dict& options) {
    const cli::FigureCliOptions o = commandOptions<cli::FigureCliOptions>("figure", options);
    {
      py::gil_scoped_release nogil;
      cli::figureCommand(o);
    }
    return o.out;
  }, py::arg("options"));
}

// the files rootsim writes, read back: CSV, trajectories, results; plate coordinates
void registerFiles(py::module_& m) {
  m.def("normalise_out_dir", [](const std::string& s) { return normaliseOutDir(s).string(); });
  m.def("read_csv", &readCsv, py::arg("path"));
  m.def("read_trajectory", &readFrames, py::arg("path"), py::arg("scene"));
  // plate coordinates of lab points [mm] (n x 3) in the scene's plate frame: (n x 3) lateral, downhill,
  // height [mm]; for Run.shape when shape.csv has no such columns
  m.def("plate_coords", [](const Scene& sc, const py::array_t<double, py::array::c_style | py::array::forcecast>& labMm) {
    if (labMm.ndim() != 2 || labMm.shape(1) != 3) throw py::value_error("plate_coords: expected an (n, 3) array");
    const PlateFrame f = sc.model.env.plane.frame();
    const py::ssize_t n = labMm.shape(0);
    py::array_t<double> out({n, py::ssize_t{3}});
    const double* in = labMm.data();
    double* o = out.mutable_data();
    for (py::ssize_t i = 0; i < n; ++i) {
      const Vec3 c = f.coords(Vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]));
      for (int k = 0; k < 3; ++k) o[3 * i + k] = c[k];
    }
    return out;
  }, py::arg("scene"), py::arg("lab_mm"));
  m.def("read_result", &readResultDict, py::arg("path"));
  m.def("result_columns", [] {
    py::list l;
    for (const ResultColumn& c : resultColumns()) l.append(py::make_tuple(c.name, c.unit, c.growthOnly, c.text));
    return l;
  });
}

// a simulation stepped from Python, a plate, a sweep
void registerSimulation(py::module_& m) {
  py::class_<PySimulation>(m, "_Simulation")
      .def(py::init<const Scene&>(), py::arg("scene"))
      .def("step", &PySimulation::step, py::arg("n"))
      .def("set", &PySimulation::set, py::arg("key"), py::arg("value"))
      .def("state", &PySimulation::state)
      .def("record", &PySimulation::record)
      .def("snapshot", &PySimulation::snapshot)
      .def_property_readonly("step_count", &PySimulation::stepCount)
      .def_property_readonly("steps_left", &PySimulation::stepsLeft)
      .def_property_readonly("scene", &PySimulation::scene, py::return_value_policy::copy);
  registerPlate(m);

  py::class_<SweepRunner>(m, "_SweepRunner")
      .def(py::init<const py::dict&>(), py::arg("options"))
      .def("next", &SweepRunner::next)
      .def("cancel", &SweepRunner::cancel)
      .def("summary", &SweepRunner::summary);
  m.def("parse_shard", &parseShard, py::arg("text"));
}

// render, montage and export (with the renderer built), have_render
void registerRenderCommands(py::module_& m) {
#ifdef ROOTSIM_HAVE_RENDER
  m.attr("have_render") = true;
  // rootsim.render's, montage's, export's, analyze's, compare's and fit's keywords (a dict, positionals
  // included) go through the command's table: commandOptions
  m.def("render_run", [](const py::dict& options) {
    const app::RenderOptions o = commandOptions<app::RenderOptions>("render", options);
    py::gil_scoped_release nogil;
    app::renderRunCommand(o);
  }, py::arg("options"));
  m.def("montage", [](const py::dict& options) {
    const app::MontageOptions o = commandOptions<app::MontageOptions>("montage", options);
    py::gil_scoped_release nogil;
    app::montageRunsCommand(o);
  }, py::arg("options"));
  m.def(
      "export_run",
      [](const py::dict& options) {
        const app::ExportOptions o = commandOptions<app::ExportOptions>("export", options);
        std::vector<fs::path> written;
        {
          py::gil_scoped_release nogil;
          app::exportRunCommand(o, &written);
        }
        std::vector<std::string> out;
        for (const fs::path& f : written) out.push_back(f.string());
        return out;
      },
      py::arg("options"));
#else
  m.attr("have_render") = false;
#endif
}

// analyze, compare and fit
void registerAnalysisCommands(py::module_& m) {
  m.def(
      "analyze_traces",
      // rootsim.analyze's keywords, as the command line's flags; the rows as dicts of analysis.csv's columns
      [](const py::dict& options) {
        app::AnalyzeOptions o = commandOptions<app::AnalyzeOptions>("analyze", options);
        o.printLines = false;
        app::Analysis all;
        {
          // with out: the command's folder too (analysis.csv, ...), else nothing written
          py::gil_scoped_release nogil;
          if (o.out.empty()) all = app::analyzeAll(o);
          else app::analyzeCommand(o, &all);
        }
        // each table as a list of dicts of its CSV's columns
        auto table = [](const auto& rows, auto fields) {
          py::list out;
          for (const auto& r : rows) {
            py::dict d;
            for (const app::RowField& f : fields(r)) {
              if (f.isText) d[f.name] = f.text;
              else d[f.name] = f.number;
            }
            out.append(d);
          }
          return out;
        };
        py::dict out;
        out["roots"] = table(all.roots, [](const app::RootRow& r) { return app::rowFields(r); });
        out["plants"] = table(all.plants, [](const app::PlantRow& r) { return app::plantFields(r); });
        out["growth"] = table(all.growth, [](const app::GrowthRow& r) { return app::growthFields(r); });
        // the column names of each table, for empty ones
        auto names = [](const std::vector<app::RowField>& fields) {
          py::list l;
          for (const app::RowField& f : fields) l.append(f.name);
          return l;
        };
        out["root_columns"] = names(app::rowFields(app::RootRow{}));
        out["plant_columns"] = names(app::plantFields(app::PlantRow{}));
        out["growth_columns"] = names(app::growthFields(app::GrowthRow{}));
        out["warnings"] = all.warnings;
        return out;
      },
      py::arg("options"));
  m.def(
      "compare_trace",
      // returns the folder written
      [](const py::dict& options) {
        app::CompareOptions o = commandOptions<app::CompareOptions>("compare", options);
        o.printTable = false;  // the command line's table on stdout
        std::string out;
        {
          py::gil_scoped_release nogil;
          app::compareCommand(o, &out);
        }
        return out;
      },
      py::arg("options"));
  m.def(
      "fit_trace",
      // rootsim.fit's keywords, as the command line's flags; returns the folder written
      [](const py::dict& options) {
        const app::FitOptions o = commandOptions<app::FitOptions>("fit", options);
        std::string out;
        {
          py::gil_scoped_release nogil;
          const auto log = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
          // a plate by group (groups=SHEET): its fit.json holds the groups and their contrasts
          out = o.groups.empty() ? app::runFit(o, log).out : app::runGroupFit(o, log).out;
        }
        return out;
      },
      py::arg("options"));
}

}  // namespace

PYBIND11_MODULE(_rootsim, m) {
  m.doc() = "rootsim's C++ core (use the `rootsim` package, not this module)";
  m.attr("__version__") = kVersion;
  registerErrors(m);
  registerScenes(m);
  registerCommands(m);
  registerFiles(m);
  registerSimulation(m);
  registerRenderCommands(m);
  registerAnalysisCommands(m);
}
