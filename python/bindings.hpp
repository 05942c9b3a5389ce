#pragma once
//! The parts of the extension `stengmc._core`, one per file; module.cpp calls each once.
#include <pybind11/pybind11.h>

namespace stengmc::python {

void bind_errors(pybind11::module_& m);    //!< errors.cpp: C++ exceptions -> stengmc.errors
void bind_study(pybind11::module_& m);     //!< study_binding.cpp: Study, read_study, parse_study
void bind_run(pybind11::module_& m);       //!< run_binding.cpp: one realisation
void bind_ensemble(pybind11::module_& m);  //!< ensemble_binding.cpp: an [ensemble] study
void bind_invert(pybind11::module_& m);    //!< invert_binding.cpp: the inverse estimator
void bind_spectrum(pybind11::module_& m);  //!< spectrum_binding.cpp: a record's spectra from numpy
void bind_circuit(pybind11::module_& m);   //!< circuit_binding.cpp: the circuit driven by numpy displacements
void bind_surface(pybind11::module_& m);   //!< surface_binding.cpp: a surface and its samples as numpy arrays

}  // namespace stengmc::python
