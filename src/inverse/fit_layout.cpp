#include "inverse/fit_layout.hpp"

#include <cmath>

namespace stengmc {

FitLayout fit_layout(const InversePrior& prior, const KnownDevice& device, const LoadPrior& loads) {
  FitLayout f;
  const double tau = prior.parameter_tolerance;
  f.load_per_atom = prior.load_cv[1] > 0.0;
  f.load_shared = !f.load_per_atom && tau > 0.0;
  f.onset_free = prior.onset_s[1] > prior.onset_s[0];
  f.damping_free = tau > 0.0 && device.model.damping_n_s_per_m > 0.0;
  f.amplitude_free = tau > 0.0;
  f.offset_free = prior.offset;
  f.coloured_noise = prior.noise == NoiseColour::coloured;
  f.nominal_load_n = device.asperity.normal_load_n;
  if (!loads.fixed()) {
    const auto [low, high] = loads.support();
    // A little beyond the prior's 1e-4 quantiles, so the fit of a load just outside is seen.
    f.min_log_load = std::log(low) - 0.2;
    f.max_log_load = std::log(high) + 0.2;
  }
  f.onset_min_s = prior.onset_s[0];
  f.onset_max_s = prior.onset_s[1];
  f.nominal_damping_rate = device.damping_rate_per_s();
  const double margin = 1.0 + 0.5 * tau;  // the bounds reach a little past the prior's
  f.min_damping_rate = f.nominal_damping_rate * (f.damping_free ? (1.0 - tau) / margin : 1.0);
  f.max_damping_rate = f.nominal_damping_rate * (f.damping_free ? (1.0 + tau) * margin : 1.0);
  f.min_amplitude = f.amplitude_free ? (1.0 - tau) / margin : 1.0;
  f.max_amplitude = f.amplitude_free ? (1.0 + tau) * margin : 1.0;
  return f;
}

}  // namespace stengmc
