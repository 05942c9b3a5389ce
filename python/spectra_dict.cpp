#include "spectra_dict.hpp"

#include <pybind11/stl.h>

#include "core/column.hpp"
#include "numpy_arrays.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

std::vector<std::int64_t> ones_and_zeros(const std::vector<bool>& flags) {
  std::vector<std::int64_t> out;
  for (bool b : flags) out.push_back(b ? 1 : 0);
  return out;
}

py::dict identifiability(const Identifiability& id) {
  py::dict out;
  out["identified"] = to_numpy(ones_and_zeros(id.identified));
  out["matched_line"] = to_numpy(std::vector<std::int64_t>(id.matched_line.begin(), id.matched_line.end()));
  out["frequency_error_hz"] = to_numpy(id.frequency_error_hz);
  out["amplitude_v"] = to_numpy(id.amplitude);
  out["n_sliding"] = id.n_sliding;
  out["n_detected"] = id.n_detected;
  out["n_identifiable"] = id.n_identifiable;
  out["ratio"] = id.ratio;
  return out;
}

}  // namespace

py::dict spectra_dict(const SpectralResult& r) {
  py::dict out;
  out["frequency_hz"] = to_numpy(r.voltage.frequency_hz);
  out["voltage_v"] = to_numpy(r.voltage.amplitude);
  if (!r.current_amplitude.empty()) out["current_a"] = rows_to_numpy(r.current_amplitude);
  out["resolution_hz"] = r.voltage.resolution_hz;
  out["noise_floor_v"] = r.noise_floor_v;
  out["start_time_s"] = r.start_time_s;
  out["mean_v"] = r.mean_v;
  out["expected_frequency_hz"] = to_numpy(r.expected_frequency_hz);
  out["sliding"] = to_numpy(ones_and_zeros(r.sliding));
  py::dict peaks;
  peaks["frequency_hz"] = to_numpy(column(r.peaks, [](const Peak& p) { return p.frequency_hz; }));
  peaks["amplitude_v"] = to_numpy(column(r.peaks, [](const Peak& p) { return p.amplitude; }));
  peaks["prominence_v"] = to_numpy(column(r.peaks, [](const Peak& p) { return p.prominence; }));
  out["peaks"] = peaks;
  py::dict ids;
  ids["fft"] = identifiability(r.fft);
  if (r.high_resolution) {
    py::dict lines;
    lines["frequency_hz"] = to_numpy(column(r.lines, [](const Line& l) { return l.frequency_hz; }));
    lines["amplitude_v"] = to_numpy(column(r.lines, [](const Line& l) { return l.amplitude; }));
    lines["damping_per_s"] = to_numpy(column(r.lines, [](const Line& l) { return l.damping_per_s; }));
    lines["phase_rad"] = to_numpy(column(r.lines, [](const Line& l) { return l.phase_rad; }));
    out["lines"] = lines;
    ids["high_resolution"] = identifiability(*r.high_resolution);
  }
  out["identifiability"] = ids;
  if (r.spectrogram) {
    py::dict s;
    s["time_s"] = to_numpy(r.spectrogram->time_s);
    s["frequency_hz"] = to_numpy(r.spectrogram->frequency_hz);
    s["voltage_v"] = rows_to_numpy(r.spectrogram->amplitude);
    out["spectrogram"] = s;
  }
  return out;
}

}  // namespace stengmc::python
