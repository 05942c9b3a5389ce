#include "ensemble/realisation_record.hpp"

namespace stengmc {

namespace {

constexpr std::array<ScalarInfo, SCALAR_COUNT> SCALARS{{
    {"summit_count", "1", "summits drawn"},
    {"asperity_count", "1", "summits in contact: the asperities simulated"},
    {"contact_density", "1", "real contact area over nominal area A_r/A0 (0 without material data)"},
    {"load_redistribution", "1", "fraction of the normal load the contact spots' interaction moves"},
    {"n_sliding", "1", "asperities expected to show a spectral line"},
    {"voltage_rms_v", "V", "rms of the clean load voltage over the valid samples"},
    {"voltage_peak_v", "V", "largest absolute load voltage"},
    {"final_charge_c", "C", "charge delivered to the load at the last valid sample"},
    {"mean_charging_rate_a", "A", "final charge over simulated time"},
    {"fft_detected", "1", "FFT peaks detected"},
    {"fft_identifiable", "1", "asperities identified by FFT peaks"},
    {"fft_ratio", "1", "asperities identified by FFT peaks over asperities sliding"},
    {"hr_detected", "1", "ESPRIT lines detected"},
    {"hr_identifiable", "1", "asperities identified by ESPRIT lines"},
    {"hr_ratio", "1", "asperities identified by ESPRIT lines over asperities sliding"},
    {"cannot_slip_count", "1", "Model 1 asperities that cannot slip"},
    {"near_length_count", "1", "Model 2 asperities breaking away near the element length"},
    {"independence_holds", "1", "1 when the contact spots' interaction stays below its threshold"},
}};

constexpr std::array<ScalarInfo, ASPERITY_COLUMN_COUNT> COLUMNS{{
    {"stiffness_n_per_m", "N/m", "asperity tangential stiffness"},
    {"normal_load_n", "N", "asperity normal load"},
    {"mass_kg", "kg", "asperity effective mass"},
    {"natural_frequency_hz", "Hz", "asperity natural frequency"},
    {"slip_fraction", "1", "fraction of the analysed samples the asperity slides"},
    {"max_x_over_l", "1", "largest displacement over the element length"},
    {"rms_velocity_m_per_s", "m/s", "rms asperity velocity"},
    {"fft_identified", "1", "1 when an FFT peak identifies the asperity"},
    {"fft_frequency_error_hz", "Hz", "FFT peak frequency minus the asperity's natural frequency (0 unmatched)"},
    {"hr_identified", "1", "1 when an ESPRIT line identifies the asperity"},
    {"hr_frequency_error_hz", "Hz", "ESPRIT line frequency minus the asperity's natural frequency (0 unmatched)"},
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
