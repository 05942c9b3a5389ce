// The extension module stengmc._core; the package stengmc (python/stengmc/__init__.py)
// is the public face, this the C++ underneath (README: Python).
#include "bindings.hpp"
#include "core/build_info.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "stengmc's C++ library: studies, runs, ensembles, the inverse estimator (use the package stengmc)";
  m.attr("version") = stengmc::program_version();
  m.attr("git_revision") = stengmc::git_revision();
  stengmc::python::bind_errors(m);
  stengmc::python::bind_study(m);
  stengmc::python::bind_run(m);
  stengmc::python::bind_ensemble(m);
  stengmc::python::bind_invert(m);
  stengmc::python::bind_spectrum(m);
  stengmc::python::bind_circuit(m);
  stengmc::python::bind_surface(m);
}
