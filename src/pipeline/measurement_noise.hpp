#pragma once
//! Measurement noise on the voltage a spectral analysis sees (docs/ensembles.md, [noise]).
#include <span>
#include <vector>

#include "core/random_stream.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! The signal-to-noise ratios [noise] accepts lie in [-MAX_SNR_DB, MAX_SNR_DB] [dB]: 10^30
//! either way keeps sigma^2 = P / 10^(snr/10) a normal double for any voltage read.
inline constexpr double MAX_SNR_DB = 300.0;

//! Measurement noise added to the voltage before the spectral analysis (MODEL.md §3):
//! the study's [noise] table.
struct NoiseSettings {
  //! White Gaussian noise at this signal-to-noise ratio: sigma^2 = P / 10^(snr/10) with
  //! P the mean square of the (mean-removed) voltage over the analysis interval [dB].
  double snr_db = 0.0;
};

NoiseSettings read_noise_settings(TomlTable& table);

struct NoisyVoltage {
  std::vector<double> voltage_v;  //!< the voltage plus white Gaussian noise [V]
  double sigma_v = 0.0;           //!< the noise's standard deviation [V]
};

//! Adds white Gaussian noise (one Boost normal draw per sample, in order, from `engine`)
//! with sigma^2 = P / 10^(snr_db/10), P the mean square of the mean-removed voltage over
//! samples [first, first + count). A voltage without power there gets no noise (sigma 0):
//! an SNR of nothing is undefined.
NoisyVoltage add_white_noise(std::span<const double> voltage_v, std::size_t first, std::size_t count, double snr_db,
                             RandomEngine& engine);

}  // namespace stengmc
