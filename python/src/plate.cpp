// rootsim._rootsim._Plate: a plate scene stepped by hand (rootsim.Plate, docs/python.md, Plates). The
// plate's roots step together through the library's PlateSimulation, built from the scene's plate as the
// scene loader resolved it (each seedling's overrides and drawn values: those `rootsim run` uses); each
// root's state, snapshot and time-series row through the converters rootsim.Simulation uses (convert.hpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "convert.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"

namespace rootsim::pyconv {

namespace {

class PyPlate {
 public:
  explicit PyPlate(const Scene& sc) : scene_(sc) {
    if (!scene_.isPlate())
      throw SceneError("rootsim.Plate(" + (scene_.path.empty() ? scene_.model.name : scene_.path) +
                       "): the scene has no [[seedling]] tables: it is one root; step it with rootsim.Simulation");
    {
      py::gil_scoped_release nogil;
      plate_.emplace(scene_.plate.params, scene_.plate.seedlings);
    }
    emergedStep_.assign(static_cast<size_t>(plate_->size()), 0);
  }
  // n growth steps of every root (as `rootsim run` of the scene: its growth.steps at most); between steps
  // the GIL is taken to poll Ctrl-C. Returns the plate's row of the last step, its "emerged" the laterals
  // that emerged in any of the n steps.
  py::dict step(long long n) {
    CallMutex::Lock lock = mu_.acquire("Plate");
    if (n < 1) throw py::value_error("step(n): n must be a positive integer (got " + std::to_string(n) + ")");
    const GrowthParams& g = plate_->seedling(0).model.growth;
    if (!g.enabled) throw SceneError(scene_.path + ": growth.enabled = false: nothing to step");
    const long long left = static_cast<long long>(g.steps) - plate_->step();
    if (n > left)
      throw py::value_error("step(" + std::to_string(n) + "): only " + std::to_string(std::max(left, 0LL)) +
                            " growth steps left of growth.steps = " + std::to_string(g.steps) + " (at step " +
                            std::to_string(plate_->step()) + "; build a Plate with a larger growth.steps)");
    const size_t before = emergedStep_.size();
    for (long long k = 0; k < n; ++k) {
      try {
        py::gil_scoped_release nogil;
        plate_->growthStep();
      } catch (...) {
        // a step that failed may have opened laterals before it did: they are the plate's roots
        emergedStep_.resize(static_cast<size_t>(plate_->size()), plate_->step() + 1);
        throw;
      }
      emergedStep_.resize(static_cast<size_t>(plate_->size()), plate_->step());
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    py::dict d = plateRecord();
    std::vector<std::string> emerged;
    for (size_t r = before; r < emergedStep_.size(); ++r) emerged.push_back(plate_->seedling(static_cast<int>(r)).name);
    d["emerged"] = emerged;
    return d;
  }
  py::dict record() {
    CallMutex::Lock lock = mu_.acquire("Plate");
    return plateRecord();
  }
  int stepCount() {
    CallMutex::Lock lock = mu_.acquire("Plate");
    return plate_->step();
  }
  int stepsLeft() {
    CallMutex::Lock lock = mu_.acquire("Plate");
    const GrowthParams& g = plate_->seedling(0).model.growth;
    return g.enabled ? std::max(g.steps - plate_->step(), 0) : 0;
  }
  int size() {
    CallMutex::Lock lock = mu_.acquire("Plate");
    return plate_->size();
  }
  // root r as plate.csv describes it: name, genotype, parent's name ("" for a seedling), order, when it
  // emerged (h and growth step; 0 for a seedling), where its base's foot sits on the plate [mm]
  py::dict rootInfo(int r) {
    CallMutex::Lock lock = mu_.acquire("Plate");
    check(r);
    const Seedling& sd = plate_->seedling(r);
    py::dict d;
    d["name"] = sd.name;
    d["genotype"] = sd.genotype;
    d["parent"] = sd.parent < 0 ? std::string() : plate_->seedling(sd.parent).name;
    d["order"] = sd.order;
    d["emerged_h"] = sd.emergedH;
    d["emerged_step"] = emergedStep_[static_cast<size_t>(r)];
    const Vec3 o = plate_->offset(r) / units::mm;
    d["offset_mm"] = py::make_tuple(o.x(), o.y(), o.z());
    d["position_lateral_mm"] = sd.position.x() / units::mm;
    d["position_downhill_mm"] = sd.position.y() / units::mm;
    d["overrides"] = sd.overrides;
    return d;
  }
  // root r's state, snapshot and time-series row: a Simulation's, in the root's own frame (its base's foot
  // at the origin: roots/NAME of the plate's run directory)
  py::dict rootState(int r) {
    CallMutex::Lock lock = mu_.acquire("Plate");
    check(r);
    return stateDict(plate_->root(r), frame(r));
  }
  py::dict rootSnapshot(int r) {
    CallMutex::Lock lock = mu_.acquire("Plate");
    check(r);
    return snapshotDict(plate_->root(r).snapshot(), frame(r));
  }
  py::dict rootRecord(int r) {
    CallMutex::Lock lock = mu_.acquire("Plate");
    check(r);
    return recordDict(plate_->root(r).last());
  }
  const Scene& scene() const { return scene_; }  // constant after construction: no lock

 private:
  void check(int r) const {
    if (r < 0 || r >= plate_->size())
      throw py::index_error("root " + std::to_string(r) + ": the plate has " + std::to_string(plate_->size()) +
                            " roots now");
  }
  PlateFrame frame(int r) const { return plate_->seedling(r).model.env.plane.frame(); }
  // plate_timeseries.csv's columns (min_gap_over_contact NaN: no two roots within reach)
  py::dict plateRecord() const {
    const PlateStepRecord& p = plate_->last();
    py::dict d;
    d["step"] = p.step;
    d["time_h"] = p.timeH;
    d["touching_pairs"] = p.touchingPairs;
    d["min_gap_over_contact"] = p.minGap;
    d["sweeps"] = p.sweeps;
    d["roots"] = plate_->size();
    std::vector<std::string> emerged;
    for (int r : plate_->emerged()) emerged.push_back(plate_->seedling(r).name);
    d["emerged"] = emerged;
    return d;
  }

  Scene scene_;
  std::optional<PlateSimulation> plate_;
  std::vector<int> emergedStep_;  // per root: the growth step it emerged in (0: a seedling)
  CallMutex mu_;
};

}  // namespace

void registerPlate(py::module_& m) {
  py::class_<PyPlate>(m, "_Plate")
      .def(py::init<const Scene&>(), py::arg("scene"))
      .def("step", &PyPlate::step, py::arg("n"))
      .def("record", &PyPlate::record)
      .def("root_info", &PyPlate::rootInfo, py::arg("root"))
      .def("root_state", &PyPlate::rootState, py::arg("root"))
      .def("root_snapshot", &PyPlate::rootSnapshot, py::arg("root"))
      .def("root_record", &PyPlate::rootRecord, py::arg("root"))
      .def_property_readonly("size", &PyPlate::size)
      .def_property_readonly("step_count", &PyPlate::stepCount)
      .def_property_readonly("steps_left", &PyPlate::stepsLeft)
      .def_property_readonly("scene", &PyPlate::scene, py::return_value_policy::copy);
}

}  // namespace rootsim::pyconv
