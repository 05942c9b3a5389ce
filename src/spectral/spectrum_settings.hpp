#pragma once
//! The `[spectrum]` section of a study: what spectral analysis a run does (README).
#include <cstddef>
#include <optional>
#include <string_view>

#include "core/toml_reader.hpp"
#include "spectral/esprit.hpp"
#include "spectral/identifiability.hpp"
#include "spectral/peaks.hpp"
#include "spectral/spectrogram.hpp"
#include "spectral/window.hpp"

namespace stengmc {

struct SpectrumSettings {
  WindowKind window = WindowKind::hann;
  double start_s = 0.0;                 //!< analysis interval start: skips the start-up transient [s]
  double end_s = 0.0;                   //!< analysis interval end [s]; 0 = the end of the run
  std::size_t zero_pad_factor = 1;      //!< FFT length = samples x this
  bool element_currents = true;         //!< also the spectrum of each element current
  PeakOptions peaks;
  bool high_resolution = true;          //!< also ESPRIT lines and their identifiability
  EspritOptions esprit;
  IdentifiabilityOptions identifiability;
  //! Lines weaker than the strongest by more than this are not reported [dB]. A simulated
  //! signal has no noise floor: harmonics and intermodulation products of the friction
  //! nonlinearity sit 80-120 dB below the lines and would count as detections. A measured
  //! (or noise-added) signal's floor usually does this job first.
  double dynamic_range_db = 60.0;
  double min_slip_fraction = 0.1;       //!< an asperity sliding less of the interval than this counts as sticking (no line expected)
  std::optional<SpectrogramOptions> spectrogram;  //!< present when [spectrum.spectrogram] is
};

//! Reads `[spectrum]` (and `[spectrum.spectrogram]`), validating every key.
SpectrumSettings read_spectrum_settings(TomlTable& table);

//! The `[spectrum]` table of `document` read alone (a settings file, or the keyword arguments
//! of the Python module): every key of it checked, the rest of the document ignored. Without
//! one, an InputError at `spectrum` that says "is missing" followed by `when_missing`.
SpectrumSettings read_spectrum_table(TomlDocument& document, std::string_view when_missing = "");

}  // namespace stengmc
