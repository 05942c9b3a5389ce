#include "inverse/record_input.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "spectral/analysed_voltage.hpp"

namespace stengmc {

RecordGrid checked_record_grid(std::span<const double> t, std::span<const double> v, const std::string& source) {
  if (t.size() != v.size())
    throw InputError(source + ": " + std::to_string(t.size()) + " times but " + std::to_string(v.size()) + " voltages");
  if (t.size() < MIN_RECORD_SAMPLES)
    throw InputError(source + ": " + std::to_string(t.size()) + " samples; inverse estimation needs at least " +
                     std::to_string(MIN_RECORD_SAMPLES));
  for (std::size_t m = 0; m < t.size(); ++m) {
    if (!std::isfinite(t[m])) throw InputError(source + ": time of sample " + std::to_string(m + 1) + " is not a finite number");
    if (!std::isfinite(v[m]))
      throw InputError(source + ": voltage of sample " + std::to_string(m + 1) + " (t = " + format_number(t[m]) +
                       " s) is not a finite number (NaN or Inf)");
    if (!(std::abs(v[m]) <= MAX_ANALYSED_VOLTAGE_V))
      throw InputError(source + ": voltage of sample " + std::to_string(m + 1) + " (t = " + format_number(t[m]) + " s) = " +
                       format_number(v[m]) + " V is beyond what the analysis can square and sum (|V| <= " +
                       format_number(MAX_ANALYSED_VOLTAGE_V) + " V)");
  }
  if (t[0] < 0.0)
    throw InputError(source + ": the first time is " + format_number(t[0]) +
                     " s; times count from the start of sliding (t = 0), when the asperities are at rest");
  const double step = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  for (std::size_t m = 1; m < t.size(); ++m) {
    const double dt = t[m] - t[m - 1];
    if (dt == 0.0)
      throw InputError(source + ": sample " + std::to_string(m + 1) + " repeats the time of sample " + std::to_string(m) +
                       " (t = " + format_number(t[m]) + " s): times must be distinct");
    if (dt < 0.0)
      throw InputError(source + ": times must increase; sample " + std::to_string(m + 1) + " (t = " + format_number(t[m]) +
                       " s) comes before sample " + std::to_string(m) + " (t = " + format_number(t[m - 1]) + " s)");
    if (std::abs(dt - step) > 1e-6 * step)
      throw InputError(source + ": the times are not uniform: the step before sample " + std::to_string(m + 1) + " is " +
                       format_number(dt) + " s, the record's mean step " + format_number(step) +
                       " s; inverse estimation needs a uniform grid (resample the record first)");
  }
  return {t.front(), step, t.size()};
}

void check_record_varies(std::span<const double> v, const std::string& source) {
  if (!v.empty() && std::all_of(v.begin(), v.end(), [&](double x) { return x == v[0]; }))
    throw InputError(source + ": the voltage is " + format_number(v[0] == 0.0 ? 0.0 : v[0]) +
                     " V at every sample: a record of a sliding device varies, so there is nothing to invert (is it "
                     "the right column, channel or file?)");
}

}  // namespace stengmc
