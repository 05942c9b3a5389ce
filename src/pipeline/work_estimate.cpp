#include "pipeline/work_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "circuit/netlist_circuit.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "tribology/counterface.hpp"

namespace stengmc {

namespace {

// The Model 2 integrator's own step budget per asperity (tribology/model2_integrator.cpp):
// it stops with a ModelError there, so no estimate needs to go beyond it.
constexpr double MODEL2_MAX_STEPS = 5e7;

double log2_at_least_1(double n) { return std::max(1.0, std::log2(std::max(n, 2.0))); }

std::string count(double n) { return format_number(std::round(n)); }

//! The highest natural frequency of the run's asperities [Hz]; 0 when they are not drawn
//! yet, so that an estimate for "at least n asperities" stays a lower bound of what any
//! realisation costs (an ensemble refuses up front only what none could do).
double fastest_natural_frequency_hz(const Study& study, bool asperities_known) {
  if (!asperities_known) return 0.0;
  double highest = 0.0;
  for (const Asperity& a : study.asperities)
    highest = std::max(highest, std::sqrt(a.stiffness_n_per_m / a.mass_kg) / (2.0 * PI));
  return highest;
}

//! The study's `[output] traces` as written in it: ["x", "v", ...] (x0 for Model 1 only).
std::vector<std::string> traces_kept(const Study& study) {
  const OutputTraces& t = study.output.traces;
  std::vector<std::string> names;
  for (const auto& [kept, name] : {std::pair{t.x, "x"}, {t.v, "v"}, {t.friction, "friction"}, {t.current, "current"},
                                   {t.charge, "charge"}, {t.x0 && study.model == ModelKind::model1, "x0"}})
    if (kept) names.emplace_back(name);
  return names;
}

//! The traces a `run` keeps and writes: each n x M in memory and in the file being written,
//! and the circuit input the element currents and charges are computed from.
void add_traces(const Study& study, double n, double samples, WorkEstimate& e) {
  const std::vector<std::string> names = traces_kept(study);
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "\"" : ", \"") + name + "\"";
  const auto traces = static_cast<double>(names.size());
  const OutputTraces& t = study.output.traces;
  const double current_input = t.current || t.charge ? CURRENT_INPUT_BYTES_PER_SAMPLE : 0.0;
  e.add_memory("[output] traces = [" + list + "]: " + count(traces) + " traces of " + count(n) + " asperities x " +
                   count(samples) + " samples, kept and written",
               n * samples * (traces * (TRACE_BYTES_PER_SAMPLE + FILE_BYTES_PER_VALUE) + current_input),
               "list fewer in [output] traces (traces = [] keeps V and Q only) or shorten duration_s");
  e.add_memory("run file: V, Q and times of " + count(samples) + " samples", 3.0 * samples * FILE_BYTES_PER_VALUE);
}

void add_tribology(const Study& study, double n, double samples, double natural_hz, bool all_motions,
                   double at_once, WorkEstimate& e) {
  const double duration = study.duration_s;
  if (study.model == ModelKind::model1) {
    const double drive_hz = study.model1.drive_angular_frequency_rad_per_s / (2.0 * PI);
    const double fastest = std::max(drive_hz, natural_hz);
    e.events = n * (EVENTS_PER_PERIOD * duration * fastest + 4.0);
    e.add_memory(std::string("~") + count(e.events) + " stick/slip events (" + count(n) + " asperities, " + format_number(duration) +
                     " s at up to " + format_number(fastest) + " Hz)",
                 e.events * BYTES_PER_EVENT);
    if (study.model1.solver == Model1Solver::exact) {
      e.add_steps("Model 1 slip-end scan: " + count(n) + " asperities x " + format_number(duration) + " s x " +
                      format_number(MODEL1_SCAN_STEPS_PER_PERIOD) + " per period of " + format_number(fastest) + " Hz",
                  n * MODEL1_SCAN_STEPS_PER_PERIOD * duration * fastest + e.events * STEPS_PER_EVENT);
    } else {
      e.add_steps("Euler-Cromer: " + count(n) + " asperities x " + count(samples) + " samples x " +
                      std::to_string(study.model1.euler_cromer_substeps) + " substeps",
                  n * samples * static_cast<double>(study.model1.euler_cromer_substeps));
    }
    return;
  }
  const double periods = duration * natural_hz;
  const double per_asperity =
      std::min(MODEL2_MAX_STEPS, std::max(MODEL2_MIN_STEPS, periods * MODEL2_STEPS_PER_PERIOD *
                                                                 std::pow(1e-8 / study.model2.relative_tolerance, 0.25)));
  double per_asperity_steps = per_asperity;
  // A modulated friction (docs/model.md §1.4) takes at least one step per node of eps's grid.
  if (study.model2.counterface.active() && natural_hz > 0.0)
    per_asperity_steps = std::min(MODEL2_MAX_STEPS,
        std::max(per_asperity, duration / modulation_step_s(correlation_time_s(study.model2.counterface,
                                                                               study.model2.belt_velocity_m_per_s),
                                                            2.0 * PI * natural_hz)));
  e.events = n * (EVENTS_PER_PERIOD * periods + 4.0);
  e.add_steps("Model 2 (RODAS4): " + count(n) + " asperities x ~" + count(per_asperity_steps) + " steps",
              n * per_asperity_steps);
  // Every motion kept, or those of the asperities in turn (the fastest one's steps bound
  // each), with their samples.
  const double in_turn = std::min(n, std::max(1.0, at_once));
  const double bytes_per_step =
      study.model2.counterface.active() ? MODEL2_BYTES_PER_RESERVED_STEP : MODEL2_BYTES_PER_STEP;
  if (all_motions)
    e.add_memory("Model 2 dense output: " + count(n) + " asperities x ~" + count(per_asperity_steps) + " steps",
                 n * per_asperity_steps * bytes_per_step);
  else
    e.add_memory("Model 2 dense output of the " + count(in_turn) + " asperities in turn: ~" + count(per_asperity_steps) +
                     " steps each",
                 in_turn * per_asperity_steps * bytes_per_step);
  if (in_turn > 1.0)
    e.add_memory("samples of the " + count(in_turn) + " asperities in turn", (in_turn - 1.0) * samples * SAMPLES_BYTES_PER_SAMPLE);
  e.add_memory(std::string("~") + count(e.events) + " stick/slip events", e.events * BYTES_PER_EVENT);
}

//! Spectra of a signal of `samples` samples and `currents` element currents; `file`: the
//! spectra are written to a file.
void add_spectra(double samples, double currents, const SpectrumSettings& s, WorkEstimate& e) {
  const double padded = samples * static_cast<double>(s.zero_pad_factor);
  const double signals = 1.0 + (s.element_currents ? currents : 0.0);
  e.add_steps("FFT spectra: " + count(signals) + " signals x " + count(padded) + " points",
              signals * padded * log2_at_least_1(padded));
  e.add_memory("FFT spectra: " + count(signals) + " signals x " + count(padded) + " points",
               FFT_BYTES_PER_POINT * padded + signals * (0.5 * padded + 1.0) * 8.0 * (1.0 + FILE_BYTES_PER_VALUE / 8.0));
  if (s.high_resolution) {
    const double analysed = std::min(samples, static_cast<double>(s.esprit.max_samples));
    const double lines = static_cast<double>(s.esprit.max_lines);
    e.add_memory("ESPRIT: " + count(analysed) + " samples x " + count(lines) + " lines",
                 analysed * lines * ESPRIT_BYTES_PER_SAMPLE_LINE);
    const double rows = std::min(analysed / 3.0, 256.0);
    e.add_steps("ESPRIT", rows * rows * rows + rows * analysed + analysed * lines * lines);
  }
  if (s.spectrogram && samples >= static_cast<double>(s.spectrogram->window_samples)) {
    const double window = static_cast<double>(s.spectrogram->window_samples);
    const double segments = std::floor((samples - window) / static_cast<double>(s.spectrogram->hop_samples)) + 1.0;
    e.add_memory("spectrogram: " + count(segments) + " segments x " + count(window / 2 + 1) + " bins",
                 segments * (window / 2.0 + 1.0) * (8.0 + FILE_BYTES_PER_VALUE));
    e.add_steps("spectrogram: " + count(segments) + " segments of " + count(window), segments * window * log2_at_least_1(window));
  }
}

//! Drawing one realisation: its summits and their interaction.
void add_sampling(const RandomSurface& surface, double realisations, WorkEstimate& e) {
  const double summits = summits_upper_bound(surface);
  e.add_memory(count(realisations) + " realisations x ~" + count(summits) + " summits", realisations * summits * BYTES_PER_SUMMIT);
  e.add_steps("drawing " + count(realisations) + " realisations x ~" + count(summits) + " summits",
              realisations * summits * 100.0);
  if (!surface.materials) return;
  // Spots within the 3 x 3 cells of side R_loc around each spot (surface/interaction.cpp).
  const double spots = summits;
  const double area = surface.nominal_area_m2;
  const double radius = surface.interaction.localisation_radius_m > 0.0
                            ? surface.interaction.localisation_radius_m
                            : surface.interaction.localisation_spacings * std::sqrt(area / std::max(spots, 1.0));
  const double neighbours = std::min(spots, 9.0 * radius * radius * spots / area + 1.0);
  e.interaction_pairs = spots * neighbours;
  const double iterations = surface.interaction_mode == InteractionMode::apply ? INTERACTION_ITERATIONS : 1.0;
  e.add_steps("spot interaction: " + count(realisations) + " realisations x ~" + count(e.interaction_pairs) + " pairs x " +
                  count(iterations) + " iterations (R_loc = " + format_number(radius) + " m)",
              realisations * e.interaction_pairs * iterations);
}

std::string describe(double amount, bool bytes) {
  return bytes ? format_number(amount / 1e9) + " GB" : format_number(amount) + " steps";
}

//! The largest part of `parts`.
const WorkPart* largest(const std::vector<WorkPart>& parts) {
  const auto it = std::max_element(parts.begin(), parts.end(),
                                   [](const WorkPart& a, const WorkPart& b) { return a.amount < b.amount; });
  return it == parts.end() ? nullptr : &*it;
}

}  // namespace

void WorkEstimate::add_memory(std::string what, double bytes, std::string remedy) {
  memory_bytes += bytes;
  memory.push_back({std::move(what), bytes, std::move(remedy)});
}

void WorkEstimate::add_steps(std::string what, double count) {
  steps += count;
  work.push_back({std::move(what), count, {}});
}

double summits_upper_bound(const RandomSurface& surface) {
  const double mean = surface.mean_summit_count();
  return surface.count_rule == CountRule::poisson ? mean + 6.0 * std::sqrt(mean) : mean;
}

namespace {

//! ngspice on the netlist: every device at every time step, every vector at every step.
void add_ngspice(const NetlistLoad& load, double n, double samples, WorkEstimate& e) {
  const double devices = netlist_circuit_devices(static_cast<std::size_t>(n), load);
  const double steps = netlist_circuit_steps(samples);
  e.add_steps("circuit (ngspice): " + count(devices) + " devices x " + count(steps) + " time steps",
              devices * steps * NGSPICE_STEPS_PER_DEVICE_STEP);
  e.add_memory("circuit (ngspice): " + count(devices) + " devices", devices * NGSPICE_BYTES_PER_DEVICE);
  const double vectors = 3.0 + n;  // time, V, the port current and, at most, each element's current
  e.add_memory("circuit (ngspice): " + count(vectors) + " vectors x " + count(steps) + " time steps",
               vectors * steps * NGSPICE_BYTES_PER_VALUE);
}

}  // namespace

ChildBudget ngspice_budget(const Study& study, const WorkLimits& limits) {
  ChildBudget budget;
  budget.memory_bytes = limits.memory_bytes;
  double steps = 0.0;
  if (study.netlist) {
    const double samples = std::round(study.duration_s * study.sample_rate_hz) + 1.0;
    steps = netlist_circuit_devices(study.asperities.size(), *study.netlist) * netlist_circuit_steps(samples) *
            NGSPICE_STEPS_PER_DEVICE_STEP;
  }
  budget.cpu_seconds = std::max(NGSPICE_MIN_CPU_SECONDS, NGSPICE_TIME_SAFETY * steps * 1e-7);
  budget.wall_seconds = 3.0 * budget.cpu_seconds + 60.0;
  return budget;
}

WorkEstimate estimate_run(const Study& study, double asperities, bool writes_run_file, bool keeps_motions,
                          std::size_t threads) {
  WorkEstimate e;
  const bool known = asperities < 0.0;
  const double n = known ? static_cast<double>(study.asperities.size()) : asperities;
  const double samples = std::round(study.duration_s * study.sample_rate_hz) + 1.0;
  e.samples = samples;
  e.asperities = n;
  e.add_memory("program", BASE_BYTES);
  e.add_memory(count(samples) + " samples", samples * RUN_BYTES_PER_SAMPLE);
  const double per_asperity_sample =
      study.model == ModelKind::model1 ? MODEL1_BYTES_PER_ASPERITY_SAMPLE : RUN_BYTES_PER_ASPERITY_SAMPLE;
  e.add_memory(count(n) + " asperities x " + count(samples) + " samples", n * samples * per_asperity_sample);
  if (writes_run_file) add_traces(study, n, samples, e);
  add_tribology(study, n, samples, fastest_natural_frequency_hz(study, known), keeps_motions || study.netlist != nullptr,
                static_cast<double>(threads), e);
  if (study.netlist) {
    add_ngspice(*study.netlist, n, samples, e);
  } else {
    e.add_steps("circuit (Radau IIA): " + count(n) + " elements x " + count(samples) + " samples x " +
                    std::to_string(study.circuit.substeps) + " substeps",
                n * std::max(samples - 1.0, 0.0) * static_cast<double>(study.circuit.substeps) * CIRCUIT_STAGES +
                    n * samples);  // and the domain check
  }
  if (study.spectrum) add_spectra(samples, n, *study.spectrum, e);
  if (const RandomSurface* surface = study.surface->random_surface()) add_sampling(*surface, 1.0, e);
  return e;
}

std::size_t run_threads_within(const Study& study, std::size_t wanted, const WorkLimits& limits) {
  std::size_t threads = std::clamp<std::size_t>(wanted, 1, std::max<std::size_t>(study.asperities.size(), 1));
  while (threads > 1 && !(estimate_run(study, -1.0, true, false, threads).memory_bytes <= limits.memory_bytes)) --threads;
  return threads;
}

WorkEstimate estimate_circuit(double samples, double elements, std::size_t substeps) {
  WorkEstimate e;
  e.samples = samples;
  e.asperities = elements;
  e.add_memory("program", BASE_BYTES);
  // x read, the spline's times, values and slopes, x' written, currents and charges: 7
  // values per element and sample, three of them written to the file.
  e.add_memory(count(elements) + " elements x " + count(samples) + " samples",
               elements * samples * (7.0 * 8.0 + 3.0 * FILE_BYTES_PER_VALUE));
  e.add_memory(count(samples) + " samples", samples * RUN_BYTES_PER_SAMPLE);
  e.add_steps("circuit (Radau IIA): " + count(elements) + " elements x " + count(samples) + " samples x " +
                  std::to_string(substeps) + " substeps",
              elements * samples * static_cast<double>(substeps) * CIRCUIT_STAGES);
  return e;
}

WorkEstimate estimate_spectrum(double samples, double currents, const SpectrumSettings& settings) {
  WorkEstimate e;
  e.samples = samples;
  e.asperities = currents;
  e.add_memory("program", BASE_BYTES);
  // Currents and velocities read (two values per element and sample), times and voltage.
  e.add_memory(count(currents) + " elements x " + count(samples) + " samples", currents * samples * 16.0);
  e.add_memory(count(samples) + " samples", samples * RUN_BYTES_PER_SAMPLE);
  add_spectra(samples, currents, settings, e);
  return e;
}

WorkEstimate estimate_surface(const RandomSurface& surface, double realisations) {
  WorkEstimate e;
  e.add_memory("program", BASE_BYTES);
  add_sampling(surface, realisations, e);
  return e;
}

std::string exceeded_limit(const WorkEstimate& e, const WorkLimits& limits, const LimitNames& names) {
  const auto over = [&](double amount, double limit, bool bytes, const std::vector<WorkPart>& parts,
                        const std::string& option) {
    std::string text = "needs ~" + describe(amount, bytes) + (bytes ? " of memory" : "") + ", " +
                       format_number(amount / limit) + " x the limit of " + describe(limit, bytes);
    const WorkPart* part = largest(parts);
    if (part) text += "; most of it: " + part->what + " (~" + describe(part->amount, bytes) + ")";
    if (part && !part->remedy.empty()) return text + ". Reduce it: " + part->remedy + "; or raise the limit with " + option;
    return text + ". Reduce it, or raise the limit with " + option;
  };
  // !(a <= b) also catches NaN and inf from absurd inputs.
  if (!(e.memory_bytes <= limits.memory_bytes)) return over(e.memory_bytes, limits.memory_bytes, true, e.memory, names.memory);
  if (!(e.steps <= limits.steps)) return over(e.steps, limits.steps, false, e.work, names.steps);
  return "";
}

void check_work(const WorkEstimate& estimate, const WorkLimits& limits, const std::string& what, const LimitNames& names) {
  const std::string exceeded = exceeded_limit(estimate, limits, names);
  if (!exceeded.empty()) throw InputError(what + " " + exceeded);
}

}  // namespace stengmc
