#include "inverse/track_lines.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "spectral/amplitude_spectrum.hpp"
#include "spectral/esprit.hpp"

namespace stengmc {

double stiffness_at(const KnownDevice& device, double frequency_hz) {
  return device.stiffness_for(2.0 * std::numbers::pi * frequency_hz);
}

double frequency_at(const KnownDevice& device, double stiffness_n_per_m) {
  return device.angular_frequency(stiffness_n_per_m) / (2.0 * std::numbers::pi);
}

std::vector<double> frequency_standard_errors(std::span<const double> f, std::span<const double> a, std::span<const double> d,
                                              std::span<const double> phi, std::size_t samples, double fs, double sigma) {
  const std::size_t lines = f.size();
  const auto params = static_cast<Eigen::Index>(4 * lines + 1);
  Eigen::MatrixXd j(static_cast<Eigen::Index>(samples), params);
  for (std::size_t n = 0; n < samples; ++n) {
    const double t = static_cast<double>(n) / fs;
    const auto row = static_cast<Eigen::Index>(n);
    for (std::size_t i = 0; i < lines; ++i) {
      const double e = std::exp(-d[i] * t), theta = 2.0 * std::numbers::pi * f[i] * t + phi[i];
      const double c = e * std::cos(theta), s = e * std::sin(theta);
      const auto col = static_cast<Eigen::Index>(4 * i);
      j(row, col) = c;                                        // d/da
      j(row, col + 1) = -t * a[i] * c;                        // d/dd
      j(row, col + 2) = -2.0 * std::numbers::pi * t * a[i] * s;  // d/df
      j(row, col + 3) = -a[i] * s;                            // d/dphi
    }
    j(row, params - 1) = 1.0;  // the window's mean, estimated too
  }
  const Eigen::MatrixXd fisher = (j.transpose() * j) / (sigma * sigma);
  const Eigen::MatrixXd covariance = fisher.ldlt().solve(Eigen::MatrixXd::Identity(params, params));
  std::vector<double> se(lines);
  for (std::size_t i = 0; i < lines; ++i) {
    const double v = covariance(static_cast<Eigen::Index>(4 * i + 2), static_cast<Eigen::Index>(4 * i + 2));
    se[i] = v > 0.0 && std::isfinite(v) ? std::sqrt(v) : std::numeric_limits<double>::infinity();
  }
  return se;
}

double LineDetector::in_band_floor(std::span<const double> centred, const std::vector<Line>& lines) const {
  // The residual once every line is taken out, its Hann amplitude spectrum's median over the
  // band: for white noise of sigma that median is 2 sigma sqrt(ln 2 sum w^2) / sum w (as
  // inverse/noise_level.cpp). An excited asperity's off-resonance response and the random
  // wander of its own line leave a floor there that white measurement noise does not explain.
  const double fs = settings_.sample_rate_hz;
  std::vector<double> residual(centred.begin(), centred.end());
  for (const Line& l : lines)
    for (std::size_t n = 0; n < residual.size(); ++n) {
      const double t = static_cast<double>(n) / fs;
      residual[n] -= l.amplitude * std::exp(-l.damping_per_s * t) * std::cos(2.0 * std::numbers::pi * l.frequency_hz * t + l.phase_rad);
    }
  SpectrumAnalyzer& analyzer = thread_spectrum_analyzer(residual.size(), WindowKind::hann);
  const AmplitudeSpectrum spectrum = analyzer.analyse(residual, fs);
  std::vector<double> band;
  for (std::size_t k = 1; k < spectrum.frequency_hz.size(); ++k)
    if (spectrum.frequency_hz[k] >= settings_.band_low_hz && spectrum.frequency_hz[k] <= settings_.band_high_hz)
      band.push_back(spectrum.amplitude[k]);
  if (band.size() < 3) return 0.0;
  auto middle = band.begin() + static_cast<std::ptrdiff_t>(band.size() / 2);
  std::nth_element(band.begin(), middle, band.end());
  const std::vector<double>& w = analyzer.window();
  const double sum = std::accumulate(w.begin(), w.end(), 0.0);
  const double squares = std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
  return *middle * sum / (2.0 * std::sqrt(std::log(2.0) * squares));
}

LineDetector::LineDetector(const KnownDevice& device, LineDetectorSettings settings) : device_(device), settings_(settings) {}

WindowLines LineDetector::detect(std::span<const double> window) const {
  WindowLines out;
  const double n = static_cast<double>(window.size());
  out.mean_v = std::accumulate(window.begin(), window.end(), 0.0) / n;
  std::vector<double> centred(window.begin(), window.end());
  for (double& v : centred) v -= out.mean_v;

  EspritOptions options;
  options.max_lines = settings_.max_lines;
  options.criterion = OrderCriterion::mdl;
  options.max_hankel_rows = 128;  // ~N/8 for 1000-sample windows; the NLS refinement recovers the accuracy
  options.min_frequency_hz = 0.5 * settings_.band_low_hz;
  const std::vector<Line> lines = estimate_lines(centred, settings_.sample_rate_hz, options);

  // Lines in the band; the rest (drift, the plateau's step, noise above the band) are dropped.
  std::vector<Line> kept;
  for (const Line& l : lines)
    if (l.frequency_hz >= settings_.band_low_hz && l.frequency_hz <= settings_.band_high_hz && l.amplitude > 0.0) kept.push_back(l);
  if (kept.empty() || !(settings_.noise_sigma_v > 0.0)) return out;

  const double fs = settings_.sample_rate_hz;
  const double sigma = std::max(settings_.noise_sigma_v, in_band_floor(centred, lines));
  out.floor_v = sigma;
  std::vector<double> f, a, d, phi;
  for (const Line& l : kept) {
    f.push_back(l.frequency_hz);
    a.push_back(l.amplitude);
    d.push_back(l.damping_per_s);
    phi.push_back(l.phase_rad);
  }
  const std::vector<double> se = frequency_standard_errors(f, a, d, phi, window.size(), fs, sigma);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    // Energy of the unit-amplitude envelope over the window: sum e^{-2 d t_n} (closed form).
    const double r = std::exp(-2.0 * d[i] / fs);
    const double energy = std::abs(1.0 - r) < 1e-12 ? n : (1.0 - std::pow(r, n)) / (1.0 - r);
    WindowLine w;
    w.frequency_hz = f[i];
    w.frequency_se_hz = se[i];
    w.amplitude_v = a[i];
    w.damping_per_s = d[i];
    // Judged against the floor: an excited asperity's off-resonance response and stick
    // episodes put broad-band power into the band that ESPRIT also fits as lines.
    w.snr = a[i] * std::sqrt(0.5 * energy) / sigma;
    w.floor_ratio = sigma / settings_.noise_sigma_v;
    if (w.snr < settings_.threshold_snr - settings_.grey_snr || !std::isfinite(se[i])) continue;
    w.detected = w.snr >= settings_.threshold_snr;
    w.stiffness_n_per_m = stiffness_at(device_, f[i]);
    w.stiffness_low = stiffness_at(device_, std::max(0.0, f[i] - Z90 * se[i]));
    w.stiffness_high = stiffness_at(device_, f[i] + Z90 * se[i]);
    out.lines.push_back(w);
  }
  // A strong ringing's harmonics (the element's capacitance is not linear in x) are no
  // asperities: a line within half a resolution cell of 2 f or 3 f of a line 3 x stronger goes.
  const double cell = settings_.sample_rate_hz / static_cast<double>(window.size());
  std::vector<WindowLine> fundamentals = out.lines;
  std::erase_if(out.lines, [&](const WindowLine& l) {
    return std::any_of(fundamentals.begin(), fundamentals.end(), [&](const WindowLine& g) {
      return g.snr >= 3.0 * l.snr && (std::abs(l.frequency_hz - 2.0 * g.frequency_hz) < 0.5 * cell ||
                                      std::abs(l.frequency_hz - 3.0 * g.frequency_hz) < 0.5 * cell);
    });
  });
  if (settings_.dynamic_range > 0.0 && !out.lines.empty()) {
    double strongest = 0.0;
    for (const WindowLine& l : out.lines) strongest = std::max(strongest, l.snr);
    std::erase_if(out.lines, [&](const WindowLine& l) { return l.snr < settings_.dynamic_range * strongest; });
  }
  if (settings_.cluster_hz > 0.0) {
    std::vector<WindowLine> by_strength = out.lines;
    std::sort(by_strength.begin(), by_strength.end(), [](const WindowLine& x, const WindowLine& y) { return x.snr > y.snr; });
    std::vector<WindowLine> kept_lines;
    for (const WindowLine& l : by_strength)
      if (std::none_of(kept_lines.begin(), kept_lines.end(), [&](const WindowLine& k) {
            return std::abs(k.frequency_hz - l.frequency_hz) < settings_.cluster_hz;
          }))
        kept_lines.push_back(l);
    std::sort(kept_lines.begin(), kept_lines.end(),
              [](const WindowLine& x, const WindowLine& y) { return x.frequency_hz < y.frequency_hz; });
    out.lines = std::move(kept_lines);
  }
  return out;
}

}  // namespace stengmc
