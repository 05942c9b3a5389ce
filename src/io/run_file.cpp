#include "io/run_file.hpp"

#include <algorithm>
#include <cmath>

#include "core/build_info.hpp"
#include "core/creation_time.hpp"
#include "core/column.hpp"
#include "core/setting.hpp"
#include "circuit/circuit_settings.hpp"
#include "tribology/model1_settings.hpp"
#include "tribology/model2_settings.hpp"
#include "io/population_file.hpp"
#include "io/spectrum_file.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

//! The evolving contact's per-asperity parameters (docs/model.md §1.4), each only where some
//! asperity has it, so other runs' files stay as they were: the truth a tracker is checked
//! against. Steps are a CF contiguous ragged array (step_count per asperity).
void write_evolving_contact(Hdf5Writer& file, const Study& study) {
  const std::vector<Asperity>& asperities = study.asperities;
  if (std::any_of(asperities.begin(), asperities.end(), [](const Asperity& a) { return std::isfinite(a.release_s); })) {
    // Finite in the file: an asperity still in contact at the end has release = the run's end, released = 0.
    const double end_s = study.duration_s;
    file.write("/asperity/release", column(asperities, [&](const Asperity& a) { return std::min(a.release_s, end_s); }));
    file.write("/asperity/released",
               column(asperities, [&](const Asperity& a) { return a.release_s < end_s ? 1.0 : 0.0; }));
  }
  if (std::any_of(asperities.begin(), asperities.end(), [](const Asperity& a) { return a.wear_rate_per_ms != 0.0; }))
    file.write("/asperity/wear_rate", column(asperities, [](const Asperity& a) { return a.wear_rate_per_ms; }));
  if (std::none_of(asperities.begin(), asperities.end(), [](const Asperity& a) { return !a.stiffness_steps.empty(); })) return;
  std::vector<double> times, factors;
  for (const Asperity& a : asperities)
    for (const StiffnessStep& s : a.stiffness_steps) {
      times.push_back(s.time_s);
      factors.push_back(s.factor);
    }
  file.write("/asperity/step_count",
             column(asperities, [](const Asperity& a) { return static_cast<double>(a.stiffness_steps.size()); }));
  file.attribute("/asperity/step_count", "sample_dimension", "step");
  file.write("/step/time", times);
  file.write("/step/factor", factors);
}

void write_model(Hdf5Writer& file, const Study& study) {
  file.group("/model");
  file.attribute("/model", "kind", model_name(study.model));
  if (study.model == ModelKind::model1) {
    write_settings(file, "/model", model1_settings(study.model1));
    file.attribute("/model", "friction_convention",
                   "tangential force the asperity transmits: mu_k N sign(x') sliding, k (x0 - x) stuck (MODEL.md 1)");
  } else {
    write_settings(file, "/model", model2_settings(study.model2));
    // The counterface's modulation (docs/model.md §1.4), only where there is one: a run
    // without it writes the file it always wrote.
    if (study.model2.counterface.active()) {
      file.group("/counterface");
      write_settings(file, "/counterface", counterface_settings(study.model2.counterface));
    }
    file.attribute("/model", "friction_convention", "F(v_r), the belt's friction force on the asperity, v_r = v_b - x' (MODEL.md 1)");
  }
}

void write_events(Hdf5Writer& file, const RunResult& result) {
  std::vector<double> times;
  std::vector<std::int64_t> asperity;
  std::vector<std::string> kinds;
  for (const Event& e : result.events) {
    times.push_back(e.time_s);
    asperity.push_back(static_cast<std::int64_t>(e.asperity));
    kinds.emplace_back(event_name(e.kind));
  }
  file.write("/events/time", times);
  file.write("/events/asperity", asperity);
  file.write("/events/kind", kinds);
}

}  // namespace

void write_provenance(Hdf5Writer& file, const Provenance& provenance) {
  // Every output is netCDF-4 and follows CF 1.10 where CF has a say: units UDUNITS-2
  // parses, long_name on every variable (io/output_vocabulary.cpp).
  file.attribute("/", "Conventions", "CF-1.10");
  file.attribute("/", "file_type", provenance.file_type);
  file.attribute("/", "format_version", RUN_FILE_FORMAT_VERSION);
  file.attribute("/", "program_version", program_version());
  file.attribute("/", "git_revision", git_revision());
  file.attribute("/", "created_utc", creation_time_utc());
  file.attribute("/", "seed", static_cast<std::int64_t>(provenance.seed));
  file.attribute("/", "input_file", provenance.input_file);
  file.attribute("/", "input_text", provenance.input_text);
  file.attribute("/", "surface_file", provenance.surface_file);
  file.attribute("/", "surface_text", provenance.surface_text);
  if (!provenance.auxiliary_inputs.empty()) file.attribute("/", "surface_auxiliary_inputs", provenance.auxiliary_inputs);
}

void write_netlist_provenance(Hdf5Writer& file, const std::shared_ptr<const NetlistLoad>& netlist) {
  if (!netlist) return;
  file.attribute("/", "netlist_file", netlist->file);
  file.attribute("/", "netlist_text", netlist->text);
  // What ngspice was given: the checked cards, included files inlined (the record is
  // complete without them).
  file.attribute("/", "netlist_cards", netlist_cards_text(*netlist));
}

void write_elements(Hdf5Writer& file, std::span<const StengElement> elements) {
  file.write("/asperity/sigma", column(elements, [](const StengElement& e) { return e.charge_density_c_per_m2; }));
  file.write("/asperity/d0", column(elements, [](const StengElement& e) { return e.effective_thickness_m; }));
  file.write("/asperity/w", column(elements, [](const StengElement& e) { return e.width_m; }));
  file.write("/asperity/l", column(elements, [](const StengElement& e) { return e.length_m; }));
}

void write_circuit(Hdf5Writer& file, const CircuitResult& circuit, const CircuitParams& params, const OutputTraces& traces) {
  file.write("/circuit/voltage", circuit.voltage_v);
  file.write("/circuit/charge", circuit.charge_c);
  if (traces.current) file.write("/asperity/current", circuit.current_a);
  if (traces.charge) file.write("/asperity/charge", circuit.element_charge_c);
  write_settings(file, "/circuit", circuit_settings(params));
  file.attribute("/circuit", "samples", static_cast<std::int64_t>(circuit.voltage_v.size()));
}

void write_run_file(const std::string& path, const Study& study, const RunResult& result, const RunSummary& summary) {
  Hdf5Writer file(path, describe_output);
  write_provenance(file, {.file_type = "stengmc-run",
                          .input_file = study.file,
                          .input_text = study.text,
                          .seed = study.seed,
                          .surface_file = study.surface_file,
                          .surface_text = study.surface_text,
                          .auxiliary_inputs = study.surface->auxiliary_inputs()});
  write_netlist_provenance(file, study.netlist);
  file.attribute("/", "title", study.title);
  file.attribute("/", "realisation", static_cast<std::int64_t>(study.realisation));
  file.attribute("/", "domain_policy", domain_policy_name(study.domain_policy));
  file.attribute("/", "valid", static_cast<std::int64_t>(result.valid ? 1 : 0));
  file.attribute("/", "duration_s", study.duration_s);
  file.attribute("/", "sample_rate_hz", study.sample_rate_hz);

  file.write("/time", result.times_s);
  write_model(file, study);

  file.write("/asperity/k", column(study.asperities, [](const Asperity& a) { return a.stiffness_n_per_m; }));
  file.write("/asperity/m", column(study.asperities, [](const Asperity& a) { return a.mass_kg; }));
  file.write("/asperity/N", column(study.asperities, [](const Asperity& a) { return a.normal_load_n; }));
  file.write("/asperity/h", column(study.asperities, [](const Asperity& a) { return a.height_m; }));
  file.write("/asperity/phi", column(study.asperities, [](const Asperity& a) { return a.drive_phase_rad; }));
  // Only where some asperity comes into contact late: files of studies without onsets stay as they were.
  if (std::any_of(study.asperities.begin(), study.asperities.end(), [](const Asperity& a) { return a.onset_s != 0.0; }))
    file.write("/asperity/onset", column(study.asperities, [](const Asperity& a) { return a.onset_s; }));
  write_evolving_contact(file, study);
  std::vector<StengElement> elements;
  for (const Asperity& a : study.asperities) elements.push_back(a.element);
  write_elements(file, elements);

  // A run of no asperity (a surface of no summits) has no asperity x time traces: an axis of
  // length 0 against the time axis is no dataset HDF5's dimension scales can describe.
  const OutputTraces traces = study.asperities.empty() ? OutputTraces{false, false, false, false, false, false}
                                                       : study.output.traces;
  if (traces.x) file.write("/asperity/x", column(result.trajectories, [](const Trajectory& t) { return t.x_m; }));
  if (traces.v) file.write("/asperity/v", column(result.trajectories, [](const Trajectory& t) { return t.v_m_per_s; }));
  if (traces.friction)
    file.write("/asperity/friction", column(result.trajectories, [](const Trajectory& t) { return t.friction_n; }));
  if (traces.x0 && study.model == ModelKind::model1) {
    auto imposed = [&](const Asperity& a) {
      std::vector<double> row;
      for (double t : result.times_s) row.push_back(imposed_displacement(study.model1, a, t));
      return row;
    };
    file.write("/asperity/x0", column(study.asperities, imposed));
  }

  const auto& s = summary.asperities;
  file.write("/asperity/natural_frequency", column(s, [](const AsperitySummary& a) { return a.natural_frequency_hz; }));
  file.write("/asperity/slip_fraction", column(s, [](const AsperitySummary& a) { return a.slip_fraction; }));
  file.write("/asperity/max_x_over_l", column(s, [](const AsperitySummary& a) { return a.max_x_over_l; }));
  file.write("/asperity/rms_velocity", column(s, [](const AsperitySummary& a) { return a.rms_velocity_m_per_s; }));
  file.write("/asperity/solver_steps",
             column(result.trajectories, [](const Trajectory& t) { return static_cast<std::int64_t>(t.solver_steps); }));

  // A flagged run's circuit stops at the first domain_exit: its own time axis (the leading
  // samples of /time), so that valid_time has a coordinate in seconds, not an index.
  if (result.circuit.voltage_v.size() < result.times_s.size())
    file.write("/valid_time", std::span(result.times_s).first(result.circuit.voltage_v.size()));
  write_circuit(file, result.circuit, study.circuit, traces);
  // R, C_L and substeps above are then the built-in load's, unused: ngspice solved the
  // root's netlist_text.
  if (study.netlist) file.attribute("/circuit", "load", "netlist");
  for (std::size_t p = 0; p < study.probes.size() && p < result.circuit.probes.size(); ++p) {
    const std::string probe_path = "/circuit/probes/" + study.probes[p].dataset;
    file.write(probe_path, result.circuit.probes[p]);
    file.attribute(probe_path, "spice_name", study.probes[p].name);
  }
  if (!result.measured_voltage_v.empty()) {
    file.write("/circuit/measured_voltage", result.measured_voltage_v);
    file.attribute("/circuit/measured_voltage", "noise_sigma_v", result.noise_sigma_v);
    file.attribute("/circuit/measured_voltage", "snr_db", study.noise->snr_db);
    file.attribute("/circuit/measured_voltage", "coloured_share", study.noise->coloured_share);
    file.attribute("/circuit/measured_voltage", "coloured_exponent", study.noise->coloured_exponent);
    file.attribute("/circuit/measured_voltage", "offset_v", study.noise->offset_v);
    file.attribute("/circuit/measured_voltage", "bandwidth_hz", study.noise->bandwidth_hz);
    file.attribute("/circuit/measured_voltage", "reference_rms_v", study.noise->reference_rms_v);
  }
  file.attribute("/circuit", "input", CIRCUIT_INPUT_NAMES.name(study.circuit_input));
  file.attribute("/circuit", "voltage_rms_v", summary.voltage_rms_v);
  file.attribute("/circuit", "voltage_peak_v", summary.voltage_peak_v);
  file.attribute("/circuit", "final_charge_c", summary.final_charge_c);
  write_events(file, result);
  if (result.spectra) write_spectra(file, *result.spectra, *study.spectrum);
  // The realisation's population and its validity report, same layout as `stengmc surface`.
  write_populations(file, "/surface", study.surface->random_surface(), std::span(&study.population, 1),
                    std::span(&result.validity, 1));
  file.commit();
}

}  // namespace stengmc
