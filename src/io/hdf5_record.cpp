#include "io/hdf5_record.hpp"

#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "io/guarded_read.hpp"
#include "io/record_units.hpp"
#include "spectral/analysed_voltage.hpp"

namespace stengmc {

namespace {

// netCDF-4 marks a dimension that has no coordinate variable with a scale of this NAME: it
// holds no times (netCDF-C, libsrc4/nc4internal.h, DIM_WITHOUT_VARIABLE).
constexpr std::string_view NETCDF_BARE_DIMENSION = "This is a netCDF dimension but not a netCDF variable";

// A float32 time keeps 24 bits: a time and the grid's ends, each rounded by half a unit in the
// last place, may put it this much (relative to the record's largest |t|) off the grid drawn
// through the ends (on top of the 1e-6 of a step the analysis allows any record).
constexpr double FLOAT32_RELATIVE_ROUNDING = 1.2e-7;

std::string where_in(const std::string& path, const std::string& object) { return path + ": " + object; }

//! The unit of a CF time coordinate, "microseconds since 2026-01-01" -> "microseconds".
std::string without_epoch(const std::string& units) {
  const std::size_t since = units.find(" since ");
  return since == std::string::npos ? units : units.substr(0, since);
}

//! Times [s] of dataset `name` from its `units` (s when absent).
std::vector<double> times_of(const Hdf5Reader& file, const std::string& path, const std::string& name) {
  std::vector<double> times = file.vector(name);
  const std::string units = without_epoch(file.string_attribute(name, "units"));
  const std::optional<double> scale = time_unit_scale(units);
  if (!scale)
    throw InputError(where_in(path, name) + ": units \"" + units +
                     "\" are not a time unit (expected s, ms, us, ns or ps, or \"<unit> since <epoch>\")");
  for (double& t : times) t *= *scale;
  return times;
}

//! Times from the dataset's sampling attributes, or nothing when it has none.
std::optional<std::vector<double>> times_from_attributes(const Hdf5Reader& file, const std::string& path, const std::string& name,
                                                         std::size_t samples) {
  const std::optional<double> interval = file.number_attribute(name, "sample_interval_s");
  const std::optional<double> rate = file.number_attribute(name, "sample_rate_hz");
  if (!interval && !rate) return std::nullopt;
  if (interval && rate)
    throw InputError(where_in(path, name) + ": has both sample_interval_s and sample_rate_hz; keep one");
  const double step = interval ? *interval : 1.0 / *rate;
  if (!(step > 0.0) || !std::isfinite(step))
    throw InputError(where_in(path, name) + (interval ? "@sample_interval_s = " + format_number(*interval) + " s"
                                                      : "@sample_rate_hz = " + format_number(*rate) + " Hz") +
                     ": expected a finite number > 0");
  const double start = file.number_attribute(name, "start_time_s").value_or(0.0);
  if (!std::isfinite(start)) throw InputError(where_in(path, name) + "@start_time_s: expected a finite number [s]");
  std::vector<double> times(samples);
  for (std::size_t k = 0; k < samples; ++k) times[k] = start + static_cast<double>(k) * step;
  return times;
}

//! Checks `times` (read from `source`) are uniform and puts them on their grid.
void put_on_grid(std::vector<double>& times, const std::string& path, const std::string& source) {
  const std::size_t n = times.size();
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isfinite(times[k]))
      throw InputError(where_in(path, source) + ": time sample " + std::to_string(k) + " is not a finite number");
  if (n < 2) return;
  const double step = (times.back() - times.front()) / static_cast<double>(n - 1);
  if (!(step > 0.0))
    throw InputError(where_in(path, source) + ": the last time " + format_number(times.back()) + " s is not after the first " +
                     format_number(times.front()) + " s: times must increase");
  const double slack = 1e-6 * step + FLOAT32_RELATIVE_ROUNDING * std::max(std::abs(times.front()), std::abs(times.back()));
  for (std::size_t k = 0; k < n; ++k) {
    const double grid = times.front() + static_cast<double>(k) * step;
    if (std::abs(times[k] - grid) > slack)
      throw InputError(where_in(path, source) + ": t[" + std::to_string(k) + "] = " + format_number(times[k]) +
                       " s is off the uniform grid (from " + format_number(times.front()) + " s in steps of " +
                       format_number(step) + " s) by " + format_number(times[k] - grid) +
                       " s: the analysis needs uniformly sampled records");
    times[k] = grid;
  }
}

SignalInput read(const std::string& path, const Hdf5RecordLocation& where) {
  Hdf5Reader file(path);
  const std::string& name = where.dataset;
  if (!file.has(name)) throw InputError(where_in(path, name) + ": no such dataset (--dataset)");
  SignalInput input;
  input.voltage_v = file.vector(name);
  if (input.voltage_v.size() < 2) throw InputError(where_in(path, name) + ": fewer than 2 samples");
  const std::string volts = file.string_attribute(name, "units");
  const std::optional<double> to_volts = voltage_unit_scale(volts);
  if (!to_volts) throw InputError(where_in(path, name) + ": units \"" + volts + "\" are not a voltage unit (expected V, mV, uV or kV)");
  for (std::size_t k = 0; k < input.voltage_v.size(); ++k) {
    double& v = input.voltage_v[k];
    v *= *to_volts;
    if (!(std::abs(v) <= MAX_ANALYSED_VOLTAGE_V))
      throw InputError(where_in(path, name) + ": sample " + std::to_string(k) + " = " + format_number(v) +
                       " V is not a finite voltage the analysis can square and sum (|V| <= 1e100 V)");
  }
  std::string source;
  if (!where.time_dataset.empty()) {
    source = where.time_dataset;
    if (!file.has(source)) throw InputError(where_in(path, source) + ": no such dataset (--time-dataset)");
    input.times_s = times_of(file, path, source);
  } else if (const std::optional<std::string> scale = file.dimension_scale(name, 0);
             scale && file.string_attribute(*scale, "NAME").rfind(NETCDF_BARE_DIMENSION, 0) != 0) {
    source = *scale;
    input.times_s = times_of(file, path, source);
  } else if (std::optional<std::vector<double>> times = times_from_attributes(file, path, name, input.voltage_v.size())) {
    source = name + "@sample_interval_s";
    input.times_s = std::move(*times);
  } else {
    throw InputError(where_in(path, name) + ": no times: give --time-dataset, attach a time coordinate (dimension scale) to "
                     "the dataset, or set its attribute sample_interval_s or sample_rate_hz");
  }
  if (input.times_s.size() != input.voltage_v.size())
    throw InputError(where_in(path, source) + ": " + std::to_string(input.times_s.size()) + " times for " +
                     std::to_string(input.voltage_v.size()) + " samples of " + name);
  put_on_grid(input.times_s, path, source);
  return input;
}

}  // namespace

SignalInput read_hdf5_record(const std::string& path, const Hdf5RecordLocation& where) {
  check_input_file(path, "the record file");
  read_in_child_first(path, [&] { (void)read(path, where); });
  return read(path, where);
}

}  // namespace stengmc
