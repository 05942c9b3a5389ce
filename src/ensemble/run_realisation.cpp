#include "ensemble/run_realisation.hpp"

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/random_stream.hpp"
#include "core/format.hpp"
#include "pipeline/study_realisation.hpp"
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

//! `base` with realisation r's [[ensemble.draw]] values set (re-read from its text, like a
//! sweep point); each value is recorded as the extra "draw:<parameter>".
Study with_draws(const StudyFile& base, std::uint64_t realisation, RealisationRecord& record) {
  std::vector<ParameterOverride> overrides = base.overrides;
  const auto& draws = base.ensemble->draws;
  for (std::size_t i = 0; i < draws.size(); ++i) {
    RandomEngine engine = random_stream(base.seed, realisation, StreamKind::draws, i);
    const double value = draws[i].draw(engine);
    overrides.push_back({draws[i].parameter, value});
    record.extras.push_back({"draw:" + draws[i].parameter, {value}});
  }
  try {
    return parse_study(base.text, base.file, std::nullopt, overrides);
  } catch (const InputError& e) {
    // The prior itself reaches values the study cannot take: every such draw would fail.
    throw InputError("realisation " + std::to_string(realisation) + ": a value drawn by [[ensemble.draw]] is refused: " + e.what());
  }
}

}  // namespace

RealisationRecord run_realisation(const StudyFile& base, std::uint64_t realisation, bool keep_traces,
                                  const WorkLimits& limits) {
  RealisationRecord record;
  record.realisation = realisation;
  try {
    const bool drawn = base.ensemble && !base.ensemble->draws.empty();
    const Study study = drawn ? study_for_realisation(with_draws(base, realisation, record), realisation)
                              : study_for_realisation(base, realisation);
    // Now that its asperities are drawn, the realisation's own work: over a limit, it is an
    // invalid realisation (the study's share of it was checked for every grid point first).
    const std::string exceeded = exceeded_limit(estimate_run(study, -1.0, false), limits);
    if (!exceeded.empty()) {
      record.valid = false;
      record.failure = std::string(WORK_LIMIT_FAILURE) + "with " + std::to_string(study.asperities.size()) +
                       " asperities the realisation " + exceeded;
      record.scalar(Scalar::summit_count) = static_cast<double>(study.population.height_m.size());
      record.scalar(Scalar::asperity_count) = static_cast<double>(study.asperities.size());
      return record;
    }
    const RunResult result = run_study(study, RunOptions{.show_progress = false, .limits = limits, .keep_traces = false});
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
      record.measured_voltage_v = result.measured_voltage_v;
    }
  } catch (const ModelError& e) {
    std::vector<RecordExtra> draws = std::move(record.extras);  // what the realisation drew, kept
    record = RealisationRecord{};
    record.extras = std::move(draws);
    record.realisation = realisation;
    record.valid = false;
    record.failure = e.what();
  } catch (const Error&) {
    throw;  // the study's (InputError) or the system's: every realisation would fail alike
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // A numerical library's own exception (a Boost root finder's "do not bracket") is this
    // realisation's failure: recorded, never the end of the ensemble.
    record = RealisationRecord{};
    record.realisation = realisation;
    record.valid = false;
    record.failure = std::string("unexpected failure (please report it with the study): ") + e.what();
  }
  return record;
}

}  // namespace stengmc
