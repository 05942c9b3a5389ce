#include "inverse/event_ringing.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

double ringing_voltage_v(const KnownDevice& device, double stiffness_n_per_m, double velocity_amplitude_m_per_s) {
  const double omega = device.angular_frequency(stiffness_n_per_m);
  const double rc = device.circuit.load_resistance_ohm * device.circuit.load_capacitance_f;
  // |R sigma w| [V s/m]: a line's amplitude is a magnitude, whatever the charge's sign.
  const double scale = std::abs(device.voltage_scale_v()) / device.model.belt_velocity_m_per_s;
  return scale * velocity_amplitude_m_per_s / std::sqrt(1.0 + omega * omega * rc * rc);
}

double onset_ringing_v(const KnownDevice& device, double k) {
  const double free_swing = device.sliding_friction_n() / std::sqrt(k * device.asperity.mass_kg);
  return ringing_voltage_v(device, k, std::min(device.model.belt_velocity_m_per_s, free_swing));
}

double release_ringing_v(const KnownDevice& device, double k) {
  return ringing_voltage_v(device, k, device.sliding_friction_n() / std::sqrt(k * device.asperity.mass_kg));
}

double step_ringing_v(const KnownDevice& device, double k_before, double k_after) {
  const double jump = device.sliding_friction_n() * std::abs(1.0 / k_after - 1.0 / k_before);
  const double swing = jump * std::sqrt(k_after / device.asperity.mass_kg);
  return ringing_voltage_v(device, k_after, std::min(device.model.belt_velocity_m_per_s, swing));
}

}  // namespace stengmc
