#include "spectral/identifiability.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "spectral/assignment.hpp"

// MODEL.md §3, read literally: asperity i is identified when
//   (a) exactly one detected line lies within relative_tolerance x f_i of f_i, and
//   (b) that line is the one the optimal one-to-one assignment gives to i (so it is matched
//       to no other asperity).
// Consequences worth knowing:
// - Two asperities with the same f_i and a single line there: (a) holds for both, the
//   assignment gives the line to one of them (which one is a tie, decided by the solver),
//   so exactly one is counted. Physically the line is the sum of both; MODEL.md's rule
//   still credits one asperity with it, because one line is all the spectrum shows.
// - A spurious second line within the tolerance makes i unidentifiable even when the
//   assignment picks the right one: the spectrum alone cannot tell which is i's.
// - matched_line, frequency_error_hz and amplitude report the optimal assignment for every
//   sliding asperity that got a line, identified or not; `identified` adds condition (a).

namespace stengmc {

Identifiability assess_identifiability(std::span<const double> expected_hz, const std::vector<bool>& sliding,
                                       std::span<const double> detected_hz, std::span<const double> detected_amplitude,
                                       const IdentifiabilityOptions& options) {
  const std::size_t n = expected_hz.size();
  if (sliding.size() != n)
    throw InputError("identifiability: " + std::to_string(n) + " expected frequencies but " +
                     std::to_string(sliding.size()) + " sliding flags");
  if (detected_amplitude.size() != detected_hz.size())
    throw InputError("identifiability: " + std::to_string(detected_hz.size()) + " detected frequencies but " +
                     std::to_string(detected_amplitude.size()) + " amplitudes");
  if (!(options.relative_tolerance > 0.0) || !std::isfinite(options.relative_tolerance))
    throw InputError("identifiability: relative_tolerance must be a positive finite number");
  for (const double f : detected_hz)
    if (!std::isfinite(f)) throw InputError("identifiability: a detected line frequency is not finite");

  Identifiability result;
  result.n_detected = detected_hz.size();
  result.matched_line.assign(n, -1);
  result.identified.assign(n, false);
  result.frequency_error_hz.assign(n, 0.0);
  result.amplitude.assign(n, 0.0);

  std::vector<std::size_t> rows;  // the sliding asperities, in order
  for (std::size_t i = 0; i < n; ++i) {
    if (!sliding[i]) continue;
    if (!(expected_hz[i] > 0.0) || !std::isfinite(expected_hz[i]))
      throw InputError("identifiability: asperity " + std::to_string(i) + " slides but its expected frequency " +
                       std::to_string(expected_hz[i]) + " Hz is not a positive finite number");
    rows.push_back(i);
  }
  result.n_sliding = rows.size();
  if (rows.empty()) return result;

  const auto within = [&](std::size_t i, std::size_t d) {
    return std::abs(detected_hz[d] - expected_hz[i]) <= options.relative_tolerance * expected_hz[i];
  };
  const auto n_rows = static_cast<Eigen::Index>(rows.size());
  const auto n_cols = static_cast<Eigen::Index>(detected_hz.size());
  Eigen::MatrixXd cost(n_rows, n_cols);
  for (Eigen::Index r = 0; r < n_rows; ++r)
    for (Eigen::Index d = 0; d < n_cols; ++d) {
      const std::size_t i = rows[static_cast<std::size_t>(r)];
      const auto line = static_cast<std::size_t>(d);
      cost(r, d) = within(i, line) ? std::abs(detected_hz[line] - expected_hz[i]) : std::numeric_limits<double>::infinity();
    }
  const std::vector<int> assigned = hungarian_assignment(cost);

  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    const int d = assigned[r];
    if (d < 0) continue;
    const auto line = static_cast<std::size_t>(d);
    result.matched_line[i] = d;
    result.frequency_error_hz[i] = detected_hz[line] - expected_hz[i];
    result.amplitude[i] = detected_amplitude[line];
    std::size_t candidates = 0;
    for (std::size_t k = 0; k < detected_hz.size(); ++k) candidates += within(i, k) ? 1 : 0;
    if (candidates == 1) {  // the assigned line is then that one candidate
      result.identified[i] = true;
      ++result.n_identifiable;
    }
  }
  result.ratio = static_cast<double>(result.n_identifiable) / static_cast<double>(result.n_sliding);
  return result;
}

}  // namespace stengmc
