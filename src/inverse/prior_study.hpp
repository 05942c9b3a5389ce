#pragma once
//! The study a calibration runs: the known device, its asperities drawn from the prior
//! (docs/inverse.md, "calibration"). It is an ordinary ensemble study, written
//! out as text (and kept in the bank, so anyone can see and re-run what was simulated):
//! a random surface whose summit count and stiffness law are [[ensemble.draw]]s, every
//! summit carrying the device's load, mass and element; white noise at a drawn SNR.
#include <string>

#include "inverse/inverse_prior.hpp"
#include "inverse/known_device.hpp"

namespace stengmc {

//! The prior study for `device` and `prior` with `realisations` records and master seed
//! `seed`; `spectrum_band_hz` bounds the [spectrum] analysis (the naive FFT count) to the
//! band where the prior's lines lie. Parses as a study (parse_study) from any folder.
std::string prior_study_text(const KnownDevice& device, const InversePrior& prior, std::size_t realisations,
                             std::uint64_t seed, double band_low_hz, double band_high_hz);

}  // namespace stengmc
