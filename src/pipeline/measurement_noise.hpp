#pragma once
//! The measurement chain between the S-TENG port and the record a spectral analysis (or a
//! user) sees: noise, an amplifier's bandwidth, an offset (docs/model.md, "The measurement
//! chain"; the study's [noise] table, docs/ensembles.md).
#include <span>
#include <vector>

#include "core/random_stream.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! The signal-to-noise ratios [noise] accepts lie in [-MAX_SNR_DB, MAX_SNR_DB] [dB]: 10^30
//! either way keeps sigma^2 = P / 10^(snr/10) a normal double for any voltage read.
inline constexpr double MAX_SNR_DB = 300.0;

//! The study's [noise] table.
struct NoiseSettings {
  //! Signal-to-noise ratio of all the noise, white and coloured: sigma^2 = P / 10^(snr/10)
  //! with P the mean square of the mean-removed clean voltage over the analysis interval [dB].
  double snr_db = 0.0;
  //! Share of sigma^2 in the 1/f^alpha part, [0, 1]; the rest is white.
  double coloured_share = 0.0;
  //! alpha of the coloured part, [0.5, 2] (1: flicker noise).
  double coloured_exponent = 1.0;
  //! A constant added after the amplifier [V].
  double offset_v = 0.0;
  //! The amplifier's first-order bandwidth (-3 dB) [Hz]; 0: none (flat).
  double bandwidth_hz = 0.0;
  //! The rms voltage the SNR refers to when the clean signal has no power (nothing slides):
  //! sigma^2 = reference_rms_v^2 / 10^(snr/10) [V]; 0: such a record gets no noise.
  double reference_rms_v = 0.0;
};

NoiseSettings read_noise_settings(TomlTable& table);

struct NoisyVoltage {
  std::vector<double> voltage_v;  //!< the measured voltage [V]
  double sigma_v = 0.0;           //!< the standard deviation of all the noise at the amplifier's input [V]
};

//! The measured voltage: V_m = H[V + n_white + n_coloured] + offset, H the amplifier's
//! first-order low-pass (exact for an input linear between samples) when bandwidth_hz > 0.
//! sigma^2 = P / 10^(snr_db/10), P the mean square of the mean-removed V over samples
//! [first, first + count) (reference_rms_v^2 when that is 0): white noise of variance (1 - share) sigma^2, one Boost normal
//! draw per sample, in order, from `white`; coloured noise (spectral/power_law_noise.hpp) of
//! variance share sigma^2 over the same samples, drawn from `coloured`. A voltage without
//! power there and no reference_rms_v gets no noise (an SNR of nothing is undefined), but
//! its offset and filter.
NoisyVoltage measure_voltage(std::span<const double> voltage_v, std::size_t first, std::size_t count,
                             double sample_rate_hz, const NoiseSettings& settings, RandomEngine& white,
                             RandomEngine& coloured);

//! y' = 2 pi f_c (x - y), solved exactly for x linear between samples, y_0 = x_0.
std::vector<double> first_order_lowpass(std::span<const double> x, double sample_rate_hz, double bandwidth_hz);

}  // namespace stengmc
