#pragma once
//! Gaussian noise with a power-law spectrum S(f) ∝ 1/f^alpha (flicker noise at alpha = 1,
//! a random walk's at 2), what a real amplifier and contact add below the white floor
//! (docs/model.md, "The measurement chain").
//!
//! Method: white Gaussian samples shaped in the frequency domain, each DFT bin k >= 1 scaled
//! by k^(-alpha/2) and the mean removed (Timmer & König 1995, A&A 300, 707: a Gaussian
//! process is fixed by its spectrum, and shaping white noise draws exactly its Fourier
//! amplitudes). The series is periodic over its length: its lowest frequency is 1/T.
#include <cstddef>
#include <vector>

#include "core/random_stream.hpp"

namespace stengmc {

//! `samples` values of zero-mean noise with S(f) ∝ 1/f^exponent, scaled to unit sample
//! variance; one Boost normal draw per sample, in order, from `engine`. FFTW plans with
//! FFTW_ESTIMATE on aligned buffers: the same bits in every thread and process.
//! @throws InputError for an exponent outside [0, 4] or fewer than 2 samples
std::vector<double> power_law_noise(std::size_t samples, double exponent, RandomEngine& engine);

}  // namespace stengmc
