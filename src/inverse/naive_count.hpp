#pragma once
//! The count a user gets today from the spectrum alone: FFT peaks of the record (Hann
//! window, local noise floor, only in the band where the prior puts lines), at several
//! prominence thresholds. The calibration keeps the threshold whose count is closest to the
//! truth (the best a user could tune it on simulations) and reports it beside the estimate.
#include <memory>
#include <span>
#include <vector>

namespace stengmc {

class SpectrumAnalyzer;

//! Prominence thresholds (x the local noise floor) the calibration tries.
const std::vector<double>& naive_count_thresholds();

class NaiveCounter {
 public:
  NaiveCounter(std::size_t samples, double sample_rate_hz, double band_low_hz, double band_high_hz);
  ~NaiveCounter();
  NaiveCounter(const NaiveCounter&) = delete;
  NaiveCounter& operator=(const NaiveCounter&) = delete;

  //! Number of FFT peaks in the band at each of `thresholds`.
  std::vector<double> count(std::span<const double> voltage, std::span<const double> thresholds);

 private:
  std::unique_ptr<SpectrumAnalyzer> analyzer_;
  double sample_rate_hz_, band_low_hz_, band_high_hz_;
};

}  // namespace stengmc
