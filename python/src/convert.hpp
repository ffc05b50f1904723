#pragma once
// The package's converters from the library's types to Python dicts (defined in module.cpp, one place),
// shared by the bindings in their own source files (plate.cpp), and the per-object lock every stepping
// object takes.
#include <pybind11/pybind11.h>

#include <atomic>
#include <string>
#include <utility>
#include <mutex>
#include <thread>

#include "rootsim/simulation.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::pyconv {

namespace py = pybind11;

// one snapshot as a dict of numpy arrays, in the package's units (trajectory.csv's), with the nodes'
// plate coordinates in the frame f
py::dict snapshotDict(const Snapshot& s, const PlateFrame& f);
// one time-series row: timeseries.csv's columns and units
py::dict recordDict(const StepRecord& r);
// the rod's state now as copies (rootsim.State's fields), plate coordinates in the frame f
py::dict stateDict(const Simulation& sim, const PlateFrame& f);

// One object (a Simulation, a Plate) used by one thread at a time: every method takes the object's
// mutex first, so concurrent calls from several threads are serialised. The mutex is waited for with the
// GIL released (a thread inside step() takes the GIL back between growth steps: waiting with it held would
// deadlock). A call made by the thread that already holds it (a signal handler or progress code running
// between growth steps of the same object) raises RuntimeError naming `what` instead of deadlocking.
class CallMutex {
 public:
  class Lock {
   public:
    explicit Lock(CallMutex& m) : m_(&m) {}
    Lock(Lock&& o) noexcept : m_(std::exchange(o.m_, nullptr)) {}
    Lock(const Lock&) = delete;
    Lock& operator=(const Lock&) = delete;
    Lock& operator=(Lock&&) = delete;
    ~Lock() {
      if (m_) {
        m_->owner_.store(std::thread::id{});
        m_->mu_.unlock();
      }
    }

   private:
    CallMutex* m_;
  };
  Lock acquire(const char* what) {
    if (owner_.load() == std::this_thread::get_id())
      throw std::runtime_error(std::string(what) + " is busy in this thread: a call from inside its own step() (a "
                               "signal handler or callback between growth steps); call it after step() returns");
    if (!mu_.try_lock()) {
      py::gil_scoped_release nogil;  // another thread is in a call: wait for it without the GIL
      mu_.lock();
    }
    owner_.store(std::this_thread::get_id());
    return Lock(*this);
  }

 private:
  std::mutex mu_;
  std::atomic<std::thread::id> owner_{};
};

// rootsim._rootsim._Plate (plate.cpp)
void registerPlate(py::module_& m);

}  // namespace rootsim::pyconv
