#include "spectral/amplitude_spectrum.hpp"

#include <fftw3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "spectral/dtft.hpp"
#include "spectral/fftw_planner.hpp"

namespace stengmc {

namespace {

// Analyzers a thread keeps for reuse; a study analyses one length and window per run, so
// a few suffice (the oldest goes when a new one would exceed this).
constexpr std::size_t ANALYZERS_PER_THREAD = 4;

// Dirichlet kernel D(y) = sum_{n<M} e^{-2 pi i y n / M} = e^{-i pi y (M-1)/M} sin(pi y) / sin(pi y / M),
// y in bins; at y = kM (0/0) the ratio's limit M cos(pi y) / cos(pi y / M) (l'Hopital).
std::complex<double> dirichlet(double y, double m) {
  const double s = std::sin(PI * y / m);
  const double ratio = std::abs(s) < 1e-9 ? m * std::cos(PI * y) / std::cos(PI * y / m) : std::sin(PI * y) / s;
  return std::polar(ratio, -PI * y * (m - 1.0) / m);
}

void check_sample_rate(double sample_rate_hz) {
  if (!(std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0)) {
    throw InputError("spectrum: sample rate must be a positive finite number of Hz, got " +
                     std::to_string(sample_rate_hz));
  }
}

}  // namespace

//! FFTW buffers and plan; owned so the analyzer's destructor releases them under the lock.
struct SpectrumAnalyzer::Plan {
  double* in = nullptr;         // windowed, zero-padded signal (padded_ values)
  fftw_complex* out = nullptr;  // bins 0 .. padded_/2
  fftw_plan plan = nullptr;

  Plan() = default;
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;
  ~Plan() {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (plan != nullptr) fftw_destroy_plan(plan);
    fftw_free(out);
    fftw_free(in);
  }
};

SpectrumAnalyzer::SpectrumAnalyzer(std::size_t samples, WindowKind window, std::size_t zero_pad_factor)
    : samples_(samples), padded_(samples * zero_pad_factor) {
  if (samples == 0) throw InputError("spectrum: the analysed signal must have at least 1 sample");
  if (zero_pad_factor == 0) throw InputError("spectrum: zero_pad_factor must be >= 1");
  if (padded_ / zero_pad_factor != samples ||
      padded_ > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError("spectrum: padded length " + std::to_string(samples) + " x " +
                     std::to_string(zero_pad_factor) + " is too large for FFTW's int sizes");
  }
  window_ = make_window(window, samples_);
  cosine_coefficients_ = cosine_coefficients(window);
  window_sum_ = std::accumulate(window_.begin(), window_.end(), 0.0);

  plan_ = std::make_unique<Plan>();
  const std::size_t bins = padded_ / 2 + 1;
  plan_->in = fftw_alloc_real(padded_);
  plan_->out = fftw_alloc_complex(bins);
  if (plan_->in == nullptr || plan_->out == nullptr) throw Error("spectrum: FFTW could not allocate buffers");
  // FFTW_ESTIMATE, not MEASURE: MEASURE picks the algorithm by timing it on this machine,
  // so two runs (or two threads) can get different plans and results that differ in the
  // last bits, which would break the bit-identical reproducibility tests (STYLE.md); it
  // also costs up to seconds per odd length. Analysis lengths are arbitrary, the FFT is a
  // small part of a realisation, and ESTIMATE's plan is deterministic.
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  plan_->plan = fftw_plan_dft_r2c_1d(static_cast<int>(padded_), plan_->in, plan_->out, FFTW_ESTIMATE);
  if (plan_->plan == nullptr) throw Error("spectrum: FFTW could not create a plan of length " + std::to_string(padded_));
}

SpectrumAnalyzer::~SpectrumAnalyzer() = default;

SpectrumAnalyzer& thread_spectrum_analyzer(std::size_t samples, WindowKind window, std::size_t zero_pad_factor) {
  thread_local std::vector<std::unique_ptr<SpectrumAnalyzer>> kept;
  thread_local std::vector<std::pair<WindowKind, std::size_t>> keys;  // window and padding of kept[i]
  // Most recently used last: the oldest unused one goes first, never one just handed out
  // (a caller holding one analyzer while asking for a second keeps the first).
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (kept[i]->samples() != samples || keys[i] != std::pair{window, zero_pad_factor}) continue;
    std::rotate(kept.begin() + static_cast<std::ptrdiff_t>(i), kept.begin() + static_cast<std::ptrdiff_t>(i) + 1, kept.end());
    std::rotate(keys.begin() + static_cast<std::ptrdiff_t>(i), keys.begin() + static_cast<std::ptrdiff_t>(i) + 1, keys.end());
    return *kept.back();
  }
  auto made = std::make_unique<SpectrumAnalyzer>(samples, window, zero_pad_factor);
  if (kept.size() == ANALYZERS_PER_THREAD) {
    kept.erase(kept.begin());
    keys.erase(keys.begin());
  }
  kept.push_back(std::move(made));
  keys.emplace_back(window, zero_pad_factor);
  return *kept.back();
}

AmplitudeSpectrum SpectrumAnalyzer::analyse(std::span<const double> signal, double sample_rate_hz) {
  if (signal.size() != samples_) {
    throw InputError("spectrum: analyser made for " + std::to_string(samples_) + " samples was given " +
                     std::to_string(signal.size()));
  }
  check_sample_rate(sample_rate_hz);
  for (std::size_t n = 0; n < samples_; ++n) plan_->in[n] = window_[n] * signal[n];
  for (std::size_t n = samples_; n < padded_; ++n) plan_->in[n] = 0.0;
  fftw_execute(plan_->plan);

  const std::size_t bins = padded_ / 2 + 1;
  AmplitudeSpectrum spectrum;
  spectrum.bin_width_hz = sample_rate_hz / static_cast<double>(padded_);
  spectrum.resolution_hz = sample_rate_hz / static_cast<double>(samples_);
  spectrum.frequency_hz.resize(bins);
  spectrum.amplitude.resize(bins);
  for (std::size_t k = 0; k < bins; ++k) {
    // The single-sided spectrum folds bin -k onto k, hence the factor 2; DC and (for an even
    // length) the Nyquist bin have no mirror image, so a constant c gives A_0 = |c| and
    // c cos(pi n) gives A_{M/2} = |c| (MODEL.md §3).
    const bool unpaired = k == 0 || 2 * k == padded_;
    const double scale = (unpaired ? 1.0 : 2.0) / window_sum_;
    spectrum.frequency_hz[k] = static_cast<double>(k) * spectrum.bin_width_hz;
    spectrum.amplitude[k] = scale * std::hypot(plan_->out[k][0], plan_->out[k][1]);
  }
  return spectrum;
}

double SpectrumAnalyzer::amplitude_at(std::span<const double> signal, double sample_rate_hz,
                                      double frequency_hz) const {
  if (signal.size() != samples_) {
    throw InputError("spectrum: analyser made for " + std::to_string(samples_) + " samples was given " +
                     std::to_string(signal.size()));
  }
  check_sample_rate(sample_rate_hz);
  if (!std::isfinite(frequency_hz)) throw InputError("spectrum: amplitude_at frequency must be finite");

  // Direct O(M) windowed DTFT (dtft.hpp): peak refinement evaluates it many times per peak.
  std::vector<double> windowed(samples_);
  for (std::size_t n = 0; n < samples_; ++n) windowed[n] = window_[n] * signal[n];
  return 2.0 * std::abs(windowed_dtft(windowed, frequency_hz / sample_rate_hz, false).value) / window_sum_;
}

double SpectrumAnalyzer::window_response(double offset_hz, double sample_rate_hz) const {
  check_sample_rate(sample_rate_hz);
  if (samples_ == 1) return 1.0;  // make_window's one-sample window is {1}
  // A cosine window w_n = sum_j c_j cos(2 pi j n / M), c_j = (-1)^j a_j, is a sum of shifted
  // rectangles in frequency: W(x) = sum_j c_j / 2 (D(x - j) + D(x + j)) (Harris 1978, §4),
  // exact and O(1), where a direct sum would cost O(M) per call.
  const double m = static_cast<double>(samples_);
  const double x = offset_hz / sample_rate_hz * m;
  std::complex<double> total = 0.0;
  double sign = 1.0;
  for (std::size_t j = 0; j < cosine_coefficients_.size(); ++j) {
    const double shift = static_cast<double>(j);
    total += 0.5 * sign * cosine_coefficients_[j] * (dirichlet(x - shift, m) + dirichlet(x + shift, m));
    sign = -sign;
  }
  return std::abs(total) / window_sum_;
}

}  // namespace stengmc
