#include "pipeline/run_study.hpp"

#include <algorithm>
#include <optional>
#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>
#include <system_error>
#include <thread>

#include "circuit/element_sums.hpp"
#include "circuit/netlist_circuit.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/imposed_drive.hpp"
#include "tribology/model1.hpp"
#include "tribology/model2.hpp"
#include "tribology/model2_integrator.hpp"
#include "tribology/model2_motion.hpp"
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

//! Says plainly when a Model 1 asperity never moved: A <= mu_s N / k (paper Eq. 1) and
//! nothing in its initial state made it slip either. Judged on the solved motion, so an
//! initial displacement or velocity that does make it slip is not misreported.
void note_model1_validity(const Study& study, RunResult& result) {
  if (study.model != ModelKind::model1) return;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    const Asperity& a = study.asperities[i];
    if (result.statistics[i].moved || model1_can_slip(study.model1, a)) continue;
    const double threshold = study.model1.friction.static_coefficient * a.normal_load_n / a.stiffness_n_per_m;
    result.notes.push_back(describe(a, i) + " never slips: the drive amplitude A = " +
                           micro(study.model1.drive_amplitude_m) + " um is not above mu_s N / k = " + micro(threshold) +
                           " um (paper Eq. 1), so x stays at its initial value and its element gives no signal");
  }
}

//! A solver that returns NaN or Inf is reported with the asperity, never written.
void check_finite(std::span<const double> x, std::span<const double> v, std::span<const double> friction,
                  const Asperity& a, std::size_t index, const TimeGrid& grid) {
  for (std::size_t j = 0; j < x.size(); ++j)
    if (!std::isfinite(x[j]) || !std::isfinite(v[j]) || (j < friction.size() && !std::isfinite(friction[j])))
      throw ModelError(describe(a, index) + ": the tribology produced a non-finite state at t = " + micro(grid.at(j)) +
                       " us; check the asperity's parameters for physically plausible values");
}

//! Slip fraction, largest x, rms velocity and the per-sample sliding flags.
AsperityStatistics statistics_of(const SlidingRule& rule, std::span<const double> x, std::span<const double> v,
                                 bool has_events) {
  AsperityStatistics s;
  s.sliding.resize(v.size());
  std::size_t sliding = 0;
  double sum_squares = 0.0;
  bool moved = has_events;
  for (std::size_t j = 0; j < v.size(); ++j) {
    const bool slides = rule.slides(v[j]);
    s.sliding[j] = slides;
    sliding += slides ? 1 : 0;
    sum_squares += v[j] * v[j];
    moved = moved || v[j] != 0.0;
  }
  s.moved = moved;
  if (!v.empty()) {
    s.slip_fraction = static_cast<double>(sliding) / static_cast<double>(v.size());
    s.rms_velocity_m_per_s = std::sqrt(sum_squares / static_cast<double>(v.size()));
  }
  s.max_x_m = x.empty() ? 0.0 : *std::max_element(x.begin(), x.end());
  return s;
}

//! Which of a run's per-asperity arrays must outlive the asperity's turn.
struct Keep {
  bool motion = false;    //!< the dense output (tests, files, and kinks the circuit evaluates)
  bool x = false, v = false, friction = false;  //!< the sample traces
  bool circuit_samples = false;  //!< the circuit input's samples, for the element currents
};

Keep what_to_keep(const Study& study, const RunOptions& options) {
  // A netlist load is solved by ngspice after the tribology, from the motions themselves.
  if (!options.keep_traces) return {.motion = study.netlist != nullptr};
  const OutputTraces& t = study.output.traces;
  const bool current_spectra = study.spectrum && study.spectrum->element_currents;
  return {options.keep_motions || study.netlist != nullptr, t.x, t.v, t.friction, t.current || t.charge || current_spectra};
}

//! Asperity i's tribology: its trajectory (the motion, Model 2's events and step counts, the
//! traces `keep` asks for), its samples on the grid (with midpoints) and its statistics.
//! Touches nothing shared: asperities are solved side by side (RunOptions::threads).
void solve_asperity(const Study& study, std::size_t i, const TimeGrid& grid, std::span<const double> times, double t_end,
                    const Keep& keep, const SlidingRule& rule, Trajectory& t, MotionSamples& samples,
                    AsperityStatistics& statistics) {
  const Asperity& a = study.asperities[i];
  if (study.model == ModelKind::model1) {
    t = solve_model1(a, study.model1, grid);
    check_finite(t.x_m, t.v_m_per_s, t.friction_n, a, i, grid);
    t.motion->sample(times, true, samples);
    statistics = statistics_of(rule, t.x_m, t.v_m_per_s, !t.events.empty());
    return;
  }
  // The counterface's modulation of asperity i: its own stream (seed, realisation, i).
  const CounterfaceStream stream{study.seed, study.realisation, i};
  Model2Solution solution = solve_model2_motion(a, study.model2, t_end, stream);
  t.solver_steps = solution.accepted_steps;
  t.rejected_steps = solution.rejected_steps;
  solution.motion->sample(times, true, samples);
  t.events = std::move(solution.events);
  t.motion = std::move(solution.motion);
  if (keep.friction) model2_friction_trace(a, study.model2, times, samples.v_m_per_s, t.friction_n, stream);
  check_finite(samples.x_m, samples.v_m_per_s, t.friction_n, a, i, grid);
  statistics = statistics_of(rule, samples.x_m, samples.v_m_per_s, !t.events.empty());
  if (keep.x) t.x_m = samples.x_m;
  if (keep.v) t.v_m_per_s = samples.v_m_per_s;
}

//! Solves asperities first, first + 1, ... (one per slot) side by side, one thread each; an
//! asperity's error is kept in its slot, to be raised in the asperities' order.
void solve_block(const Study& study, std::size_t first, std::span<MotionSamples> slots,
                 std::span<std::exception_ptr> errors, const TimeGrid& grid, std::span<const double> times, double t_end,
                 const Keep& keep, const SlidingRule& rule, RunResult& result) {
  auto solve = [&](std::size_t s) {
    errors[s] = nullptr;
    try {
      solve_asperity(study, first + s, grid, times, t_end, keep, rule, result.trajectories[first + s], slots[s],
                     result.statistics[first + s]);
    } catch (...) {
      errors[s] = std::current_exception();
    }
  };
  // A thread the system will not start leaves its asperities to this one.
  std::vector<std::thread> helpers;
  std::size_t started = 1;
  try {
    for (; started < slots.size(); ++started) helpers.emplace_back(solve, started);
  } catch (const std::system_error&) {
  }
  solve(0);
  for (std::size_t s = started; s < slots.size(); ++s) solve(s);
  for (std::thread& helper : helpers) helper.join();
}

//! Finds the first time this element's displacement reaches its l; applies the policy.
//! Returns the exit time (infinity when none).
double domain_exit(const Study& study, std::size_t i, const Motion& input, std::span<const double> times,
                   const MotionSamples& samples, std::span<const double> sampled_x, RunResult& result) {
  const Asperity& a = study.asperities[i];
  std::optional<double> exit;
  try {
    // Model 1 keeps its own samples (so its outputs stay what they were); Model 2 reads
    // the velocities from the samples instead of evaluating them again.
    exit = sampled_x.empty() ? first_domain_exit(input, times, samples, a.element.length_m)
                             : first_domain_exit(input, times, sampled_x, a.element.length_m);
  } catch (const ModelError& e) {
    throw ModelError(describe(a, i) + ": " + e.what());
  }
  if (!exit) return INFINITY;
  result.events.push_back({*exit, i, EventKind::domain_exit});
  const std::string what = describe(a, i) + ": x reaches l = " + micro(a.element.length_m) + " um at t = " +
                           micro(*exit) + " us; the S-TENG element formulas (MODEL.md §2) hold only for x < l";
  if (study.domain_policy == DomainPolicy::error)
    throw ModelError(study.file + ": " + what +
                     ". Lengthen the element (length_m) or set [domain] policy = \"flag\" to keep the valid part.");
  result.notes.push_back(what + "; the circuit stops there and the run is marked invalid");
  return *exit;
}

//! Spectra of the valid part of the run; an asperity is expected to show its line at its
//! damped natural frequency when it slides for at least min_slip_fraction of the same
//! interval the spectrum analyses.
SpectralResult analyse_run_spectra(const Study& study, const RunResult& result) {
  const SpectrumSettings& settings = *study.spectrum;
  SpectralInput input;
  input.times_s = std::span<const double>(result.times_s.data(), result.circuit_samples);
  input.voltage_v = result.measured_voltage_v.empty() ? result.circuit.voltage_v : result.measured_voltage_v;
  input.currents_a = result.circuit.current_a.empty() ? nullptr : &result.circuit.current_a;
  try {
    const AnalysisRange range = analysis_range(input.times_s, settings);
    for (std::size_t i = 0; i < study.asperities.size(); ++i) {
      const Asperity& a = study.asperities[i];
      const double damping = study.model == ModelKind::model2 ? study.model2.damping_n_s_per_m : 0.0;
      input.expected_frequency_hz.push_back(damped_natural_frequency_hz(a.stiffness_n_per_m, a.mass_kg, damping));
      const std::vector<bool>& sliding = result.statistics[i].sliding;
      const std::size_t first = std::min(range.first_sample, sliding.size());
      const std::size_t count = std::min(range.samples, sliding.size() - first);
      const auto begin = sliding.begin() + static_cast<std::ptrdiff_t>(first);
      const auto slides = static_cast<double>(std::count(begin, begin + static_cast<std::ptrdiff_t>(count), true));
      const double fraction = count > 0 ? slides / static_cast<double>(count) : 0.0;
      input.sliding.push_back(fraction >= settings.min_slip_fraction);
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
  // The white part keeps the stream it always had; the coloured part has a sub-stream.
  RandomEngine white = random_stream(study.seed, study.realisation, StreamKind::noise);
  RandomEngine coloured = random_stream(study.seed, study.realisation, StreamKind::noise, 1);
  const AnalysisRange range =
      analysis_range(std::span<const double>(result.times_s.data(), result.circuit_samples), *study.spectrum);
  NoisyVoltage noisy = measure_voltage(result.circuit.voltage_v, range.first_sample, range.samples, study.sample_rate_hz,
                                       *study.noise, white, coloured);
  result.measured_voltage_v = std::move(noisy.voltage_v);
  result.noise_sigma_v = noisy.sigma_v;
}

}  // namespace

RunResult run_study(const Study& study, const RunOptions& options) {
  // Before any allocation: one absurd value (a drive at 1e300 Hz) must not start a run that
  // cannot finish or fit. Commands check the same estimate, with their output, earlier.
  check_work(estimate_run(study, -1.0, false, options.keep_traces && options.keep_motions, options.threads),
             options.limits, study.file + ": the run");
  RunResult result;
  const TimeGrid grid = study.grid();
  result.times_s = grid.times();
  const std::span<const double> times(result.times_s);
  const std::size_t n = study.asperities.size();
  // The prior checks of the population; Model 1's "never slips" is judged on the solved
  // motion below instead, which also sees the initial state.
  const ModelScope scope{study.model == ModelKind::model1, study.model == ModelKind::model2};
  result.validity = assess_validity(study.population, study.model1, study.model2, {}, scope);
  result.notes = result.validity.contact_warnings;
  if (study.model == ModelKind::model2)
    result.notes.insert(result.notes.end(), result.validity.model2_warnings.begin(), result.validity.model2_warnings.end());

  // Each asperity in turn: tribology, its samples, the domain check, its statistics, and
  // its share of the circuit's sums; then everything the study does not keep is dropped.
  const Keep keep = what_to_keep(study, options);
  const SlidingRule rule = SlidingRule::of(study);
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;
  ElementSums sums(times);
  std::vector<MotionSamples> circuit_samples(keep.circuit_samples ? n : 0);
  MotionSamples drive_samples;
  // Model 2's asperities are solved `threads` at a time, each into a slot, then taken in
  // their order: the circuit's sums see them in the same order whatever the count, so the
  // run is the same bit for bit. Model 1 (cheap) takes them one by one.
  const std::size_t width =
      study.model == ModelKind::model2 ? std::clamp<std::size_t>(options.threads, 1, std::max<std::size_t>(n, 1)) : 1;
  std::vector<MotionSamples> slots(width);
  std::vector<std::exception_ptr> errors(width);
  double first_exit = INFINITY;
  result.trajectories.resize(n);
  result.statistics.resize(n);
  const auto tribology_start = Clock::now();
  {
    std::optional<Progress> progress;
    if (options.show_progress) progress.emplace("tribology", n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t slot = i % width;
      if (slot == 0) {
        const std::size_t count = std::min(width, n - i);
        solve_block(study, i, std::span<MotionSamples>(slots).first(count),
                    std::span<std::exception_ptr>(errors).first(count), grid, times, t_end, keep, rule, result);
      }
      // An error is raised where the asperities' order meets it, as if they ran one by one.
      if (errors[slot]) std::rethrow_exception(errors[slot]);
      const Asperity& a = study.asperities[i];
      Trajectory& t = result.trajectories[i];
      const MotionSamples& samples = slots[slot];
      for (Event e : t.events) {
        e.asperity = i;
        result.events.push_back(e);
      }
      // What drives the element: the actual x(t), or the imposed x0(t) (Fig. 3c).
      const Motion* input = t.motion.get();
      const MotionSamples* input_samples = &samples;
      std::vector<double> drive_x;
      if (study.circuit_input == CircuitInput::imposed) {
        result.drives.push_back(std::make_unique<ImposedDriveMotion>(study.model1, a));
        input = result.drives.back().get();
        input->sample(times, true, drive_samples);
        input_samples = &drive_samples;
        drive_x = drive_samples.x_m;
      }
      const std::span<const double> own_x = study.model == ModelKind::model1
          ? std::span<const double>(study.circuit_input == CircuitInput::imposed ? drive_x : t.x_m)
          : std::span<const double>();
      first_exit = std::min(first_exit, domain_exit(study, i, *input, times, *input_samples, own_x, result));
      const bool circuit_needs_motion = sums.add(a.element, *input_samples, *input);
      // The element's current and charge read x, x' and its left limits, not the midpoints.
      if (keep.circuit_samples) {
        circuit_samples[i].x_m = input_samples->x_m;
        circuit_samples[i].v_m_per_s = input_samples->v_m_per_s;
        circuit_samples[i].v_left_m_per_s = input_samples->v_left_m_per_s;
      }
      if (study.model == ModelKind::model1 && !keep.x) t.x_m = {};
      if (study.model == ModelKind::model1 && !keep.v) t.v_m_per_s = {};
      if (study.model == ModelKind::model1 && !keep.friction) t.friction_n = {};
      // The circuit evaluates a motion itself only inside intervals holding its cuts.
      if (!keep.motion && !(circuit_needs_motion && input == t.motion.get())) t.motion.reset();
      if (progress) progress->advance();
    }
  }
  result.tribology_seconds = seconds_since(tribology_start);
  note_model1_validity(study, result);
  result.valid = std::isinf(first_exit);
  result.circuit_samples = result.valid ? result.times_s.size()
      : static_cast<std::size_t>(std::lower_bound(result.times_s.begin(), result.times_s.end(), first_exit) -
                                 result.times_s.begin());
  std::stable_sort(result.events.begin(), result.events.end(),
                   [](const Event& a, const Event& b) { return a.time_s < b.time_s; });

  const auto circuit_start = Clock::now();
  if (n == 0) {
    // Nothing slides (a surface of no summits): no source drives the load, V = Q = 0.
    result.circuit.voltage_v.assign(result.circuit_samples, 0.0);
    result.circuit.charge_c.assign(result.circuit_samples, 0.0);
  } else if (study.netlist) {
    std::vector<const Motion*> inputs;
    std::vector<StengElement> elements;
    for (std::size_t i = 0; i < n; ++i) {
      inputs.push_back(study.circuit_input == CircuitInput::imposed ? result.drives[i].get()
                                                                     : result.trajectories[i].motion.get());
      elements.push_back(study.asperities[i].element);
    }
    std::vector<std::string> probe_vectors;
    for (const NetlistProbe& probe : study.probes) probe_vectors.push_back(probe.vector);
    result.circuit = solve_netlist_circuit(elements, inputs, times.first(result.circuit_samples), *study.netlist,
                                           keep.circuit_samples, probe_vectors, ngspice_budget(study, options.limits),
                                           options.show_progress)
                         .circuit;
  } else {
    std::optional<Progress> progress;
    if (options.show_progress) progress.emplace("circuit", result.circuit_samples);
    SummedCircuit circuit = solve_summed_circuit(sums, result.circuit_samples, study.circuit, progress ? &*progress : nullptr);
    if (keep.circuit_samples) {
      result.circuit.current_a.resize(n);
      result.circuit.element_charge_c.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        element_traces(study.asperities[i].element, circuit_samples[i], circuit, times, i + 1, result.circuit.current_a[i],
                       result.circuit.element_charge_c[i]);
    }
    result.circuit.voltage_v = std::move(circuit.voltage_v);
    result.circuit.charge_c = std::move(circuit.charge_c);
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
