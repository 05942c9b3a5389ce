#pragma once
// How often the 90 % intervals of held-out calibration records, calibrated by a bank's maps,
// cover their truths: the coverage tests of the inverse (ideal and broadened priors) count
// the same way.
#include <cstddef>

#include "inverse/calibration_maps.hpp"
#include "inverse/calibration_run.hpp"

namespace stengmc::testing {

struct HeldOutCoverage {
  std::size_t records = 0, count_covered = 0;
  std::size_t median_records = 0, median_covered = 0;  //!< records with a line found and a truth to compare
  std::size_t sd_records = 0, sd_covered = 0;          //!< records with two lines or more on both sides

  [[nodiscard]] double count() const { return static_cast<double>(count_covered) / static_cast<double>(records); }
  [[nodiscard]] double median() const { return static_cast<double>(median_covered) / static_cast<double>(median_records); }
  [[nodiscard]] double sd() const { return static_cast<double>(sd_covered) / static_cast<double>(sd_records); }
};

inline HeldOutCoverage held_out_coverage(const CalibrationBank& bank, const CalibrationBank& held_out) {
  HeldOutCoverage c;
  for (const CalibrationSample& s : held_out.samples) {
    if (!s.valid) continue;
    const CalibratedEstimate e = calibrate_estimate(s.raw_estimate(), &bank.maps, bank.setup.prior);
    ++c.records;
    c.count_covered += e.interval_low <= s.true_count() && s.true_count() <= e.interval_high;
    if (s.count >= 1 && s.true_count() >= 1) {
      ++c.median_records;
      c.median_covered += e.median_low <= s.true_median() && s.true_median() <= e.median_high;
    }
    if (s.count >= 2 && s.true_count() >= 2) {
      ++c.sd_records;
      c.sd_covered += e.sd_log_low <= s.true_sd_log() && s.true_sd_log() <= e.sd_log_high;
    }
  }
  return c;
}

}  // namespace stengmc::testing
