#pragma once
//! Single-sided amplitude spectrum (MODEL.md §3): A_k = 2 |sum_n w_n y_n e^{-2 pi i k n / M}| / sum_n w_n,
//! in the signal's own unit, f_k = k / (M dt), computed with FFTW.
#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "spectral/window.hpp"

namespace stengmc {

struct AmplitudeSpectrum {
  std::vector<double> frequency_hz;  //!< f_k, k = 0 .. padded/2 [Hz]
  std::vector<double> amplitude;     //!< A_k in the signal's unit (A_0 is the mean, not doubled)
  double bin_width_hz = 0.0;         //!< 1 / (padded length x dt) [Hz]
  double resolution_hz = 0.0;        //!< 1 / T of the analysed samples (before padding) [Hz]
};

//! Amplitude spectra of many signals of one length: the FFTW plan and the window are made
//! once and reused (FFTW planning costs far more than an FFT). Not thread-safe: one per thread.
class SpectrumAnalyzer {
 public:
  //! @param samples        length of the analysed signal
  //! @param window         window shape
  //! @param zero_pad_factor  FFT length = samples x zero_pad_factor (>= 1); padding interpolates
  //!                         the spectrum, it does not improve resolution
  SpectrumAnalyzer(std::size_t samples, WindowKind window, std::size_t zero_pad_factor = 1);
  ~SpectrumAnalyzer();
  SpectrumAnalyzer(const SpectrumAnalyzer&) = delete;
  SpectrumAnalyzer& operator=(const SpectrumAnalyzer&) = delete;

  //! A_k of `signal` (exactly `samples` values) sampled at `sample_rate_hz`.
  [[nodiscard]] AmplitudeSpectrum analyse(std::span<const double> signal, double sample_rate_hz);

  //! 2 |sum_n w_n y_n e^{-2 pi i f n dt}| / sum w at any frequency f (the windowed DTFT,
  //! MODEL.md's A_k between bins), for refining peaks.
  [[nodiscard]] double amplitude_at(std::span<const double> signal, double sample_rate_hz, double frequency_hz) const;

  //! |W(offset)| / W(0): the amplitude a unit line leaks `offset_hz` away (its negative-frequency
  //! image not included), in closed form from Dirichlet kernels, O(1). For side-lobe tests.
  [[nodiscard]] double window_response(double offset_hz, double sample_rate_hz) const;

  [[nodiscard]] const std::vector<double>& window() const { return window_; }
  [[nodiscard]] std::size_t samples() const { return samples_; }

 private:
  struct Plan;
  std::size_t samples_;
  std::size_t padded_;
  std::vector<double> window_;
  std::vector<double> cosine_coefficients_;  // a_j of window_ (window.hpp)
  double window_sum_ = 0.0;
  std::unique_ptr<Plan> plan_;
};

//! This thread's analyzer for signals of `samples` values with `window` and padding,
//! made on first use and kept (a few per thread) for every later call: planning costs
//! more than the FFT, and an ensemble analyses the same length in every realisation.
//! FFTW_ESTIMATE plans are deterministic, so which thread made one never shows in a result.
SpectrumAnalyzer& thread_spectrum_analyzer(std::size_t samples, WindowKind window, std::size_t zero_pad_factor = 1);

}  // namespace stengmc
