#pragma once
// A known-device study for the inverse tests: MODEL.md Table 1-2 values, Model 2 at
// v_b = 10 m/s (consistent friction), l = 50 um, R = 1 MOhm, C_L = 0, every known parameter
// written out, records of `duration` at 100 MHz, and the given [inverse] table's keys.
#include <string>

namespace stengmc::testing {

inline std::string known_device_study(const std::string& duration, const std::string& inverse) {
  return "duration_s = " + duration + R"(
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
static_friction = 0.28
kinetic_friction = 0.22
damping_n_s_per_m = 1e-7
stribeck_decay_s_per_m = 1e-7
atan_sharpness_s_per_m = 1e3
friction_form = "consistent"
[circuit]
load_resistance_ohm = 1e6
load_capacitance_f = 0
[surface.defaults]
mass_kg = 1e-12
normal_load_n = 1e-3
charge_density_c_per_m2 = 80e-6
effective_thickness_m = 50e-6
width_m = 10e-6
length_m = 50e-6
[[surface.asperity]]
stiffness_n_per_m = 75
[inverse]
)" + inverse;
}

}  // namespace stengmc::testing
