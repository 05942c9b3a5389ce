#pragma once
//! The /spectrum and /spectrogram groups of an output file (docs/output-files.md).
#include "core/hdf5_file.hpp"
#include "pipeline/analyse_spectra.hpp"
#include "spectral/spectrum_settings.hpp"

namespace stengmc {

void write_spectra(Hdf5Writer& file, const SpectralResult& result, const SpectrumSettings& settings);

}  // namespace stengmc
