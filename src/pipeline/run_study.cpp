#include "pipeline/run_study.hpp"

#include <algorithm>
#include <optional>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/imposed_drive.hpp"
#include "tribology/model1.hpp"
#include "tribology/model2.hpp"
#include "pipeline/measurement_noise.hpp"
#include "pipeline/slip_fraction.hpp"

namespace stengmc {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string micro(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value * 1e6;
  return out.str();
}

std::string describe(const Asperity& a, std::size_t index) {
  std::ostringstream out;
  out << "asperity " << index + 1 << " (k = " << a.stiffness_n_per_m << " N/m)";
  return out.str();
}

Trajectory solve_one(const Study& study, const Asperity& asperity, const TimeGrid& grid) {
  return study.model == ModelKind::model1 ? solve_model1(asperity, study.model1, grid)
                                          : solve_model2(asperity, study.model2, grid);
}

//! Says plainly when a Model 1 asperity never moved: A <= mu_s N / k (paper Eq. 1) and
//! nothing in its initial state made it slip either. Judged on the solved motion, so an
//! initial displacement or velocity that does make it slip is not misreported.
void note_model1_validity(const Study& study, RunResult& result) {
  if (study.model != ModelKind::model1) return;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    const Asperity& a = study.asperities[i];
    const Trajectory& t = result.trajectories[i];
    const bool moved = !t.events.empty() || std::any_of(t.v_m_per_s.begin(), t.v_m_per_s.end(), [](double v) { return v != 0.0; });
    if (moved || model1_can_slip(study.model1, a)) continue;
    const double threshold = study.model1.friction.static_coefficient * a.normal_load_n / a.stiffness_n_per_m;
    result.notes.push_back(describe(a, i) + " never slips: the drive amplitude A = " +
                           micro(study.model1.drive_amplitude_m) + " um is not above mu_s N / k = " + micro(threshold) +
                           " um (paper Eq. 1), so x stays at its initial value and its element gives no signal");
  }
}

//! A solver that returns NaN or Inf is reported with the asperity, never written.
void check_finite(const Trajectory& trajectory, const Asperity& a, std::size_t index, const TimeGrid& grid) {
  for (std::size_t j = 0; j < trajectory.x_m.size(); ++j)
    if (!std::isfinite(trajectory.x_m[j]) || !std::isfinite(trajectory.v_m_per_s[j]) || !std::isfinite(trajectory.friction_n[j]))
      throw ModelError(describe(a, index) + ": the tribology produced a non-finite state at t = " + micro(grid.at(j)) +
                       " us; check the asperity's parameters for physically plausible values");
}

//! Finds the first time any element's displacement reaches its l; applies the policy.
std::size_t valid_prefix(const Study& study, const std::vector<const Motion*>& inputs,
                         const std::vector<std::vector<double>>& input_samples, RunResult& result) {
  double first_exit = INFINITY;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const Asperity& a = study.asperities[i];
    std::optional<double> exit;
    try {
      exit = first_domain_exit(*inputs[i], result.times_s, input_samples[i], a.element.length_m);
    } catch (const ModelError& e) {
      throw ModelError(describe(a, i) + ": " + e.what());
    }
    if (!exit) continue;
    result.events.push_back({*exit, i, EventKind::domain_exit});
    const std::string what = describe(a, i) + ": x reaches l = " + micro(a.element.length_m) + " um at t = " +
                             micro(*exit) + " us; the S-TENG element formulas (MODEL.md §2) hold only for x < l";
    if (study.domain_policy == DomainPolicy::error)
      throw ModelError(study.file + ": " + what +
                       ". Lengthen the element (length_m) or set [domain] policy = \"flag\" to keep the valid part.");
    result.notes.push_back(what + "; the circuit stops there and the run is marked invalid");
    first_exit = std::min(first_exit, *exit);
  }
  if (std::isinf(first_exit)) return result.times_s.size();
  result.valid = false;
  return static_cast<std::size_t>(
      std::lower_bound(result.times_s.begin(), result.times_s.end(), first_exit) - result.times_s.begin());
}

//! Spectra of the valid part of the run; an asperity is expected to show its line at its
//! damped natural frequency when it slides for at least min_slip_fraction of the same
//! interval the spectrum analyses.
SpectralResult analyse_run_spectra(const Study& study, const RunResult& result) {
  const SpectrumSettings& settings = *study.spectrum;
  SpectralInput input;
  input.times_s = std::span<const double>(result.times_s.data(), result.circuit_samples);
  input.voltage_v = result.measured_voltage_v.empty() ? result.circuit.voltage_v : result.measured_voltage_v;
  input.currents_a = &result.circuit.current_a;
  try {
    const AnalysisRange range = analysis_range(input.times_s, settings);
    for (std::size_t i = 0; i < study.asperities.size(); ++i) {
      const Asperity& a = study.asperities[i];
      const double damping = study.model == ModelKind::model2 ? study.model2.damping_n_s_per_m : 0.0;
      input.expected_frequency_hz.push_back(damped_natural_frequency_hz(a.stiffness_n_per_m, a.mass_kg, damping));
      const auto& v = result.trajectories[i].v_m_per_s;
      const std::size_t first = std::min(range.first_sample, v.size());
      const std::span<const double> interval(v.data() + first, std::min(range.samples, v.size() - first));
      input.sliding.push_back(slip_fraction(study, interval) >= settings.min_slip_fraction);
    }
    return analyse_spectra(input, settings);
  } catch (const InputError& e) {
    throw InputError(study.file + ": [spectrum]: " + e.what());
  }
}

//! V plus the study's [noise], what the spectra analyse. The noise has its own stream of
//! (seed, realisation): a realisation gets the same noise in a single run and in an
//! ensemble, and no other quantity's draws move.
void add_measurement_noise(const Study& study, RunResult& result) {
  if (!study.noise) return;
  RandomEngine engine = random_stream(study.seed, study.realisation, StreamKind::noise);
  const AnalysisRange range =
      analysis_range(std::span<const double>(result.times_s.data(), result.circuit_samples), *study.spectrum);
  NoisyVoltage noisy = add_white_noise(result.circuit.voltage_v, range.first_sample, range.samples, study.noise->snr_db, engine);
  result.measured_voltage_v = std::move(noisy.voltage_v);
  result.noise_sigma_v = noisy.sigma_v;
}

}  // namespace

RunResult run_study(const Study& study, const RunOptions& options) {
  // Before any allocation: one absurd value (a drive at 1e300 Hz) must not start a run that
  // cannot finish or fit. Commands check the same estimate, with their output, earlier.
  check_work(estimate_run(study, -1.0, false), options.limits, study.file + ": the run");
  RunResult result;
  const TimeGrid grid = study.grid();
  result.times_s = grid.times();
  const std::size_t n = study.asperities.size();
  // The prior checks of the population; Model 1's "never slips" is judged on the solved
  // motion below instead, which also sees the initial state.
  const ModelScope scope{study.model == ModelKind::model1, study.model == ModelKind::model2};
  result.validity = assess_validity(study.population, study.model1, study.model2, {}, scope);
  result.notes = result.validity.contact_warnings;
  if (study.model == ModelKind::model2)
    result.notes.insert(result.notes.end(), result.validity.model2_warnings.begin(), result.validity.model2_warnings.end());

  const auto tribology_start = Clock::now();
  {
    std::optional<Progress> progress;
    if (options.show_progress) progress.emplace("tribology", n);
    for (std::size_t i = 0; i < n; ++i) {
      result.trajectories.push_back(solve_one(study, study.asperities[i], grid));
      check_finite(result.trajectories.back(), study.asperities[i], i, grid);
      for (Event e : result.trajectories.back().events) {
        e.asperity = i;
        result.events.push_back(e);
      }
      if (progress) progress->advance();
    }
  }
  result.tribology_seconds = seconds_since(tribology_start);
  note_model1_validity(study, result);

  // What drives the elements: the actual x(t), or the imposed x0(t) (Fig. 3c).
  std::vector<const Motion*> inputs;
  std::vector<std::vector<double>> input_samples;
  for (std::size_t i = 0; i < n; ++i) {
    if (study.circuit_input == CircuitInput::imposed) {
      result.drives.push_back(std::make_unique<ImposedDriveMotion>(study.model1, study.asperities[i]));
      std::vector<double> x0(grid.count);
      for (std::size_t j = 0; j < grid.count; ++j) x0[j] = result.drives.back()->at(result.times_s[j]).x_m;
      inputs.push_back(result.drives.back().get());
      input_samples.push_back(std::move(x0));
    } else {
      inputs.push_back(result.trajectories[i].motion.get());
      input_samples.push_back(result.trajectories[i].x_m);
    }
  }
  result.circuit_samples = valid_prefix(study, inputs, input_samples, result);
  std::stable_sort(result.events.begin(), result.events.end(),
                   [](const Event& a, const Event& b) { return a.time_s < b.time_s; });

  const auto circuit_start = Clock::now();
  std::vector<StengElement> elements;
  for (const Asperity& a : study.asperities) elements.push_back(a.element);
  {
    std::optional<Progress> progress;
    if (options.show_progress) progress.emplace("circuit", result.circuit_samples);
    result.circuit = solve_circuit(elements, inputs, std::span<const double>(result.times_s.data(), result.circuit_samples),
                                   study.circuit, progress ? &*progress : nullptr);
  }
  result.circuit_seconds = seconds_since(circuit_start);

  if (study.spectrum) {
    const auto spectrum_start = Clock::now();
    try {
      add_measurement_noise(study, result);
      result.spectra = analyse_run_spectra(study, result);
    } catch (const InputError& e) {
      // A run cut at the first x = l may leave too short an interval: that is this run's
      // fate, not a fault of the study, so it is said and the run stays (invalid).
      if (result.valid) throw;
      result.notes.push_back(std::string("no spectra: ") + e.what());
    }
    result.spectrum_seconds = seconds_since(spectrum_start);
  }
  return result;
}

}  // namespace stengmc
