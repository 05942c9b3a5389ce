#include "ensemble/run_realisation.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/format.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/run_summary.hpp"
#include "tribology/events.hpp"

namespace stengmc {

namespace {

void fill_scalars(const Study& study, const RunResult& result, const RunSummary& summary, RealisationRecord& r) {
  const Population& p = study.population;
  r.scalar(Scalar::summit_count) = static_cast<double>(p.height_m.size());
  r.scalar(Scalar::asperity_count) = static_cast<double>(study.asperities.size());
  r.scalar(Scalar::contact_density) = result.validity.contact_density;
  r.scalar(Scalar::load_redistribution) = result.validity.load_redistribution;
  r.scalar(Scalar::voltage_rms_v) = summary.voltage_rms_v;
  r.scalar(Scalar::voltage_peak_v) = summary.voltage_peak_v;
  r.scalar(Scalar::final_charge_c) = summary.final_charge_c;
  r.scalar(Scalar::mean_charging_rate_a) = summary.final_charge_c / study.duration_s;
  r.scalar(Scalar::cannot_slip_count) = static_cast<double>(result.validity.cannot_slip_count);
  r.scalar(Scalar::near_length_count) = static_cast<double>(result.validity.near_length_count);
  r.scalar(Scalar::independence_holds) = result.validity.independence_holds ? 1.0 : 0.0;
  if (!result.spectra) return;
  const SpectralResult& s = *result.spectra;
  r.scalar(Scalar::n_sliding) = static_cast<double>(s.fft.n_sliding);
  r.scalar(Scalar::fft_detected) = static_cast<double>(s.fft.n_detected);
  r.scalar(Scalar::fft_identifiable) = static_cast<double>(s.fft.n_identifiable);
  r.scalar(Scalar::fft_ratio) = s.fft.ratio;
  if (s.high_resolution) {
    r.scalar(Scalar::hr_detected) = static_cast<double>(s.high_resolution->n_detected);
    r.scalar(Scalar::hr_identifiable) = static_cast<double>(s.high_resolution->n_identifiable);
    r.scalar(Scalar::hr_ratio) = s.high_resolution->ratio;
  }
}

void fill_asperities(const Study& study, const RunResult& result, const RunSummary& summary, RealisationRecord& r) {
  const std::size_t n = study.asperities.size();
  for (auto& column : r.asperities) column.assign(n, 0.0);
  auto col = [&](AsperityColumn c) -> std::vector<double>& { return r.asperities[static_cast<std::size_t>(c)]; };
  for (std::size_t i = 0; i < n; ++i) {
    const Asperity& a = study.asperities[i];
    col(AsperityColumn::stiffness_n_per_m)[i] = a.stiffness_n_per_m;
    col(AsperityColumn::normal_load_n)[i] = a.normal_load_n;
    col(AsperityColumn::mass_kg)[i] = a.mass_kg;
    col(AsperityColumn::natural_frequency_hz)[i] = summary.asperities[i].natural_frequency_hz;
    col(AsperityColumn::slip_fraction)[i] = summary.asperities[i].slip_fraction;
    col(AsperityColumn::max_x_over_l)[i] = summary.asperities[i].max_x_over_l;
    col(AsperityColumn::rms_velocity_m_per_s)[i] = summary.asperities[i].rms_velocity_m_per_s;
    if (!result.spectra) continue;
    const Identifiability& fft = result.spectra->fft;
    col(AsperityColumn::fft_identified)[i] = fft.identified[i] ? 1.0 : 0.0;
    col(AsperityColumn::fft_frequency_error_hz)[i] = fft.frequency_error_hz[i];
    if (const auto& hr = result.spectra->high_resolution) {
      col(AsperityColumn::hr_identified)[i] = hr->identified[i] ? 1.0 : 0.0;
      col(AsperityColumn::hr_frequency_error_hz)[i] = hr->frequency_error_hz[i];
    }
  }
}

//! Why a flagged run is invalid: its first domain exit.
std::string flagged_failure(const Study& study, const RunResult& result) {
  for (const Event& e : result.events)
    if (e.kind == EventKind::domain_exit)
      return "x reached l (asperity " + std::to_string(e.asperity + 1) + ", k = " +
             format_number(study.asperities[e.asperity].stiffness_n_per_m) + " N/m, at t = " + format_number(e.time_s) +
             " s)";
  return "the run was marked invalid";
}

}  // namespace

RealisationRecord run_realisation(const Study& base, std::uint64_t realisation, bool keep_traces) {
  RealisationRecord record;
  record.realisation = realisation;
  try {
    const Study study = study_for_realisation(base, realisation);
    const RunResult result = run_study(study, RunOptions{.show_progress = false, .keep_traces = false});
    const RunSummary summary = summarise(study, result);
    fill_scalars(study, result, summary, record);
    fill_asperities(study, result, summary, record);
    if (!result.valid) {
      record.valid = false;
      record.failure = flagged_failure(study, result);
    }
    if (keep_traces) {
      record.time_s.assign(result.times_s.begin(), result.times_s.begin() + static_cast<long>(result.circuit_samples));
      record.voltage_v = result.circuit.voltage_v;
      record.charge_c = result.circuit.charge_c;
    }
  } catch (const ModelError& e) {
    record = RealisationRecord{};
    record.realisation = realisation;
    record.valid = false;
    record.failure = e.what();
  }
  return record;
}

}  // namespace stengmc
