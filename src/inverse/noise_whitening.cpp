#include "inverse/noise_whitening.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

namespace {

// Bands grow by this factor in frequency: ~40 bands over 10^4 bins.
constexpr double BAND_GROWTH = 1.25;

//! sum_{k=1}^{K} k^-alpha.
double power_sum(double alpha, std::size_t bins) {
  double s = 0.0;
  for (std::size_t k = 1; k <= bins; ++k) s += std::pow(static_cast<double>(k), -alpha);
  return s;
}

}  // namespace

double NoiseSpectrum::variance(std::size_t samples) const {
  const std::size_t bins = samples / 2;
  return white_v2 + coloured_v2 * power_sum(exponent, bins) / static_cast<double>(bins);
}

double NoiseSpectrum::coloured_share(std::size_t samples) const {
  const double total = variance(samples);
  return total > 0.0 ? (total - white_v2) / total : 0.0;
}

Whitener::Whitener(std::vector<double> coefficients, double innovation_sigma_v)
    : coefficients_(std::move(coefficients)), innovation_sigma_v_(innovation_sigma_v) {}

void Whitener::apply(std::span<const double> in, std::span<double> out) const {
  if (in.size() != out.size()) throw Error("Whitener::apply: input and output differ in length");
  const std::size_t p = coefficients_.size();
  if (p == 0) {
    if (in.data() != out.data()) std::copy(in.begin(), in.end(), out.begin());
    return;
  }
  // Backwards, so out may be in: each output reads only inputs at or before its index. By
  // blocks of outputs, tap by tap: each output's sum keeps its order (in[t], then taps 1..p in
  // turn: the same bits as one output at a time), but the outputs of a block are independent,
  // so the loop over them vectorises where one output's p dependent additions could not (the
  // filter is applied to every column of every Jacobian of a fit in coloured noise).
  constexpr std::size_t BLOCK = 64;
  std::array<double, BLOCK> e{};
  for (std::size_t end = in.size(); end > 0;) {
    const std::size_t begin = end > BLOCK ? end - BLOCK : 0, length = end - begin;
    for (std::size_t i = 0; i < length; ++i) e[i] = in[begin + i];
    for (std::size_t j = 1; j <= p; ++j) {
      const double c = coefficients_[j - 1];
      // Only outputs t >= j have a tap j.
      for (std::size_t i = begin >= j ? 0 : j - begin; i < length; ++i) e[i] += c * in[begin + i - j];
    }
    for (std::size_t i = 0; i < length; ++i) out[begin + i] = e[i];
    end = begin;
  }
}

NoiseSpectrum fit_noise_spectrum(std::span<const double> residual) {
  const std::size_t m = residual.size();
  if (m < 64) throw Error("fit_noise_spectrum: too short a residual");
  // Hann periodogram normalised so that white noise of variance s^2 has E[P_k] = s^2.
  SpectrumAnalyzer analyzer(m, WindowKind::hann);
  std::vector<double> centred(residual.begin(), residual.end());
  const double mean = std::accumulate(centred.begin(), centred.end(), 0.0) / static_cast<double>(m);
  for (double& v : centred) v -= mean;
  const AmplitudeSpectrum s = analyzer.analyse(centred, 1.0);
  const std::vector<double>& w = analyzer.window();
  const double sum = std::accumulate(w.begin(), w.end(), 0.0);
  const double squares = std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
  // A_k = 2 |X_k| / sum w  ->  |X_k|^2 / sum w^2 = (A_k sum w / 2)^2 / sum w^2.
  const double to_power = sum * sum / (4.0 * squares);
  const std::size_t bins = std::min(s.amplitude.size() - 1, m / 2);
  // Band medians (median of an exponential variable = ln 2 x its mean).
  std::vector<double> centre, power, weight;
  std::vector<double> band;
  for (std::size_t lo = 1; lo <= bins;) {
    const std::size_t hi = std::min(bins, std::max(lo, static_cast<std::size_t>(std::floor(static_cast<double>(lo) * BAND_GROWTH))));
    band.clear();
    for (std::size_t k = lo; k <= hi; ++k) band.push_back(s.amplitude[k] * s.amplitude[k] * to_power);
    auto middle = band.begin() + static_cast<std::ptrdiff_t>(band.size() / 2);
    std::nth_element(band.begin(), middle, band.end());
    const double median = *middle / (band.size() >= 3 ? std::log(2.0) : 1.0);
    centre.push_back(std::sqrt(static_cast<double>(lo) * static_cast<double>(hi)));
    power.push_back(std::max(median, 1e-300));
    weight.push_back(static_cast<double>(band.size()));
    lo = hi + 1;
  }
  // For each alpha: weighted least squares of power ~ w + c k^-alpha with relative errors,
  // both >= 0; the alpha whose fit is closest in log.
  NoiseSpectrum best;
  double best_misfit = INFINITY;
  std::vector<double> shape(power.size());
  for (int a = 0; a <= 30; ++a) {
    const double alpha = 0.5 + 1.5 * a / 30.0;
    for (std::size_t j = 0; j < power.size(); ++j) shape[j] = std::pow(centre[j], -alpha);
    // Iteratively reweighted: a band's error is relative to its true power, so its weight is
    // its size over the model's power squared. Weights from the band's own power (the first
    // pass only) favour the bands that came out low: the single-bin bands at the lowest
    // frequencies scatter as exponential variables, and 1/P^2 of one drawn near zero outweighs
    // all the others (white noise was fitted 0.84 x its variance, 70 % 1/f noise as 30 %).
    double white = 0.0, coloured = 0.0;
    for (int pass = 0; pass < 6; ++pass) {
      double s11 = 0, s12 = 0, s22 = 0, b1 = 0, b2 = 0;
      for (std::size_t j = 0; j < power.size(); ++j) {
        const double x = shape[j];
        const double expected = pass == 0 ? power[j] : std::max(white + coloured * x, 1e-300);
        const double q = weight[j] / (expected * expected);
        s11 += q, s12 += q * x, s22 += q * x * x, b1 += q * power[j], b2 += q * x * power[j];
      }
      const double det = s11 * s22 - s12 * s12;
      white = det > 0.0 ? (b1 * s22 - b2 * s12) / det : b1 / s11;
      coloured = det > 0.0 ? (s11 * b2 - s12 * b1) / det : 0.0;
      if (coloured < 0.0) coloured = 0.0, white = b1 / s11;
      if (white < 0.0) white = 0.0, coloured = b2 / s22;
    }
    double misfit = 0.0;
    for (std::size_t j = 0; j < power.size(); ++j) {
      const double model = std::max(white + coloured * shape[j], 1e-300);
      misfit += weight[j] * std::pow(std::log(power[j] / model), 2);
    }
    if (misfit < best_misfit) best_misfit = misfit, best = {white, coloured, alpha};
  }
  return best;
}

Whitener whitener_of(const NoiseSpectrum& spectrum, std::size_t samples, std::size_t order) {
  // The spectrum's autocorrelation over a period of `samples`: r_tau = (1/M) sum_k S_k e^{2 pi i k tau / M}.
  const std::size_t bins = samples / 2;
  std::vector<double> r(order + 1, 0.0);
  for (std::size_t k = 1; k <= bins; ++k) {
    const double s = spectrum.white_v2 + spectrum.coloured_v2 * std::pow(static_cast<double>(k), -spectrum.exponent);
    const double factor = (k == bins && samples % 2 == 0) ? 1.0 : 2.0;  // +-k
    for (std::size_t tau = 0; tau <= order; ++tau)
      r[tau] += factor * s * std::cos(2.0 * PI * static_cast<double>(k * tau) / static_cast<double>(samples));
  }
  // The k = 0 bin: the offset is fitted, so it carries the white level only.
  for (std::size_t tau = 0; tau <= order; ++tau) r[tau] = (r[tau] + spectrum.white_v2) / static_cast<double>(samples);
  if (!(r[0] > 0.0)) return {};
  // Levinson–Durbin.
  std::vector<double> a(order, 0.0), previous;
  double error = r[0];
  for (std::size_t i = 0; i < order; ++i) {
    double acc = r[i + 1];
    for (std::size_t j = 0; j < i; ++j) acc += a[j] * r[i - j];
    const double reflection = -acc / error;
    previous = a;
    a[i] = reflection;
    for (std::size_t j = 0; j < i; ++j) a[j] = previous[j] + reflection * previous[i - 1 - j];
    error *= 1.0 - reflection * reflection;
    if (!(error > 0.0)) break;
  }
  return Whitener(std::move(a), std::sqrt(std::max(error, 0.0)));
}

}  // namespace stengmc
