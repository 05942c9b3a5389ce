#include "spectral/power_law_noise.hpp"

#include <fftw3.h>

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

#include "core/error.hpp"
#include "spectral/fftw_planner.hpp"

namespace stengmc {

namespace {

//! FFTW buffers and the two plans, released under the planner's lock.
struct ShapingPlans {
  double* real = nullptr;
  fftw_complex* bins = nullptr;
  fftw_plan forward = nullptr;
  fftw_plan backward = nullptr;

  explicit ShapingPlans(std::size_t n) {
    real = fftw_alloc_real(n);
    bins = fftw_alloc_complex(n / 2 + 1);
    if (real == nullptr || bins == nullptr) throw Error("power-law noise: FFTW could not allocate " + std::to_string(n) + " values");
    // FFTW_ESTIMATE: a deterministic plan (spectral/amplitude_spectrum.cpp says why).
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    forward = fftw_plan_dft_r2c_1d(static_cast<int>(n), real, bins, FFTW_ESTIMATE);
    backward = fftw_plan_dft_c2r_1d(static_cast<int>(n), bins, real, FFTW_ESTIMATE);
    if (forward == nullptr || backward == nullptr) throw Error("power-law noise: FFTW could not plan " + std::to_string(n) + " points");
  }
  ShapingPlans(const ShapingPlans&) = delete;
  ShapingPlans& operator=(const ShapingPlans&) = delete;
  ~ShapingPlans() {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (backward != nullptr) fftw_destroy_plan(backward);
    if (forward != nullptr) fftw_destroy_plan(forward);
    fftw_free(bins);
    fftw_free(real);
  }
};

}  // namespace

std::vector<double> power_law_noise(std::size_t samples, double exponent, RandomEngine& engine) {
  if (!(exponent >= 0.0 && exponent <= 4.0))
    throw InputError("power-law noise: the exponent must lie in [0, 4], got " + std::to_string(exponent));
  if (samples < 2) throw InputError("power-law noise needs at least 2 samples");
  if (samples > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw InputError("power-law noise: " + std::to_string(samples) + " samples exceed FFTW's int sizes");
  ShapingPlans plans(samples);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t j = 0; j < samples; ++j) plans.real[j] = normal(engine);
  fftw_execute(plans.forward);
  plans.bins[0][0] = plans.bins[0][1] = 0.0;  // zero mean
  for (std::size_t k = 1; k <= samples / 2; ++k) {
    const double gain = std::pow(static_cast<double>(k), -0.5 * exponent);
    plans.bins[k][0] *= gain;
    plans.bins[k][1] *= gain;
  }
  fftw_execute(plans.backward);
  std::vector<double> out(plans.real, plans.real + samples);
  double mean = 0.0;
  for (const double v : out) mean += v;
  mean /= static_cast<double>(samples);
  double variance = 0.0;
  for (const double v : out) variance += (v - mean) * (v - mean);
  variance /= static_cast<double>(samples);
  const double scale = variance > 0.0 ? 1.0 / std::sqrt(variance) : 0.0;
  for (double& v : out) v = (v - mean) * scale;
  return out;
}

}  // namespace stengmc
