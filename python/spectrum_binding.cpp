// stengmc._core.spectrum: a voltage record given as a numpy array, analysed as `stengmc
// spectrum` analyses a record file (pipeline/analyse_spectra.hpp) with the [spectrum]
// settings given as TOML text (the Python side writes it from keyword arguments), so the
// keys are checked, and misspellings named, by the same reader as a study's.
#include <cmath>

#include "bindings.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"
#include "numpy_arrays.hpp"
#include "pipeline/analyse_spectra.hpp"
#include "spectra_dict.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

py::dict spectrum(const py::array_t<double, py::array::forcecast>& voltage_v, double sample_rate_hz,
                  const std::string& settings_text, const std::string& name) {
  if (!(std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0))
    throw InputError(name + ": sample_rate_hz = " + format_number(sample_rate_hz) + " must be a finite number > 0 [Hz]");
  const std::vector<double> voltage = from_numpy(voltage_v, name + ": voltage_v");
  SpectralResult result;
  {
    py::gil_scoped_release release;
    const SpectrumSettings settings = read_spectrum_table(*TomlDocument::from_string(settings_text, name));
    std::vector<double> times(voltage.size());
    for (std::size_t i = 0; i < times.size(); ++i) times[i] = static_cast<double>(i) / sample_rate_hz;
    SpectralInput input;
    input.times_s = times;
    input.voltage_v = voltage;
    try {
      result = analyse_spectra(input, settings);
    } catch (const InputError& e) {
      throw InputError(name + ": " + e.what());
    }
  }
  return spectra_dict(result);
}

}  // namespace

void bind_spectrum(py::module_& m) {
  m.def("spectrum", &spectrum, py::arg("voltage_v"), py::arg("sample_rate_hz"), py::arg("settings_text"),
        py::arg("name"),
        "The spectral analysis `stengmc spectrum` makes of a record: a 1-D voltage [V] sampled at sample_rate_hz [Hz], "
        "with the [spectrum] table given as TOML text");
}

}  // namespace stengmc::python
