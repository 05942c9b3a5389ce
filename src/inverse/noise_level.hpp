#pragma once
//! The noise of a record, from the part of its spectrum no line reaches (README: inverse
//! estimation, "noise"): above the prior's highest plausible line only noise is left, so the
//! median of the periodogram there measures sigma without any fit. Cross-checked against the
//! final residual by the verdict.
#include <cstddef>
#include <memory>
#include <span>

namespace stengmc {

class SpectrumAnalyzer;

struct NoiseLevel {
  double sigma_v = 0.0;      //!< standard deviation of white noise [V]
  std::size_t bins = 0;      //!< periodogram bins the median was taken over (0: no band)
};

class NoiseEstimator {
 public:
  //! @param samples record length; @param band_low_hz lowest frequency of the noise band
  NoiseEstimator(std::size_t samples, double sample_rate_hz, double band_low_hz);
  ~NoiseEstimator();
  NoiseEstimator(const NoiseEstimator&) = delete;
  NoiseEstimator& operator=(const NoiseEstimator&) = delete;

  //! sigma from the median of the Hann-windowed amplitude spectrum over [band_low, 0.95 f_Nyquist]:
  //! for white noise each bin is Rayleigh with mean square 4 sigma^2 sum w^2 / (sum w)^2, so
  //! median = 2 sigma sqrt(ln 2 sum w^2) / sum w. Fewer than 64 bins there: bins = 0, sigma 0.
  NoiseLevel estimate(std::span<const double> voltage);

  //! Mean squared amplitude of the same spectrum inside [low, high] over that in the noise
  //! band (1 for white noise): the verdict's whiteness check of a residual.
  double band_power_ratio(std::span<const double> residual, double low_hz, double high_hz);

 private:
  std::unique_ptr<SpectrumAnalyzer> analyzer_;
  double sample_rate_hz_;
  double band_low_hz_;
  double window_factor_ = 0.0;  // 2 sqrt(ln 2 sum w^2) / sum w
};

}  // namespace stengmc
