#pragma once
//! The spectral part of a run's summary table.
#include <string>

#include "pipeline/analyse_spectra.hpp"

namespace stengmc {

//! Per asperity: its expected line, whether it slides, and whether the FFT peaks and the
//! ESPRIT lines identify it (with the frequency error); then the counts and ratios.
std::string format_spectral_summary(const SpectralResult& result);

}  // namespace stengmc
