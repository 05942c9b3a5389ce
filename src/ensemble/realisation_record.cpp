#include "ensemble/realisation_record.hpp"

namespace stengmc {

namespace {

constexpr std::array<ScalarInfo, SCALAR_COUNT> SCALARS{{
    {"summit_count", "1"},
    {"asperity_count", "1"},
    {"contact_density", "1"},
    {"load_redistribution", "1"},
    {"n_sliding", "1"},
    {"voltage_rms_v", "V"},
    {"voltage_peak_v", "V"},
    {"final_charge_c", "C"},
    {"mean_charging_rate_a", "A"},
    {"fft_detected", "1"},
    {"fft_identifiable", "1"},
    {"fft_ratio", "1"},
    {"hr_detected", "1"},
    {"hr_identifiable", "1"},
    {"hr_ratio", "1"},
    {"cannot_slip_count", "1"},
    {"near_length_count", "1"},
    {"independence_holds", "1"},
}};

constexpr std::array<ScalarInfo, ASPERITY_COLUMN_COUNT> COLUMNS{{
    {"stiffness_n_per_m", "N/m"},
    {"normal_load_n", "N"},
    {"mass_kg", "kg"},
    {"natural_frequency_hz", "Hz"},
    {"slip_fraction", "1"},
    {"max_x_over_l", "1"},
    {"rms_velocity_m_per_s", "m/s"},
    {"fft_identified", "1"},
    {"fft_frequency_error_hz", "Hz"},
    {"hr_identified", "1"},
    {"hr_frequency_error_hz", "Hz"},
}};

}  // namespace

const ScalarInfo& scalar_info(Scalar scalar) { return SCALARS[static_cast<std::size_t>(scalar)]; }

const ScalarInfo& column_info(AsperityColumn column) { return COLUMNS[static_cast<std::size_t>(column)]; }

bool scalar_by_name(std::string_view name, Scalar& out) {
  for (std::size_t i = 0; i < SCALAR_COUNT; ++i)
    if (SCALARS[i].name == name) {
      out = static_cast<Scalar>(i);
      return true;
    }
  return false;
}

std::string scalar_names() {
  std::string out;
  for (const ScalarInfo& s : SCALARS) out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

}  // namespace stengmc
