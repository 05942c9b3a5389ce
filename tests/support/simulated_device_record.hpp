#pragma once
// A study run by the project's forward model and read as a known device's noisy record: what the
// tests of the record readers (tracking, onset steps) start from. One copy, so that each test
// says only which asperities and which noise.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/study.hpp"

namespace stengmc::testing {

struct Simulated {
  KnownDevice device;
  RecordGrid grid;
  std::vector<double> voltage;
  double noise_sigma_v = 0.0;  //!< the white noise added
};

//! The study `text` run, plus white noise of SNR `snr_db` over the mean-removed clean voltage
//! (drawn here, seeded: the test is the same every run).
inline Simulated simulate(const std::string& text, double snr_db = 25.0, unsigned seed = 3) {
  const Study study = parse_study(text, "simulated_record_test.toml");
  RunOptions options;
  options.show_progress = false;
  options.keep_traces = false;
  const RunResult run = run_study(study, options);
  Simulated s{known_device_from_study(study), {run.times_s.front(), run.times_s[1] - run.times_s[0], run.times_s.size()},
              run.circuit.voltage_v};
  double mean = 0.0, power = 0.0;
  for (double v : s.voltage) mean += v / static_cast<double>(s.voltage.size());
  for (double v : s.voltage) power += (v - mean) * (v - mean) / static_cast<double>(s.voltage.size());
  std::mt19937_64 rng(seed);
  s.noise_sigma_v = std::sqrt(power / std::pow(10.0, snr_db / 10.0));
  std::normal_distribution<double> normal(0.0, s.noise_sigma_v);
  for (double& v : s.voltage) v += normal(rng);
  return s;
}

}  // namespace stengmc::testing
