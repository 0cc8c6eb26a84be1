// The extension module pronk._pronk; the package pronk (python/pronk/) re-exports it.
#include "io/build_info.hpp"
#include "python/src/bindings.hpp"
#include "python/src/gil_probe.hpp"

PYBIND11_MODULE(_pronk, m) {
  m.doc() = "pronk: simulate and tune robots that run by ballistic hops";
  m.attr("__version__") = pronk::version();
  m.attr("commit") = pronk::git_commit();
  pronk::python::bind_errors(m);
  pronk::python::bind_simulate(m);
  pronk::python::bind_study(m);
  pronk::python::bind_engines(m);
  pronk::python::bind_gil_probe(m);
}
