// The GIL-release probe (see gil_probe.hpp): one armed wait at a time, shared
// by the bindings of the process; used by python/tests only.
#include "python/src/gil_probe.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace pronk::python {

namespace {

/// Long enough for any machine under any load; expiring means "not released".
constexpr std::chrono::seconds kProbeTimeout{60};

struct Probe {
  std::atomic<bool> armed{false};
  std::mutex mutex;
  std::condition_variable changed;
  bool reached = false;   ///< a released call is parked in the probe
  bool signaled = false;  ///< a thread holding the GIL signaled it
  int verdict = -1;       ///< -1 not yet, 1 signaled while parked, 0 timed out
};

Probe& probe() {
  static Probe p;
  return p;
}

void arm() {
  Probe& p = probe();
  std::lock_guard<std::mutex> lock(p.mutex);
  p.reached = false;
  p.signaled = false;
  p.verdict = -1;
  p.armed = true;
}

/// Waits with the GIL released until a call is parked in the probe; true if one is.
bool wait_reached(double timeout_s) {
  Probe& p = probe();
  py::gil_scoped_release nogil;
  std::unique_lock<std::mutex> lock(p.mutex);
  return p.changed.wait_for(lock, std::chrono::duration<double>(timeout_s),
                            [&p] { return p.reached; });
}

/// Runs under the GIL (as every binding without a release does).
void signal() {
  Probe& p = probe();
  std::lock_guard<std::mutex> lock(p.mutex);
  p.signaled = true;
  p.changed.notify_all();
}

}  // namespace

void gil_probe_point() {
  Probe& p = probe();
  if (!p.armed.load() || !p.armed.exchange(false)) return;  // unarmed: one load
  std::unique_lock<std::mutex> lock(p.mutex);
  p.reached = true;
  p.changed.notify_all();
  p.verdict = p.changed.wait_for(lock, kProbeTimeout, [&p] { return p.signaled; }) ? 1 : 0;
}

void bind_gil_probe(py::module_& m) {
  m.def("_gil_probe_arm", &arm,
        "Test hook: the next call that releases the GIL parks right after the release "
        "until _gil_probe_signal (at most 60 s).");
  m.def("_gil_probe_wait_reached", &wait_reached, py::arg("timeout"),
        "Test hook: waits (GIL released) until a call is parked in the probe; returns once "
        "this thread holds the GIL again, which it can only do if the parked call released "
        "it.");
  m.def("_gil_probe_signal", &signal, "Test hook: releases the parked call (needs the GIL).");
  m.def(
      "_gil_probe_result",
      [] {
        Probe& p = probe();
        std::lock_guard<std::mutex> lock(p.mutex);
        return p.verdict < 0 ? py::object(py::none()) : py::object(py::bool_(p.verdict == 1));
      },
      "Test hook: True if the parked call was signaled, False if it waited 60 s in vain "
      "(the GIL was not released), None if no call was parked.");
}

}  // namespace pronk::python
