// stengmc._core.run: one realisation of a study (pipeline/run_study.hpp) as numpy arrays,
// the same numbers `stengmc run` writes to its run file (README: output files), named
// with their SI units, its spectra when the study has [spectrum], and the summary it prints.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "core/column.hpp"
#include "numpy_arrays.hpp"
#include "ensemble/study_file.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/study_realisation.hpp"
#include "pipeline/run_summary.hpp"
#include "pipeline/spectral_summary.hpp"
#include "spectra_dict.hpp"
#include "tribology/model1.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

struct Computed {
  Study study;
  RunResult result;
  RunSummary summary;
};

//! The run file's /asperity/{k, m, N, h, phi, sigma, d0, w, l} and its summary columns.
py::dict asperity_table(const Computed& c) {
  const std::vector<Asperity>& a = c.study.asperities;
  const std::vector<AsperitySummary>& s = c.summary.asperities;
  py::dict out;
  out["stiffness_n_per_m"] = to_numpy(column(a, [](const Asperity& x) { return x.stiffness_n_per_m; }));
  out["mass_kg"] = to_numpy(column(a, [](const Asperity& x) { return x.mass_kg; }));
  out["normal_load_n"] = to_numpy(column(a, [](const Asperity& x) { return x.normal_load_n; }));
  out["height_m"] = to_numpy(column(a, [](const Asperity& x) { return x.height_m; }));
  out["drive_phase_rad"] = to_numpy(column(a, [](const Asperity& x) { return x.drive_phase_rad; }));
  out["charge_density_c_per_m2"] = to_numpy(column(a, [](const Asperity& x) { return x.element.charge_density_c_per_m2; }));
  out["effective_thickness_m"] = to_numpy(column(a, [](const Asperity& x) { return x.element.effective_thickness_m; }));
  out["width_m"] = to_numpy(column(a, [](const Asperity& x) { return x.element.width_m; }));
  out["length_m"] = to_numpy(column(a, [](const Asperity& x) { return x.element.length_m; }));
  out["natural_frequency_hz"] = to_numpy(column(s, [](const AsperitySummary& x) { return x.natural_frequency_hz; }));
  out["slip_fraction"] = to_numpy(column(s, [](const AsperitySummary& x) { return x.slip_fraction; }));
  out["max_x_over_l"] = to_numpy(column(s, [](const AsperitySummary& x) { return x.max_x_over_l; }));
  out["rms_velocity_m_per_s"] = to_numpy(column(s, [](const AsperitySummary& x) { return x.rms_velocity_m_per_s; }));
  out["solver_steps"] = to_numpy(
      column(c.result.trajectories, [](const Trajectory& t) { return static_cast<std::int64_t>(t.solver_steps); }));
  return out;
}

//! The asperity x sample traces the study's [output] keeps (all by default).
py::dict traces(const Computed& c) {
  const OutputTraces& kept = c.study.output.traces;
  const std::vector<Trajectory>& t = c.result.trajectories;
  py::dict out;
  if (kept.x) out["x_m"] = rows_to_numpy(column(t, [](const Trajectory& x) { return x.x_m; }));
  if (kept.v) out["v_m_per_s"] = rows_to_numpy(column(t, [](const Trajectory& x) { return x.v_m_per_s; }));
  if (kept.friction) out["friction_n"] = rows_to_numpy(column(t, [](const Trajectory& x) { return x.friction_n; }));
  if (kept.current) out["current_a"] = rows_to_numpy(c.result.circuit.current_a);
  if (kept.charge) out["charge_c"] = rows_to_numpy(c.result.circuit.element_charge_c);
  if (kept.x0 && c.study.model == ModelKind::model1) {
    const auto imposed = [&](const Asperity& a) {
      std::vector<double> row;
      for (double time : c.result.times_s) row.push_back(imposed_displacement(c.study.model1, a, time));
      return row;
    };
    out["x0_m"] = rows_to_numpy(column(c.study.asperities, imposed));
  }
  return out;
}

py::dict events(const RunResult& result) {
  std::vector<double> times;
  std::vector<std::int64_t> asperity;
  py::list kinds;
  for (const Event& e : result.events) {
    times.push_back(e.time_s);
    asperity.push_back(static_cast<std::int64_t>(e.asperity));
    kinds.append(std::string(event_name(e.kind)));
  }
  py::dict out;
  out["time_s"] = to_numpy(std::move(times));
  out["asperity"] = to_numpy(std::move(asperity));
  out["kind"] = kinds;
  return out;
}

//! What `stengmc run` prints, as numbers and as its text.
py::dict summary(const Computed& c) {
  std::string text = format_summary(c.study, c.result, c.summary);
  if (c.result.spectra) text += format_spectral_summary(*c.result.spectra);
  for (const std::string& note : c.result.notes) text += "NOTE: " + note + "\n";
  py::dict out;
  out["voltage_rms_v"] = c.summary.voltage_rms_v;
  out["voltage_peak_v"] = c.summary.voltage_peak_v;
  out["final_charge_c"] = c.summary.final_charge_c;
  out["asperity_count"] = c.study.asperities.size();
  out["valid"] = c.result.valid;
  out["circuit_samples"] = c.result.circuit_samples;
  out["notes"] = c.result.notes;
  out["tribology_seconds"] = c.result.tribology_seconds;
  out["circuit_seconds"] = c.result.circuit_seconds;
  out["text"] = text;
  return out;
}

py::dict run(const StudyFile& base, std::uint64_t realisation, bool progress) {
  std::unique_ptr<Computed> c;
  {
    // The computation holds no Python object: other Python threads run meanwhile.
    py::gil_scoped_release release;
    Study study = study_for_realisation(base, realisation);
    // Arrays, not dense motions, come back: each motion goes once summed (a long run fits).
    RunResult result =
        run_study(study, RunOptions{.show_progress = progress, .limits = WorkLimits{}, .keep_motions = false});
    RunSummary s = summarise(study, result);
    c = std::make_unique<Computed>(Computed{std::move(study), std::move(result), std::move(s)});
  }
  py::dict out;
  out["realisation"] = realisation;
  out["time_s"] = to_numpy(c->result.times_s);
  out["voltage_v"] = to_numpy(c->result.circuit.voltage_v);
  out["charge_c"] = to_numpy(c->result.circuit.charge_c);
  if (!c->result.measured_voltage_v.empty()) out["measured_voltage_v"] = to_numpy(c->result.measured_voltage_v);
  out["asperities"] = asperity_table(*c);
  out["traces"] = traces(*c);
  out["events"] = events(c->result);
  if (c->result.spectra) out["spectra"] = spectra_dict(*c->result.spectra);
  out["summary"] = summary(*c);
  return out;
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("run", &run, py::arg("study"), py::arg("realisation") = 0, py::arg("progress") = false,
        "Runs one realisation (as `stengmc run --realisation`); a dict of numpy arrays and the summary");
}

}  // namespace stengmc::python
