#pragma once
//! The centre of a driven asperity's line over a long span (docs/tracking.md, excited regime).
//! An asperity driven by the counterface's broad-band friction modulation is a damped
//! oscillator under a random force: its response is a stationary narrow-band Gaussian process
//! whose spectrum near the line is a Lorentzian centred at its damped frequency with half-width
//! gamma = c/2m [rad/s]. It is not a sinusoid: a short window's peak wanders by ~1/T_window.
//! Its centre is estimated from the periodogram of the whole span by the Whittle likelihood
//! (Whittle, "Estimation and information in stationary time series", Ark. Mat. 2 (1953);
//! Percival & Walden, "Spectral Analysis for Physical Applications", CUP 1993, sec. 6.6): the
//! ordinates at the Fourier frequencies j/T are independent, each exponential with mean S(f_j).
//! Its Fisher information for the centre, with the line above the noise, is T/gamma: the
//! centre's standard deviation is sqrt(gamma/T) [rad/s], 0.17 % of f (0.33 % of k) over 300 us
//! at k = 60 N/m with Table 1 values (centre_standard_deviation_hz).
#include <cstddef>
#include <span>
#include <vector>

namespace stengmc {

//! Periodogram ordinates |sum_n v_n e^{-2 pi i f_j n / fs}|^2 / n at the Fourier frequencies
//! f_j = j fs / n of a span (its mean and linear trend removed: the plateau's drift leaks),
//! for the f_j in [low_hz, high_hz] only (a direct sum: a band of a few hundred kHz).
struct LocalPeriodogram {
  std::vector<double> frequency_hz;
  std::vector<double> power;  //!< [V^2 s] up to a constant factor (irrelevant to the fit)
  double span_s = 0.0;        //!< T = n / fs
};

LocalPeriodogram local_periodogram(std::span<const double> v, double sample_rate_hz, double low_hz, double high_hz);

//! S(f) = height / (1 + ((f - centre) / half_width)^2) + noise (+ neighbours' lines), fitted by
//! Whittle's likelihood.
struct LorentzianFit {
  double centre_hz = 0.0;
  //! Standard error of the centre: the inverse of Whittle's (expected) information over all
  //! four parameters at the fit [Hz]; infinite when it is not definite.
  double centre_se_hz = 0.0;
  double half_width_hz = 0.0;     //!< [Hz]
  double height = 0.0;            //!< line's peak density over noise (same units as power)
  double noise = 0.0;             //!< flat density under it
  double log_likelihood = 0.0;    //!< Whittle's: -sum (log S_j + P_j / S_j)
  bool valid = false;             //!< enough ordinates, finite curvature
};

//! Whittle fit of one Lorentzian plus a flat floor to `p`, started at `centre_guess_hz` with
//! half-width `half_width_guess_hz` (the device's gamma / 2 pi). With `fit_width` false the
//! half-width stays the device's: over 300 us a line of 8 kHz half-width spans ~5 independent
//! ordinates, too few to fit its width (it scatters by a factor 0.5-3 between realisations,
//! and the centre's error bar with it); the known device fixes it. `neighbours_hz`: other
//! asperities' lines, fitted with it where they lie in the band (their own centre and height,
//! the same width), so that their tails do not drag its centre; the centre's error then counts
//! their overlap.
LorentzianFit fit_lorentzian(const LocalPeriodogram& p, double centre_guess_hz, double half_width_guess_hz,
                             bool fit_width = false, std::span<const double> neighbours_hz = {});

//! The band a line is fitted in and the neighbours fitted with it: [low_hz, high_hz] widened by
//! `reach_hz` each way; of the other lines in it, the two nearest the band's middle are fitted
//! with the line, and the band stops half-way to any further one (each neighbour adds two
//! parameters to the simplex: a crowded band of many would cost seconds per fit).
struct FitBand {
  double low_hz = 0.0, high_hz = 0.0;
  std::vector<double> neighbours_hz;  //!< fitted with the line
};
FitBand fit_band(double low_hz, double high_hz, double reach_hz, std::span<const double> neighbours_hz, double least_reach_hz);

//! The Cramer-Rao standard deviation of the centre of a Lorentzian line of half-width
//! `half_width_hz` well above the noise observed for `span_s`: sqrt(gamma / T) / 2 pi with
//! gamma = 2 pi half_width, i.e. sqrt(half_width / (2 pi T)) [Hz].
double centre_standard_deviation_hz(double half_width_hz, double span_s);

}  // namespace stengmc
