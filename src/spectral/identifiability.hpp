#pragma once
//! FFT peak identifiability (MODEL.md §3): asperity i is identifiable when exactly one
//! detected line lies within a tolerance of its line f_i and that line is matched to no
//! other asperity (optimal one-to-one assignment on frequency distance).
#include <cstddef>
#include <span>
#include <vector>

namespace stengmc {

struct IdentifiabilityOptions {
  double relative_tolerance = 0.02;  //!< a detected line within this x f_i of f_i can be asperity i's
};

struct Identifiability {
  std::size_t n_sliding = 0;       //!< asperities expected to show a line
  std::size_t n_detected = 0;      //!< detected lines
  std::size_t n_identifiable = 0;  //!< asperities identified
  double ratio = 0.0;              //!< n_identifiable / n_sliding (0 when none slides)
  std::vector<int> matched_line;   //!< per asperity: index into the detected lines, or -1
  std::vector<bool> identified;    //!< per asperity
  std::vector<double> frequency_error_hz;  //!< per asperity: detected - expected (0 if unmatched)
  std::vector<double> amplitude;           //!< per asperity: the matched line's amplitude (0 if unmatched)
};

//! @param expected_hz  per asperity: its damped natural frequency
//! @param sliding      per asperity: whether it slides at all (a sticking asperity has no line)
//! @param detected_hz  detected line frequencies; `detected_amplitude` their amplitudes
Identifiability assess_identifiability(std::span<const double> expected_hz, const std::vector<bool>& sliding,
                                       std::span<const double> detected_hz, std::span<const double> detected_amplitude,
                                       const IdentifiabilityOptions& options);

}  // namespace stengmc
