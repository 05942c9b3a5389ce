#pragma once
//! Short-time Fourier transform (the paper's tftb `tfrstft`), as amplitude spectra of
//! windowed segments (MODEL.md §3).
#include <cstddef>
#include <span>
#include <vector>

#include "spectral/window.hpp"

namespace stengmc {

struct SpectrogramOptions {
  std::size_t window_samples = 256;  //!< segment length
  std::size_t hop_samples = 64;      //!< step between segment starts
  WindowKind window = WindowKind::hann;
};

struct Spectrogram {
  std::vector<double> time_s;                   //!< centre time of each segment [s]
  std::vector<double> frequency_hz;             //!< bin frequencies [Hz]
  std::vector<std::vector<double>> amplitude;   //!< [segment][bin], signal unit (MODEL.md §3 A_k per segment)
};

//! Spectrogram of `signal` sampled at `sample_rate_hz`; segments that would run past the
//! end are not taken. Throws InputError if the window is longer than the signal or hop is 0.
Spectrogram compute_spectrogram(std::span<const double> signal, double sample_rate_hz, const SpectrogramOptions& options);

}  // namespace stengmc
