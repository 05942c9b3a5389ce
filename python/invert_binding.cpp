// stengmc._core.invert: the inverse estimator (inverse/inversion.hpp) on one measured record
// given as arrays, as `stengmc invert` runs it on one record (src/app/command_invert.cpp):
// the known device's study, the record's grid checked, the bank (when given) checked
// against the device, the atoms, one Inverter. The result holds what the inverse file's
// /inverse/ datasets hold for that record, under the same names.
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>

#include "bindings.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/inversion.hpp"
#include "inverse/inversion_work.hpp"
#include "inverse/record_input.hpp"
#include "io/calibration_bank_file.hpp"
#include "numpy_arrays.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

//! One /inverse/stiffness/laws entry per fitted family, best AIC first.
py::list laws(const std::vector<LawFit>& fits) {
  py::list out;
  const double best = fits.empty() ? 0.0 : fits.front().aic;
  for (const LawFit& law : fits) {
    py::dict d;
    d["family"] = std::string(stiffness_family_name(law.family));
    d["fitted"] = law.fitted;
    d["first"] = law.parameters[0];
    d["first_low"] = law.interval[0][0];
    d["first_high"] = law.interval[0][1];
    d["second"] = law.parameters[1];
    d["second_low"] = law.interval[1][0];
    d["second_high"] = law.interval[1][1];
    d["aic"] = law.aic;
    d["delta_aic"] = law.fitted ? law.aic - best : 0.0;
    d["median"] = law.median;
    d["sd_log"] = law.sd_log;
    out.append(d);
  }
  return out;
}

py::dict to_dict(const Inversion& inv, const std::string& bank_path) {
  const RecordEstimate& e = inv.raw;
  const CalibratedEstimate& c = inv.calibrated;
  py::dict count;
  count["counts"] = to_numpy_int64(c.counts);
  count["estimate"] = c.count;
  count["interval_low"] = c.interval_low;
  count["interval_high"] = c.interval_high;
  count["naive_fft"] = inv.naive_count;
  count["probability"] = to_numpy(c.probability);
  // The raw posterior on the calibrated counts (0 where it has no mass), as the file holds it.
  std::vector<double> raw(c.counts.size(), 0.0);
  for (std::size_t j = 0; j < e.posterior.counts.size(); ++j) {
    const std::size_t n = e.posterior.counts[j];
    if (n >= c.counts.front() && n <= c.counts.back()) raw[n - c.counts.front()] = e.posterior.probability[j];
  }
  count["raw_probability"] = to_numpy(std::move(raw));

  std::vector<double> k, se, inflation, frequency, amplitude, separation;
  for (const EstimatedLine& line : e.lines) {
    k.push_back(line.stiffness_n_per_m);
    se.push_back(line.log_stiffness_se);
    inflation.push_back(line.se_inflation);
    frequency.push_back(line.frequency_hz);
    amplitude.push_back(line.amplitude_v);
    separation.push_back(line.nearest_separation_hz);
  }
  py::dict lines;
  lines["stiffness_n_per_m"] = to_numpy(std::move(k));
  lines["stiffness_low"] = to_numpy(c.line_low);
  lines["stiffness_high"] = to_numpy(c.line_high);
  lines["log_stiffness_se"] = to_numpy(std::move(se));
  lines["se_inflation"] = to_numpy(std::move(inflation));
  lines["frequency_hz"] = to_numpy(std::move(frequency));
  lines["amplitude_v"] = to_numpy(std::move(amplitude));
  lines["nearest_separation_hz"] = to_numpy(std::move(separation));

  py::dict stiffness;
  stiffness["median"] = c.median;
  stiffness["median_low"] = c.median_low;
  stiffness["median_high"] = c.median_high;
  stiffness["sd_log"] = c.sd_log;
  stiffness["sd_log_low"] = c.sd_log_low;
  stiffness["sd_log_high"] = c.sd_log_high;
  stiffness["intervals_calibrated"] = c.population_intervals;
  stiffness["laws"] = laws(inv.laws);

  py::dict record;
  record["noise_sigma_v"] = e.noise.sigma_v;
  record["residual_sigma_v"] = e.residual_sigma_v;
  record["signal_to_noise_db"] = e.signal_to_noise_db;
  record["band_power_ratio"] = e.in_band_power_ratio;
  record["lines_outside_prior"] = e.lines_outside_prior;
  record["onset_steps"] = e.onset_steps;
  record["seconds"] = e.seconds;

  py::dict out;
  out["name"] = inv.name;
  out["calibrated"] = c.calibrated;
  out["bank"] = bank_path;
  out["count"] = count;
  out["lines"] = lines;
  out["stiffness"] = stiffness;
  out["record"] = record;
  out["verdict"] = inv.verdict;
  out["warnings"] = inv.warnings;
  out["model_v"] = to_numpy(inv.model_v);
  return out;
}

//! A limit given as a keyword argument: a finite number > 0, else InputError naming it.
double checked_limit(double value, const char* argument, const char* unit) {
  if (!(std::isfinite(value) && value > 0.0))
    throw InputError(std::string("invert: ") + argument + " = " + format_number(value) + " must be a finite number > 0 [" +
                     unit + "]");
  return value;
}

py::dict invert(const std::string& known, const py::array_t<double, py::array::forcecast>& time_s,
                const py::array_t<double, py::array::forcecast>& voltage_v, const std::optional<std::string>& bank_path,
                const std::string& name, double max_memory_gb, double max_steps) {
  // As the command line's --max-memory-gb and --max-steps, raised under their own names.
  const WorkLimits limits{checked_limit(max_memory_gb, "max_memory_gb", "GB") * 1e9, checked_limit(max_steps, "max_steps", "steps")};
  const LimitNames names{"max_memory_gb", "max_steps"};
  const std::vector<double> times = from_numpy(time_s, name + ": time_s");
  const std::vector<double> voltage = from_numpy(voltage_v, name + ": voltage_v");
  if (times.size() != voltage.size())
    throw InputError(name + ": time_s has " + std::to_string(times.size()) + " samples and voltage_v " +
                     std::to_string(voltage.size()) + ": expected one time per voltage");
  Inversion inversion;
  {
    py::gil_scoped_release release;
    const Study study = read_study(known, std::nullopt);
    const RecordGrid grid = checked_record_grid(times, voltage, name);
    InverseSetup setup;
    try {
      setup = inverse_setup(study, grid);
    } catch (const InputError& e) {
      // As `stengmc invert`: a sample rate too low for the prior is the record's fault as much as the prior's.
      const std::string what = e.what();
      if (what.rfind("the record's sample rate", 0) == 0) throw InputError(name + ": " + what);
      throw;
    }
    std::optional<StoredBank> bank;
    if (bank_path) {
      bank = read_calibration_bank(*bank_path);
      const std::string differences = bank->identity.differences(setup.identity);
      if (!differences.empty())
        throw InputError(*bank_path + " was made for other known parameters than " + known + " and this record: " +
                         differences + ". Make a bank for them with stengmc calibrate (the study's duration_s and "
                         "sample_rate_hz set the record grid)");
    }
    check_work(estimate_inversion(study, setup, {.records = 1, .threads = 1, .builds_atoms = !bank}), limits,
               name + ": inverting its " + std::to_string(setup.grid.samples) + " samples", names);
    check_record_varies(voltage, name);
    const std::unique_ptr<AtomLibrary> atoms = bank ? build_atom_library(setup, bank->atoms) : build_atom_library(setup);
    Inverter inverter(setup, *atoms, bank ? &bank->maps : nullptr);
    inversion = inverter.invert(name, voltage);
  }
  return to_dict(inversion, bank_path.value_or(""));
}

}  // namespace

void bind_invert(py::module_& m) {
  m.def("invert", &invert, py::arg("known"), py::arg("time_s"), py::arg("voltage_v"), py::arg("bank") = py::none(),
        py::arg("name") = "record", py::arg("max_memory_gb") = WorkLimits{}.memory_bytes / 1e9,
        py::arg("max_steps") = WorkLimits{}.steps,
        "Inverts one measured record of the known device `known` (a study file with [inverse]); with `bank` "
        "(from `stengmc calibrate`) the answer is calibrated, without it the raw posterior");
}

}  // namespace stengmc::python
