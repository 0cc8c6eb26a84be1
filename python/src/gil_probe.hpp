// Releasing the GIL, with a test probe that proves it without timing: every
// binding that runs long C++ work releases the GIL with ReleaseGil, which calls
// the probe right after the release. A test arms the probe, starts the call on a
// worker thread and waits (GIL released) until the worker is parked in the
// probe; the test's main thread can only return from that wait and signal the
// probe if the worker no longer holds the GIL. Unarmed, the probe is one atomic
// load. Python side: pronk._pronk._gil_probe_{arm,wait_reached,signal,result}.
#pragma once

#include "python/src/bindings.hpp"

namespace pronk::python {

/// Where a released call parks when the probe is armed (first call after arming
/// only): it waits, at most 60 s, for the signal of a thread that holds the GIL.
void gil_probe_point();

/// py::gil_scoped_release that passes the probe right after releasing.
class ReleaseGil {
 public:
  ReleaseGil() { gil_probe_point(); }
  ReleaseGil(const ReleaseGil&) = delete;
  ReleaseGil& operator=(const ReleaseGil&) = delete;

 private:
  py::gil_scoped_release release_;  // constructed before the body calls the probe
};

void bind_gil_probe(py::module_& m);

}  // namespace pronk::python
