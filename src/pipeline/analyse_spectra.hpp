#pragma once
//! The spectral analysis of one run (MODEL.md §3): the voltage's spectrum, its peaks and
//! high-resolution lines, each element current's spectrum, the spectrogram, and the
//! identifiability of each sliding asperity's line.
#include <optional>
#include <string>
#include <span>
#include <vector>

#include "spectral/amplitude_spectrum.hpp"
#include "spectral/esprit.hpp"
#include "spectral/identifiability.hpp"
#include "spectral/peaks.hpp"
#include "spectral/spectrogram.hpp"
#include "spectral/spectrum_settings.hpp"

namespace stengmc {

//! The signal to analyse and what each asperity is expected to show.
struct SpectralInput {
  std::span<const double> times_s;                    //!< uniform grid
  std::span<const double> voltage_v;                  //!< same length
  const std::vector<std::vector<double>>* currents_a = nullptr;  //!< [element][sample], or none
  std::vector<double> expected_frequency_hz;          //!< per asperity: damped natural frequency
  std::vector<bool> sliding;                          //!< per asperity: does it slide in the interval
};

//! The analysis interval as samples: half-open [t0 + start_s, t0 + end_s).
struct AnalysisRange {
  std::size_t first_sample = 0;
  std::size_t samples = 0;
  double sample_rate_hz = 0.0;
};

//! The interval `settings` selects on a uniform grid (InputError if not uniform).
AnalysisRange analysis_range(std::span<const double> times_s, const SpectrumSettings& settings);

struct SpectralResult {
  std::size_t first_sample = 0;          //!< analysis interval [first, first + samples)
  std::size_t samples = 0;
  double start_time_s = 0.0;             //!< time of the first analysed sample [s]
  double mean_v = 0.0;                   //!< the voltage's mean over the interval, removed before analysis (A_0) [V]
  std::vector<std::string> notes;        //!< plain-language caveats
  double sample_rate_hz = 0.0;
  std::vector<double> expected_frequency_hz;  //!< per asperity, as given
  std::vector<bool> sliding;                  //!< per asperity, as given
  AmplitudeSpectrum voltage;             //!< of V
  double noise_floor_v = 0.0;            //!< robust floor of that spectrum
  std::vector<Peak> peaks;               //!< FFT peaks of V
  std::vector<std::vector<double>> current_amplitude;  //!< [element][bin], same frequencies as `voltage`
  std::vector<Line> lines;               //!< ESPRIT lines of V (if asked)
  Identifiability fft;                   //!< identifiability from the FFT peaks
  std::optional<Identifiability> high_resolution;  //!< from the ESPRIT lines
  std::optional<Spectrogram> spectrogram;          //!< of V over the whole run
};

//! Throws InputError when the interval holds too few samples or the grid is not uniform.
SpectralResult analyse_spectra(const SpectralInput& input, const SpectrumSettings& settings);

}  // namespace stengmc
