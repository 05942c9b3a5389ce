#pragma once
//! The lines of one tracking window (docs/tracking.md, line detection): ESPRIT with the MDL
//! order, lines outside the device's band or below a detection threshold set by the
//! record's noise dropped, each line's frequency with its Cramer-Rao standard error and the
//! stiffness it implies with a 90 % interval.
#include <cstddef>
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "spectral/esprit.hpp"

namespace stengmc {

struct LineDetectorSettings {
  double band_low_hz = 0.0;       //!< lowest plausible line of the device [Hz]
  double band_high_hz = 0.0;      //!< highest [Hz]
  double noise_sigma_v = 0.0;     //!< white noise standard deviation of the record [V]
  double sample_rate_hz = 0.0;
  //! A line is detected when its matched-filter amplitude SNR z = a sqrt(sum e^{-2dt} / 2) / sigma_floor
  //! is at least this (sigma_floor: the larger of noise_sigma_v and the in-band floor the fitted
  //! lines leave): with ~T B = 20 independent frequency cells per window, noise alone reaches
  //! z = 5 with probability ~20 e^{-12.5} = 7e-5 per window.
  double threshold_snr = 5.0;
  //! Lines down to threshold_snr - grey_snr are kept as candidates for the count's interval.
  double grey_snr = 1.645;
  std::size_t max_lines = 16;     //!< most lines ESPRIT considers per window
  //! > 0: a line within this of a stronger one is taken as part of it and dropped [Hz]. An
  //! excited asperity's line is a random narrow-band process: within one window ESPRIT splits
  //! it into a main line and weaker satellites ~0.6-0.8 / T away (seen on simulated records);
  //! the excited regime's periodogram peaks (track_peaks.hpp) use 2 / T, the Hann main lobe.
  double cluster_hz = 0.0;
  //! > 0: lines weaker (in snr) than this fraction of the window's strongest are dropped. (The
  //! tracker sets 0: excited, its peaks' Lorentzian-tail rule does this job, track_peaks.cpp.)
  double dynamic_range = 0.0;
};

//! One ESPRIT line of a window with what it implies (stiffness_low/high: 90 %, from the Cramer-Rao
//! error; tracking scales that error to each track's scatter afterwards).
struct WindowLine {
  double frequency_hz = 0.0;
  double frequency_se_hz = 0.0;   //!< Cramer-Rao standard error of the frequency [Hz]
  double amplitude_v = 0.0;       //!< amplitude at the window's first sample [V]
  double damping_per_s = 0.0;     //!< envelope decay rate [1/s]
  double snr = 0.0;               //!< matched-filter amplitude SNR z against the window's floor (see threshold_snr)
  double stiffness_n_per_m = 0.0; //!< k = m ((2 pi f)^2 + (c/2m)^2) [N/m]
  double stiffness_low = 0.0;     //!< 90 % interval of k from f +- 1.645 se [N/m]
  double stiffness_high = 0.0;
  bool detected = false;          //!< snr >= threshold (else a grey candidate)
  double floor_ratio = 1.0;       //!< the window's noise floor over the record's white noise (1: white only)
};

//! The window's mean and lines (detected and grey candidates), sorted by frequency.
struct WindowLines {
  double mean_v = 0.0;             //!< mean of the window's samples [V] (the plateau)
  //! The noise level the lines were judged against: the record's white noise, or the in-band
  //! floor the lines leave when higher [V].
  double floor_v = 0.0;
  std::vector<WindowLine> lines;
};

//! z of the normal quantile the 90 % intervals use.
inline constexpr double Z90 = 1.6448536269514722;

//! Stiffness of a line at frequency f of the device's asperities [N/m].
double stiffness_at(const KnownDevice& device, double frequency_hz);

//! Frequency of the line of stiffness k [Hz] (the inverse of stiffness_at).
double frequency_at(const KnownDevice& device, double stiffness_n_per_m);

class LineDetector {
 public:
  LineDetector(const KnownDevice& device, LineDetectorSettings settings);
  //! The lines of `window` (its mean removed first).
  [[nodiscard]] WindowLines detect(std::span<const double> window) const;
  [[nodiscard]] const LineDetectorSettings& settings() const { return settings_; }

 private:
  //! The equivalent white sigma of what `lines` leave in the band of `centred` [V].
  [[nodiscard]] double in_band_floor(std::span<const double> centred, const std::vector<Line>& lines) const;
  const KnownDevice& device_;
  LineDetectorSettings settings_;
};

//! Cramer-Rao standard errors of the frequencies of lines a e^{-d t} cos(2 pi f t + phi)
//! (t = n / fs, n = 0..samples-1) plus a constant, in white noise of sigma: the inverse of the
//! joint Fisher information (1/sigma^2) J^T J over all lines' (a, d, f, phi) and the constant
//! (Yao & Pandit, IEEE Trans. Signal Process. 43(4), 1995, for one damped line; joint here, so
//! close lines inflate each other's errors) [Hz].
std::vector<double> frequency_standard_errors(std::span<const double> frequency_hz, std::span<const double> amplitude,
                                              std::span<const double> damping_per_s, std::span<const double> phase_rad,
                                              std::size_t samples, double sample_rate_hz, double sigma);

}  // namespace stengmc
