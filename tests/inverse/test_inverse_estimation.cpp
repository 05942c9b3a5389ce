// The inverse estimation end to end on records simulated by the forward model: the issue's
// must-show cases (a noise-free record of four well-separated lines; a record outside the
// prior warned about) and the calibration's coverage on held-out records (a test that can
// fail: it compares intervals with truths the estimator never saw).
#include <gtest/gtest.h>

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <filesystem>
#include <vector>

#include "core/error.hpp"
#include "core/random_stream.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/inversion.hpp"
#include "inverse/record_input.hpp"
#include "inverse/simulated_record.hpp"
#include "pipeline/study.hpp"
#include "support/cli_runner.hpp"
#include "support/held_out_coverage.hpp"
#include "support/inverse_device.hpp"

namespace stengmc {
namespace {

using testing::ScratchDir;

using testing::known_device_study;

TEST(InverseEstimation, NoiseFreeRecordOfFourSeparatedLines) {
  // The regime (100 us at 100 MHz, prior n 1..16, lognormal medians 40-120 N/m);
  // four lines 0.87, 1.23, 1.67, 2.25 MHz apart by ~25 line widths.
  const Study study = parse_study(known_device_study("100e-6", ""), "four_lines.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(study);
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  const AtomLibrary& atoms = *library;
  const std::vector<double> k = {30.0, 60.0, 110.0, 200.0};
  const std::vector<double> record = simulate_record(setup.device, k, setup.grid);
  Inverter inverter(setup, atoms, nullptr);
  const Inversion result = inverter.invert("four lines", record);
  EXPECT_EQ(result.calibrated.count, 4u);
  EXPECT_LE(result.calibrated.interval_high - result.calibrated.interval_low, 1u);
  ASSERT_EQ(result.raw.lines.size(), 4u);
  // Without noise the only error is the record model's (~1e-4 relative L2 per atom): the
  // issue asks for 1e-3 on each k.
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(result.raw.lines[i].stiffness_n_per_m / k[i], 1.0, 1e-3) << "line " << i;
}

TEST(InverseEstimation, RecordOutsideThePriorIsWarnedAbout) {
  // A narrow prior (medians 60-80 N/m, sigma_log 0.1-0.15: k within ~39-140 N/m) and a
  // record with a line at 190 N/m (inside the atoms' 1.25x margin, outside the prior).
  const Study study = parse_study(known_device_study("30e-6", "median_n_per_m = [60, 80]\nsigma_log = [0.1, 0.15]\ncount = [1, 6]\n"),
                                  "narrow.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(study);
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  const AtomLibrary& atoms = *library;
  std::vector<double> record = simulate_record(setup.device, std::vector<double>{70.0, 170.0}, setup.grid);
  RandomEngine engine = random_stream(1, 0, StreamKind::noise);
  boost::random::normal_distribution<double> noise(0.0, 1e-4);
  for (double& v : record) v += noise(engine);
  Inverter inverter(setup, atoms, nullptr);
  const Inversion result = inverter.invert("outside", record);
  bool warned = false;
  for (const std::string& w : result.warnings) warned = warned || w.find("outside the prior") != std::string::npos;
  EXPECT_TRUE(warned) << "no warning that a line lies outside the prior";
  // And one inside the prior gets no such warning.
  std::vector<double> inside = simulate_record(setup.device, std::vector<double>{70.0, 90.0}, setup.grid);
  for (double& v : inside) v += noise(engine);
  for (const std::string& w : inverter.invert("inside", inside).warnings) EXPECT_EQ(w.find("outside the prior"), std::string::npos) << w;
}

TEST(InverseEstimation, NinetyPercentIntervalsCoverHeldOutRecords) {
  // A small calibration (240 records, seed 11) and 240 held-out records of the same prior
  // with another seed (12): the held-out records' 90 % intervals, calibrated by the first
  // bank's maps, must cover their truths in 0.83-0.97 of the records. With 240 records a
  // true coverage of 0.90 gives 0.90 +- 0.019 (one sd): the band is ~3.5 sd wide, so a
  // correct calibration passes and an over- or under-confident one does not.
  // Cheap records (30 us, 1-6 asperities) keep the test at ~1 min on two cores.
  const std::string inverse = "count = [1, 6]\nmedian_n_per_m = [50, 100]\nsigma_log = [0.2, 0.5]\ncalibration_records = 240\n";
  ScratchDir scratch("inverse-coverage");
  CalibrationOptions options;
  options.show_progress = false;
  options.seed = 11;
  const Study study = parse_study(known_device_study("30e-6", inverse), "coverage.toml", std::nullopt);
  const CalibrationBank bank = run_calibration(study, scratch.file("bank.journal"), options);
  options.seed = 12;
  const CalibrationBank held_out = run_calibration(study, scratch.file("held_out.journal"), options);

  // count = [1, 6]: every record has a line and a truth, so the median's records are all of them.
  const testing::HeldOutCoverage coverage = testing::held_out_coverage(bank, held_out);
  ASSERT_GE(coverage.records, 200u);
  const double median_coverage = coverage.median(), sd_coverage = coverage.sd(), count_coverage = coverage.count();
  std::printf("held-out coverage of the 90 %% intervals: n %.3f, median %.3f, sd(ln k) %.3f (%zu records)\n", count_coverage,
              median_coverage, sd_coverage, coverage.records);
  EXPECT_GE(median_coverage, 0.83);
  EXPECT_LE(median_coverage, 0.97);
  EXPECT_GE(sd_coverage, 0.83);
  EXPECT_LE(sd_coverage, 0.97);
  EXPECT_GE(count_coverage, 0.83);
}

TEST(InverseRecordInput, RejectsWhatCannotBeInverted) {
  std::vector<double> t(100), v(100, 0.0);
  for (std::size_t m = 0; m < t.size(); ++m) t[m] = 1e-8 * static_cast<double>(m);
  EXPECT_NO_THROW(checked_record_grid(t, v, "ok"));
  auto message = [&](std::vector<double> times, std::vector<double> volts) {
    try {
      checked_record_grid(times, volts, "rec.csv");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({t.begin(), t.begin() + 63}, {v.begin(), v.begin() + 63}).find("at least 64"), std::string::npos);
  auto duplicated = t;
  duplicated[50] = duplicated[49];
  EXPECT_NE(message(duplicated, v).find("repeats the time of sample 50"), std::string::npos);
  auto uneven = t;
  uneven[50] += 3e-9;
  EXPECT_NE(message(uneven, v).find("not uniform"), std::string::npos);
  auto nan = v;
  nan[7] = std::nan("");
  EXPECT_NE(message(t, nan).find("sample 8"), std::string::npos);
  auto negative = t;
  for (double& x : negative) x -= 1e-6;
  EXPECT_NE(message(negative, v).find("start of sliding"), std::string::npos);
}

}  // namespace
}  // namespace stengmc
