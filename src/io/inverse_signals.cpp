#include "io/inverse_signals.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "io/guarded_read.hpp"
#include "io/hdf5_record.hpp"
#include "io/instrument_csv.hpp"
#include "io/run_file.hpp"
#include "io/signal_input.hpp"

namespace stengmc {

namespace {

//! The record of one trace group of an ensemble file.
NamedRecord trace_record(const Hdf5Reader& file, const std::string& path, const std::string& group) {
  NamedRecord r;
  r.name = path + "#" + group.substr(std::string("/traces/").size());
  r.times_s = file.vector(group + "/time");
  r.voltage_v = file.has(group + "/measured_voltage") ? file.vector(group + "/measured_voltage") : file.vector(group + "/voltage");
  return r;
}

//! The records of a run, circuit or ensemble file (or of another program's file with /time
//! and /circuit/voltage); numbers of any HDF5 type (integers, float32) read as doubles.
std::vector<NamedRecord> read_hdf5_records(const std::string& path, std::vector<std::string>* notes) {
  Hdf5Reader file(path);
  check_format_version(file, path, RUN_FILE_FORMAT_VERSION);
  if (file.string_attribute("/", "file_type") == "stengmc-ensemble") {
    // Traces by realisation id, in /realisations order (sweeps: by grid point).
    const std::vector<double> ids = file.vector("/realisations/realisation");
    const std::vector<double> points = file.vector("/realisations/grid_point");
    const bool sweep = file.integer_attribute("/", "grid_points").value_or(1) > 1;
    // An invalid realisation (the model left the device's range: an asperity reached l, the
    // solver failed) keeps the trace up to where it stopped: not a record of the device, and
    // of another length than the others.
    const std::vector<double> valid = file.has("/realisations/valid") ? file.vector("/realisations/valid") : std::vector<double>(ids.size(), 1.0);
    std::size_t skipped = 0;
    std::vector<NamedRecord> records;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::string realisation = "realisation_" + std::to_string(static_cast<long long>(ids[i]));
      if (i < valid.size() && valid[i] == 0.0) {
        ++skipped;
        continue;
      }
      const std::string group = sweep ? "/traces/point_" + std::to_string(static_cast<long long>(points[i])) + "/" + realisation
                                      : "/traces/" + realisation;
      if (file.has(group + "/time")) records.push_back(trace_record(file, path, group));
    }
    if (skipped > 0 && notes)
      notes->push_back(path + ": " + std::to_string(skipped) + " invalid realisation(s) skipped (/realisations/valid = 0: the model left the device's range; /realisations/failure says how)");
    if (records.empty())
      throw InputError(path + ": the ensemble kept no traces of valid realisations to invert (set [ensemble] trace_all = true, or trace_realisations)");
    return records;
  }
  if (!file.has("/circuit/voltage") || !file.has("/time"))
    throw InputError(path + ": no /time and /circuit/voltage to invert (give a CSV `t,V`, a run file or an ensemble file)");
  NamedRecord r;
  r.name = path;
  r.voltage_v = file.has("/circuit/measured_voltage") ? file.vector("/circuit/measured_voltage") : file.vector("/circuit/voltage");
  r.times_s = file.vector("/time");
  r.times_s.resize(std::min(r.times_s.size(), r.voltage_v.size()));  // an invalid run's circuit stops early
  return {std::move(r)};
}

}  // namespace

std::vector<NamedRecord> read_inverse_records(const std::string& path, const RecordReadOptions& text, std::vector<std::string>* notes) {
  if (!std::filesystem::exists(path)) throw InputError(path + ": no such file");
  if (!text.hdf5.dataset.empty()) {
    SignalInput s = read_hdf5_record(path, text.hdf5);
    return {{path + "#" + text.hdf5.dataset, std::move(s.times_s), std::move(s.voltage_v)}};
  }
  if (is_record_text(path, text)) {
    SignalInput s = read_record_text(path, text);
    return {{path, std::move(s.times_s), std::move(s.voltage_v)}};
  }
  // As every HDF5 input: a regular file, read first by a child process that a damaged file
  // may crash or hang instead of this one (io/guarded_read.hpp).
  check_input_file(path, "the record file");
  read_in_child_first(path, [&] { (void)read_hdf5_records(path, nullptr); });
  return read_hdf5_records(path, notes);
}

}  // namespace stengmc
