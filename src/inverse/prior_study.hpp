#pragma once
//! The study a calibration runs: the known device, its asperities drawn from the prior
//! (docs/inverse.md, "calibration"). It is an ordinary ensemble study, written
//! out as text (and kept in the bank, so anyone can see and re-run what was simulated):
//! a random surface whose summit count and stiffness law are [[ensemble.draw]]s, every
//! summit carrying the device's mass and element and its load (or a Greenwood–Williamson
//! spread of it), the measurement chain at a drawn SNR.
#include <string>

#include "inverse/inverse_prior.hpp"
#include "inverse/known_device.hpp"

namespace stengmc {

//! The prior study for `device` and `prior` with `realisations` records and master seed
//! `seed`; `band_low_hz`, `band_high_hz` bound the [spectrum] analysis (the naive FFT count)
//! to the band where the prior's lines lie; `reference_rms_v` is the noise reference of a
//! record with no sliding asperity ([noise] reference_rms_v). Each prior key becomes draws:
//! count, the law's parameters and the SNR always; load_cv (a "spread" load), onsets (an
//! [onset] law), the tolerance (mu_s, mu_k, c, the mean load, sigma, d0), the coloured
//! noise's share and exponent, the offset, when the prior asks for them. Parses as a study
//! (parse_study) from any folder.
std::string prior_study_text(const KnownDevice& device, const InversePrior& prior, std::size_t realisations,
                             std::uint64_t seed, double band_low_hz, double band_high_hz, double reference_rms_v);

}  // namespace stengmc
