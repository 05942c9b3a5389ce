#include "tribology/counterface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/constants.hpp"

namespace stengmc {

double correlation_time_s(const CounterfaceParams& counterface, double belt_velocity_m_per_s) {
  const double speed = std::abs(belt_velocity_m_per_s);
  if (!(speed > 0.0)) return std::numeric_limits<double>::infinity();
  return counterface.correlation_length_m / speed;
}

double modulation_step_s(double correlation_time_s, double highest_angular_frequency_rad_per_s) {
  // tau_c / 20: the aliases of the sampled Lorentzian add ~dt^2 / (12 tau_c^2) = 2e-4 of
  // its level; T_min / 200: linear interpolation lowers the spectrum at the line by
  // (omega dt)^2 / 6 = 1.6e-4.
  const double period = 2.0 * PI / highest_angular_frequency_rad_per_s;
  return std::min(correlation_time_s / 20.0, period / 200.0);
}

ModulationSequence::ModulationSequence(const CounterfaceStream& stream, double rms, double correlation_time_s,
                                       double step_s)
    : engine_(random_stream(stream.seed, stream.realisation, StreamKind::counterface, stream.asperity)),
      rms_(rms),
      rho_(std::exp(-step_s / correlation_time_s)),
      innovation_(rms * std::sqrt(-std::expm1(-2.0 * step_s / correlation_time_s))),
      step_s_(step_s) {
  value_ = rms_ * normal_(engine_);
  next_ = draw();
}

double ModulationSequence::draw() { return rho_ * value_ + innovation_ * normal_(engine_); }

void ModulationSequence::advance() {
  ++index_;
  value_ = next_;
  next_ = draw();
}

}  // namespace stengmc
