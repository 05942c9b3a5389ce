#include "inverse/track_peaks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

namespace {
constexpr std::size_t ZERO_PAD = 4;
}  // namespace

PeakLineDetector::PeakLineDetector(const KnownDevice& device, LineDetectorSettings settings)
    : device_(device), settings_(settings) {}

WindowLines PeakLineDetector::detect(std::span<const double> window) const {
  WindowLines out;
  const std::size_t n = window.size();
  const double nd = static_cast<double>(n), fs = settings_.sample_rate_hz, length_s = nd / fs;
  out.mean_v = std::accumulate(window.begin(), window.end(), 0.0) / nd;
  std::vector<double> centred(window.begin(), window.end());
  for (double& v : centred) v -= out.mean_v;
  SpectrumAnalyzer& analyzer = thread_spectrum_analyzer(n, WindowKind::hann, ZERO_PAD);
  const AmplitudeSpectrum spectrum = analyzer.analyse(centred, fs);
  const std::vector<double>& f = spectrum.frequency_hz;
  const std::vector<double>& a = spectrum.amplitude;

  // The floor: the band's median amplitude converted to the white sigma that gives it (for white
  // noise of sigma the Hann amplitude's median is 2 sigma sqrt(ln 2 sum w^2) / sum w; see
  // inverse/noise_level.cpp); lines fill a small share of the band.
  std::vector<double> band;
  std::size_t first = f.size(), last = 0;
  for (std::size_t k = 1; k + 1 < f.size(); ++k)
    if (f[k] >= settings_.band_low_hz && f[k] <= settings_.band_high_hz) {
      band.push_back(a[k]);
      first = std::min(first, k);
      last = k;
    }
  if (band.size() < 3 || !(settings_.noise_sigma_v > 0.0)) return out;
  std::nth_element(band.begin(), band.begin() + static_cast<std::ptrdiff_t>(band.size() / 2), band.end());
  const std::vector<double>& w = analyzer.window();
  const double sum = std::accumulate(w.begin(), w.end(), 0.0);
  const double squares = std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
  const double band_sigma = band[band.size() / 2] * sum / (2.0 * std::sqrt(std::log(2.0) * squares));
  const double sigma = std::max(settings_.noise_sigma_v, band_sigma);
  out.floor_v = sigma;

  const double gamma = device_.damping_rate_per_s();
  // A window of two coherence times holds about one random realisation of the line's shape: its
  // peak lands anywhere within the half-width of the line as the window resolves it, the
  // line's own c / 4 pi m widened by the Hann window's ~1.5 / (2 pi T) (13 kHz measured between
  // the windows of the single excited asperity of tests/inverse/test_tracking.cpp, 11.9 kHz
  // from this). The centre's Cramer-Rao bound sqrt(gamma / T) / 2 pi (5.6 kHz) needs many
  // coherence times to be reached: the segments' fits do that (line_centre_fit.hpp).
  const double wander_hz = (gamma + 1.5 / length_s) / (2.0 * std::numbers::pi);
  SpectrumAnalyzer& halves = thread_spectrum_analyzer(n / 2, WindowKind::hann);
  const std::span<const double> first_half(centred.data(), n / 2), second_half(centred.data() + n / 2, n / 2);
  const double half_s = static_cast<double>(n / 2) / fs;
  const double z_min = settings_.threshold_snr - settings_.grey_snr;
  std::vector<WindowLine> lines;
  for (std::size_t k = std::max<std::size_t>(first, 1); k <= last; ++k) {
    if (!(a[k] > a[k - 1] && a[k] >= a[k + 1])) continue;
    const double z_peak = a[k] * std::sqrt(0.5 * nd) / sigma;
    if (z_peak < z_min) continue;
    // Parabola through the log amplitudes (exact for a Gaussian lobe; Hann's is close).
    const double l0 = std::log(a[k - 1]), l1 = std::log(a[k]), l2 = std::log(a[k + 1]);
    const double denominator = l0 - 2.0 * l1 + l2;
    const double offset = denominator < 0.0 ? std::clamp(0.5 * (l0 - l2) / denominator, -0.5, 0.5) : 0.0;
    WindowLine line;
    line.frequency_hz = f[k] + offset * spectrum.bin_width_hz;
    line.amplitude_v = std::exp(l1 - 0.25 * (l0 - l2) * offset);
    line.snr = line.amplitude_v * std::sqrt(0.5 * nd) / sigma;
    const double noise_term = std::sqrt(6.0) / (2.0 * std::numbers::pi * line.snr * length_s);
    line.frequency_se_hz = std::hypot(wander_hz, noise_term);
    const double a1 = halves.amplitude_at(first_half, fs, line.frequency_hz);
    const double a2 = halves.amplitude_at(second_half, fs, line.frequency_hz);
    line.damping_per_s = a1 > 0.0 && a2 > 0.0 ? std::log(a1 / a2) / half_s : 0.0;
    line.floor_ratio = sigma / settings_.noise_sigma_v;
    line.detected = line.snr >= settings_.threshold_snr;
    line.stiffness_n_per_m = stiffness_at(device_, line.frequency_hz);
    line.stiffness_low = stiffness_at(device_, std::max(0.0, line.frequency_hz - Z90 * line.frequency_se_hz));
    line.stiffness_high = stiffness_at(device_, line.frequency_hz + Z90 * line.frequency_se_hz);
    lines.push_back(line);
  }
  // Strongest first: a peak within cluster_hz of a stronger one is its side lobe or a bump of
  // the same random line; harmonics (2f, 3f of a line 3x stronger) and peaks below the window's
  // dynamic range go as in LineDetector. And a driven line's Lorentzian tail, amplitude
  // A b / sqrt(df^2 + b^2) at df from it (b: its half-width as the window resolves it), is a
  // random process too: its periodogram is exponentially distributed about that level, and
  // over the ~T B = 50 cells of a window it reaches 8.5 x its mean power (2.9 x in amplitude)
  // with probability 1e-2. A weaker peak is a line of its own only above 3 x the tails of the
  // stronger lines kept (at eps = 0.01 the tails' bumps reach 1/5-1/8 of the line at 50-130 kHz
  // from it: seen on the single excited asperity of tests/inverse/test_tracking.cpp).
  std::sort(lines.begin(), lines.end(), [](const WindowLine& x, const WindowLine& y) { return x.snr > y.snr; });
  const double cluster_hz = settings_.cluster_hz > 0.0 ? settings_.cluster_hz : 2.0 / length_s;
  const double cell = 1.0 / length_s;
  const double strongest = lines.empty() ? 0.0 : lines.front().snr;
  for (const WindowLine& l : lines) {
    if (settings_.dynamic_range > 0.0 && l.snr < settings_.dynamic_range * strongest) continue;
    const bool shadowed = std::any_of(out.lines.begin(), out.lines.end(), [&](const WindowLine& g) {
      const double df = g.frequency_hz - l.frequency_hz;
      return std::abs(df) < cluster_hz || l.amplitude_v < 3.0 * g.amplitude_v * wander_hz / std::hypot(df, wander_hz) ||
             (g.snr >= 3.0 * l.snr && (std::abs(l.frequency_hz - 2.0 * g.frequency_hz) < 0.5 * cell ||
                                       std::abs(l.frequency_hz - 3.0 * g.frequency_hz) < 0.5 * cell));
    });
    if (!shadowed) out.lines.push_back(l);
  }
  std::sort(out.lines.begin(), out.lines.end(), [](const WindowLine& x, const WindowLine& y) { return x.frequency_hz < y.frequency_hz; });
  return out;
}

}  // namespace stengmc
