#pragma once
//! A run's spectral analysis ([spectrum]) as a dict named as the run file's /spectrum and
//! /spectrogram datasets (io/spectrum_file.hpp), with their units.
#include <pybind11/pybind11.h>

#include "pipeline/analyse_spectra.hpp"

namespace stengmc::python {

pybind11::dict spectra_dict(const SpectralResult& result);

}  // namespace stengmc::python
