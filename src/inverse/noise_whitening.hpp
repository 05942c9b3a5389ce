#pragma once
//! The noise's spectrum estimated from a fit's residual, and the filter that whitens it
//! (docs/inverse.md, "noise"): a record's noise need not be white (an amplifier's 1/f part),
//! and a least-squares fit that treats it as white both weighs the low frequencies, where a
//! 1/f part lives, as much as any other and misjudges how much a misfit means.
//!
//! The spectrum is modelled as white plus a power law, S(f) = w + c (f/f_1)^{-alpha},
//! alpha in [0.5, 2] (MODEL.md §3.6): smooth, so no line of an unfitted asperity can hide in
//! it. It is fitted to the residual's Hann periodogram through the medians of logarithmic
//! bands (a median per band is robust to the few bins a line leaves), a weighted least squares
//! in (w, c) on a grid of alpha. The whitening filter is then the prediction-error filter of
//! order p of that spectrum (Levinson–Durbin on its autocorrelation; Kay, "Modern Spectral
//! Estimation", 1988, ch. 6):
//!
//!   e_t = x_t + sum_{j=1}^p a_j x_{t-j},
//!
//! which turns noise of spectrum S into nearly white noise of variance sigma_e^2.
#include <span>
#include <vector>

namespace stengmc {

//! The fitted spectrum, in the variance one periodogram bin of k cycles per record holds [V^2].
struct NoiseSpectrum {
  double white_v2 = 0.0;     //!< w
  double coloured_v2 = 0.0;  //!< c, at k = 1 (f = 1/T)
  double exponent = 1.0;     //!< alpha
  //! Total variance of the noise, w + c sum_k k^-alpha / (M/2) [V^2]... per sample.
  [[nodiscard]] double variance(std::size_t samples) const;
  //! The share of the variance in the coloured part [-].
  [[nodiscard]] double coloured_share(std::size_t samples) const;
};

class Whitener {
 public:
  Whitener() = default;  //!< the identity (white noise)
  Whitener(std::vector<double> coefficients, double innovation_sigma_v);

  //! out = the filtered in (zero before the first sample); out may be in.
  void apply(std::span<const double> in, std::span<double> out) const;
  [[nodiscard]] bool identity() const { return coefficients_.empty(); }
  //! a_1 .. a_p.
  [[nodiscard]] const std::vector<double>& coefficients() const { return coefficients_; }
  //! sigma_e: the filtered noise's standard deviation [V].
  [[nodiscard]] double innovation_sigma_v() const { return innovation_sigma_v_; }

 private:
  std::vector<double> coefficients_;
  double innovation_sigma_v_ = 0.0;
};

//! S fitted to `residual` (its mean removed) as described above.
NoiseSpectrum fit_noise_spectrum(std::span<const double> residual);

//! The order-`order` prediction-error filter of `spectrum` for records of `samples` samples.
Whitener whitener_of(const NoiseSpectrum& spectrum, std::size_t samples, std::size_t order = 16);

}  // namespace stengmc
