#include "pipeline/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/constants.hpp"
#include "pipeline/slip_fraction.hpp"

namespace stengmc {

namespace {

double rms(const std::vector<double>& values, std::size_t count) {
  if (count == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t j = 0; j < count; ++j) sum += values[j] * values[j];
  return std::sqrt(sum / static_cast<double>(count));
}

}  // namespace

RunSummary summarise(const Study& study, const RunResult& result) {
  RunSummary summary;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    const Asperity& a = study.asperities[i];
    const AsperityStatistics& t = result.statistics[i];
    AsperitySummary s;
    const double damping = study.model == ModelKind::model2 ? study.model2.damping_n_s_per_m : 0.0;
    s.natural_frequency_hz = damped_natural_frequency_hz(a.stiffness_n_per_m, a.mass_kg, damping);
    s.slip_fraction = t.slip_fraction;
    s.max_x_over_l = t.max_x_m / a.element.length_m;
    s.rms_velocity_m_per_s = t.rms_velocity_m_per_s;
    summary.asperities.push_back(s);
  }
  const auto& v = result.circuit.voltage_v;
  summary.voltage_rms_v = rms(v, v.size());
  for (double x : v) summary.voltage_peak_v = std::max(summary.voltage_peak_v, std::abs(x));
  summary.final_charge_c = result.circuit.charge_c.empty() ? 0.0 : result.circuit.charge_c.back();
  return summary;
}

std::string format_summary(const Study& study, const RunResult& result, const RunSummary& summary) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-4s %10s %12s %10s %9s %14s\n", "#", "k [N/m]", "f_n [MHz]", "slip frac",
                "max x/l", "rms x' [m/s]");
  out += line;
  for (std::size_t i = 0; i < summary.asperities.size(); ++i) {
    const AsperitySummary& s = summary.asperities[i];
    std::snprintf(line, sizeof line, "%-4zu %10.4g %12.4f %10.3f %9.3f %14.4g%s\n", i + 1,
                  study.asperities[i].stiffness_n_per_m, s.natural_frequency_hz * 1e-6, s.slip_fraction, s.max_x_over_l,
                  s.rms_velocity_m_per_s, s.max_x_over_l >= 1.0 ? "   <- x reaches l" : "");
    out += line;
  }
  std::snprintf(line, sizeof line, "voltage: rms %.4g V, peak %.4g V; final charge %.4g C%s\n", summary.voltage_rms_v,
                summary.voltage_peak_v, summary.final_charge_c,
                result.valid ? "" : "  (circuit cut at the first x = l: run INVALID)");
  out += line;
  std::snprintf(line, sizeof line, "time: tribology %.3f s, circuit %.3f s, spectra %.3f s; %zu events\n",
                result.tribology_seconds, result.circuit_seconds, result.spectrum_seconds, result.events.size());
  out += line;
  return out;
}

}  // namespace stengmc
