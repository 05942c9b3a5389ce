#include "inverse/line_centre_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <numeric>

namespace stengmc {

namespace {

//! x = (centre [Hz], log half-width, log height, log noise, then per neighbour line: centre
//! [Hz], log height). Every line shares the half-width: the asperities share m and c.
using Parameters = std::vector<double>;

double spectrum_at(const Parameters& x, double f) {
  const double b = std::exp(x[1]);
  double s = std::exp(x[3]);
  for (std::size_t i = 0; i < x.size(); i += (i == 0 ? 4 : 2)) {
    const double centre = x[i], height = std::exp(x[i == 0 ? 2 : i + 1]);
    const double u = (f - centre) / b;
    s += height / (1.0 + u * u);
  }
  return s;
}

double negative_log_likelihood(const LocalPeriodogram& p, const Parameters& x) {
  double sum = 0.0;
  for (std::size_t j = 0; j < p.power.size(); ++j) {
    const double s = spectrum_at(x, p.frequency_hz[j]);
    sum += std::log(s) + p.power[j] / s;
  }
  return sum;
}

//! Nelder-Mead simplex (Nelder & Mead, Computer Journal 7 (1965)), standard coefficients; a
//! zero step keeps that parameter where it starts (every vertex shares it).
Parameters minimise(const LocalPeriodogram& p, Parameters start, const Parameters& step) {
  const std::size_t d = start.size();
  std::vector<Parameters> simplex(d + 1, start);
  std::vector<double> value(d + 1);
  for (std::size_t i = 0; i <= d; ++i) {
    if (i > 0) simplex[i][i - 1] += step[i - 1];
    value[i] = negative_log_likelihood(p, simplex[i]);
  }
  std::vector<std::size_t> order(d + 1);
  for (int iteration = 0; iteration < 500 * static_cast<int>(d); ++iteration) {
    for (std::size_t i = 0; i <= d; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return value[a] < value[b]; });
    const std::size_t best = order[0], worst = order[d], second = order[d - 1];
    if (std::abs(value[worst] - value[best]) < 1e-10 * (1.0 + std::abs(value[best]))) break;
    Parameters centroid(d, 0.0);
    for (std::size_t i = 0; i < d; ++i)
      for (std::size_t k = 0; k < d; ++k) centroid[k] += simplex[order[i]][k] / static_cast<double>(d);
    auto along = [&](double t) {
      Parameters q(d);
      for (std::size_t k = 0; k < d; ++k) q[k] = centroid[k] + t * (simplex[worst][k] - centroid[k]);
      return q;
    };
    const Parameters reflected = along(-1.0);
    const double fr = negative_log_likelihood(p, reflected);
    if (fr < value[best]) {
      const Parameters expanded = along(-2.0);
      const double fe = negative_log_likelihood(p, expanded);
      if (fe < fr) simplex[worst] = expanded, value[worst] = fe;
      else simplex[worst] = reflected, value[worst] = fr;
    } else if (fr < value[second]) {
      simplex[worst] = reflected, value[worst] = fr;
    } else {
      const Parameters contracted = fr < value[worst] ? along(-0.5) : along(0.5);
      const double fc = negative_log_likelihood(p, contracted);
      if (fc < std::min(fr, value[worst])) {
        simplex[worst] = contracted, value[worst] = fc;
      } else {
        for (std::size_t i = 1; i <= d; ++i) {
          for (std::size_t k = 0; k < d; ++k) simplex[order[i]][k] = 0.5 * (simplex[order[i]][k] + simplex[best][k]);
          value[order[i]] = negative_log_likelihood(p, simplex[order[i]]);
        }
      }
    }
  }
  return simplex[static_cast<std::size_t>(std::min_element(value.begin(), value.end()) - value.begin())];
}

//! Mean of the ordinates within `radius_hz` of `f` (at least the nearest one).
double local_level(const LocalPeriodogram& p, double f, double radius_hz) {
  double sum = 0.0;
  std::size_t count = 0, nearest = 0;
  for (std::size_t j = 0; j < p.power.size(); ++j) {
    if (std::abs(p.frequency_hz[j] - f) < std::abs(p.frequency_hz[nearest] - f)) nearest = j;
    if (std::abs(p.frequency_hz[j] - f) <= radius_hz) sum += p.power[j], ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : p.power[nearest];
}

}  // namespace

LocalPeriodogram local_periodogram(std::span<const double> v, double fs, double low_hz, double high_hz) {
  LocalPeriodogram p;
  const std::size_t n = v.size();
  if (n < 8) return p;
  p.span_s = static_cast<double>(n) / fs;
  // Mean and linear trend out (least squares on the centred index).
  const double nd = static_cast<double>(n), middle = 0.5 * (nd - 1.0);
  double mean = 0.0, slope_num = 0.0, slope_den = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += v[i] / nd;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) - middle;
    slope_num += u * (v[i] - mean);
    slope_den += u * u;
  }
  const double slope = slope_num / slope_den;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) y[i] = v[i] - mean - slope * (static_cast<double>(i) - middle);
  const double bin = fs / nd;
  for (auto j = static_cast<std::size_t>(std::ceil(low_hz / bin)); static_cast<double>(j) * bin <= high_hz; ++j) {
    const double f = static_cast<double>(j) * bin;
    if (f <= 0.0 || f >= 0.5 * fs) continue;
    // e^{-i w n} by recurrence, renormalised every 1024 samples (its modulus drifts by ~1e-16 a step).
    const std::complex<double> rotation = std::polar(1.0, -2.0 * std::numbers::pi * f / fs);
    std::complex<double> phasor(1.0, 0.0), sum(0.0, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      sum += y[i] * phasor;
      phasor *= rotation;
      if ((i & 1023u) == 1023u) phasor /= std::abs(phasor);
    }
    p.frequency_hz.push_back(f);
    p.power.push_back(std::norm(sum) / nd);
  }
  return p;
}

LorentzianFit fit_lorentzian(const LocalPeriodogram& p, double centre_guess_hz, double half_width_guess_hz, bool fit_width,
                             std::span<const double> neighbours_hz) {
  LorentzianFit fit;
  const std::size_t m = p.power.size();
  if (m < 8 || !(half_width_guess_hz > 0.0)) return fit;
  // Start at the largest ordinate of the periodogram smoothed over about one half-width, within
  // three half-widths of the guess (the track's windows place the line that well).
  const double bin = p.frequency_hz[1] - p.frequency_hz[0];
  const auto radius = static_cast<std::ptrdiff_t>(std::max(1.0, std::round(half_width_guess_hz / bin)));
  std::size_t peak = m;
  double peak_value = -1.0;
  for (std::size_t j = 0; j < m; ++j) {
    if (std::abs(p.frequency_hz[j] - centre_guess_hz) > 3.0 * half_width_guess_hz) continue;
    double smooth = 0.0;
    std::size_t count = 0;
    for (std::ptrdiff_t k = -radius; k <= radius; ++k) {
      const std::ptrdiff_t q = static_cast<std::ptrdiff_t>(j) + k;
      if (q < 0 || q >= static_cast<std::ptrdiff_t>(m)) continue;
      smooth += p.power[static_cast<std::size_t>(q)];
      ++count;
    }
    smooth /= static_cast<double>(count);
    if (smooth > peak_value) peak_value = smooth, peak = j;
  }
  if (peak == m) return fit;
  std::vector<double> sorted = p.power;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(m / 2), sorted.end());
  const double noise0 = std::max(sorted[m / 2] / std::numbers::ln2, 1e-300);  // an exponential's median is ln 2 x its mean
  const double height0 = std::max(peak_value - noise0, noise0);
  // The periodogram of a span T expects the autocovariance tapered by the triangle 1 - |tau|/T,
  // ~e^{-|tau|/T} over the line's coherence time: the expected line is a Lorentzian wider by
  // 1 / (2 pi T) (to first order in 1 / (gamma T)). Fixed widths are widened by it.
  const double leakage_hz = fit_width ? 0.0 : 1.0 / (2.0 * std::numbers::pi * p.span_s);
  Parameters x{p.frequency_hz[peak], std::log(half_width_guess_hz + leakage_hz), std::log(height0), std::log(noise0)};
  Parameters step{half_width_guess_hz, fit_width ? 0.5 : 0.0, 0.5, 0.5};
  // Other tracks' lines inside the band (not the line itself: 3 half-widths clear of it) are
  // fitted with it, so their tails are no slope under it that drags its centre.
  const double low = p.frequency_hz.front(), high = p.frequency_hz.back();
  for (double other : neighbours_hz)
    if (other > low && other < high && std::abs(other - x[0]) > 3.0 * half_width_guess_hz) {
      x.push_back(other);
      x.push_back(std::log(std::max(local_level(p, other, half_width_guess_hz) - noise0, noise0)));
      step.push_back(half_width_guess_hz);
      step.push_back(0.5);
    }
  x = minimise(p, x, step);
  for (std::size_t i = 0; i < step.size(); ++i) step[i] *= (i == 0 || (i >= 4 && i % 2 == 0)) ? 0.2 * std::exp(x[1]) / half_width_guess_hz : 0.2;
  x = minimise(p, x, step);  // restarted: Nelder-Mead can stall
  fit.centre_hz = x[0];
  fit.half_width_hz = std::exp(x[1]);
  fit.height = std::exp(x[2]);
  fit.noise = std::exp(x[3]);
  fit.log_likelihood = -negative_log_likelihood(p, x);
  // Whittle's information (the expected one: sum_j grad log S_j grad log S_j^T, Percival &
  // Walden sec. 6.6), at the fit, over every free parameter; steadier than the observed
  // curvature, which the periodogram's exponential scatter shakes.
  const std::size_t lines = 1 + (x.size() - 4) / 2;
  const auto free = static_cast<Eigen::Index>((fit_width ? 4 : 3) + 2 * (lines - 1));
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(free, free);
  for (std::size_t j = 0; j < m; ++j) {
    const double f = p.frequency_hz[j];
    const double s = spectrum_at(x, f);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(free);
    double width_term = 0.0;
    for (std::size_t l = 0; l < lines; ++l) {
      const double centre = l == 0 ? x[0] : x[4 + 2 * (l - 1)];
      const double height = std::exp(l == 0 ? x[2] : x[5 + 2 * (l - 1)]);
      const double u = (f - centre) / fit.half_width_hz;
      const double lorentz = 1.0 / (1.0 + u * u);
      width_term += height * lorentz * lorentz * 2.0 * u * u;
      const Eigen::Index c = l == 0 ? 0 : static_cast<Eigen::Index>((fit_width ? 4 : 3) + 2 * (l - 1));
      g(c) = height * lorentz * lorentz * 2.0 * u / fit.half_width_hz / s;  // d log S / d centre
      g(l == 0 ? (fit_width ? 2 : 1) : c + 1) = height * lorentz / s;      // d log S / d log height
    }
    if (fit_width) g(1) = width_term / s;                                  // d log S / d log half-width
    g(fit_width ? 3 : 2) = fit.noise / s;                                  // d log S / d log noise
    information += g * g.transpose();
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const double variance = ldlt.isPositive() ? ldlt.solve(Eigen::MatrixXd::Identity(free, free))(0, 0) : -1.0;
  fit.centre_se_hz = variance > 0.0 && std::isfinite(variance) ? std::sqrt(variance) : std::numeric_limits<double>::infinity();
  fit.valid = std::isfinite(fit.centre_se_hz) && fit.centre_hz > low && fit.centre_hz < high;
  return fit;
}

FitBand fit_band(double low_hz, double high_hz, double reach_hz, std::span<const double> neighbours_hz, double least_reach_hz) {
  FitBand band{low_hz - reach_hz, high_hz + reach_hz, {}};
  const double middle = 0.5 * (low_hz + high_hz);
  std::vector<double> inside;
  for (double f : neighbours_hz)
    if (f > band.low_hz && f < band.high_hz && (f < low_hz || f > high_hz)) inside.push_back(f);
  std::sort(inside.begin(), inside.end(), [&](double a, double b) { return std::abs(a - middle) < std::abs(b - middle); });
  for (std::size_t i = 0; i < inside.size(); ++i) {
    if (i < 2) {
      band.neighbours_hz.push_back(inside[i]);
      continue;
    }
    if (inside[i] < low_hz) band.low_hz = std::max(band.low_hz, std::min(low_hz - least_reach_hz, 0.5 * (low_hz + inside[i])));
    else band.high_hz = std::min(band.high_hz, std::max(high_hz + least_reach_hz, 0.5 * (high_hz + inside[i])));
  }
  // A fitted neighbour the band no longer holds is dropped.
  std::erase_if(band.neighbours_hz, [&](double f) { return f <= band.low_hz || f >= band.high_hz; });
  return band;
}

double centre_standard_deviation_hz(double half_width_hz, double span_s) {
  return std::sqrt(half_width_hz / (2.0 * std::numbers::pi * span_s));
}

}  // namespace stengmc
