#pragma once
// Study text of MODEL.md's Table 1-2 device, shared by the tests that simulate it or pass it
// as a `--known` device: one copy, so that a test that varies one key (the belt, the damping,
// the charge, the counterface) says only that. (The tracking validation script takes the same
// keys from studies/monitoring/device_unexcited.toml; tests/support/known_device.toml is the
// v_b = 10 m/s device that the Python checks read as a file.)
#include <string>

namespace stengmc::testing {

//! What a test varies of the Table 1-2 device; every other key is Table 1-2's.
struct Table1Device {
  std::string belt_velocity_m_per_s = "5";
  std::string damping_n_s_per_m = "1e-7";
  std::string charge_density_c_per_m2 = "80e-6";
  std::string counterface{};  //!< a whole [counterface] table, or nothing (unexcited)
};

//! `[model]` (Model 2, consistent friction), the optional `[counterface]` and `[circuit]`
//! (R = 1 MOhm, C_L = 0): what a random surface of Table 1-2 asperities needs beside it.
inline std::string table1_model_and_circuit(const Table1Device& d = {}) {
  return R"([model]
kind = "model2"
belt_velocity_m_per_s = )" + d.belt_velocity_m_per_s + R"(
static_friction = 0.28
kinetic_friction = 0.22
damping_n_s_per_m = )" + d.damping_n_s_per_m + R"(
stribeck_decay_s_per_m = 1e-7
atan_sharpness_s_per_m = 1e3
friction_form = "consistent"
)" + d.counterface + R"(
[circuit]
load_resistance_ohm = 1e6
load_capacitance_f = 0
)";
}

//! table1_model_and_circuit and `[surface.defaults]` (m = 1e-12 kg, N = 1 mN, l = 50 um,
//! w = 10 um, d = 50 um): every key a known device must write out. The caller puts the
//! top-level keys (duration_s, sample_rate_hz, seed) before it and its asperities after it.
inline std::string table1_device_keys(const Table1Device& d = {}) {
  return table1_model_and_circuit(d) + R"([surface.defaults]
mass_kg = 1e-12
normal_load_n = 1e-3
charge_density_c_per_m2 = )" + d.charge_density_c_per_m2 + R"(
effective_thickness_m = 50e-6
width_m = 10e-6
length_m = 50e-6
)";
}

//! A random surface of `summits` Table 1-2 asperities (fixed count, heights, load and element
//! geometry) whose stiffnesses are lognormal(`median` N/m, `sigma_log`), with its [domain]
//! policy "flag" (an invalid realisation is kept and marked) and a plain [spectrum]. The caller
//! adds [model], [noise] and [ensemble].
inline std::string table1_random_surface(int summits, const std::string& median, const std::string& sigma_log) {
  return R"([domain]
policy = "flag"
[surface]
kind = "random"
nominal_area_m2 = 1e-6
[surface.summits]
count_rule = "fixed"
count = )" + std::to_string(summits) + R"(
[surface.heights]
kind = "fixed"
values = [110e-6]
[surface.stiffness]
kind = "lognormal"
median = )" + median + R"(
sigma_log = )" + sigma_log + R"(
[surface.load]
rule = "fixed"
normal_load_n = 1e-3
[surface.element]
geometry = "fixed"
length_m = 50e-6
width_m = 10e-6
charge_density_c_per_m2 = 80e-6
effective_thickness_m = 50e-6
[spectrum]
high_resolution = false
element_currents = false
)";
}

}  // namespace stengmc::testing
