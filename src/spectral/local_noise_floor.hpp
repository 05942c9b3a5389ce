#pragma once
//! A noise floor that follows the spectrum (README: spectra, "noise floor"): the running
//! median of A_k over a window of frequencies, scaled like noise_floor() to the rms of a
//! white-noise bin. Where the noise is not white (a measured amplifier's 1/f, a simulation
//! whose "noise" is round-off far from its lines), one floor for 0 .. Nyquist is too high
//! in one place and too low in another; a local one sets a peak's threshold by its
//! neighbourhood.
#include <vector>

#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

//! Per bin, median of A over [f - width/2, f + width/2] (bins above DC) / sqrt(ln 2).
//! Computed at every max(1, window/8)-th bin and linearly interpolated between (the median of
//! a window moved by 1/8 of its width changes little). A window holding no bin: the global floor.
std::vector<double> local_noise_floor(const AmplitudeSpectrum& spectrum, double width_hz);

}  // namespace stengmc
