// Inverse estimation's costs (issues 11 and 23): prints medians and means itself.
//  1. `invert` after calibration on a 10^4-sample record (100 us at 100 MHz, v_b = 10 m/s,
//     studies/inverse/device_vb10.toml): the bank's atom shapes restored, then one record
//     inverted (n = 1, 8, 16), median of 3 each; thread CPU time. Target (issue 23): <= 1 s.
//  2. A calibration record, exactly as `calibrate` makes one (the prior study's realisation
//     simulated by the ensemble runner, then estimated), for the ideal prior of device_vb10.toml
//     and the broadened prior of device_vb10_real.toml: mean CPU per record, simulation and
//     estimation apart, and the estimation's ratio to the simulation measured in the same
//     process. Target (issue 23): <= 150 ms per record.
//
//   bench_inverse [records per prior]    (default 12)
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ensemble/run_realisation.hpp"
#include "ensemble/study_file.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/inversion.hpp"
#include "inverse/prior_study.hpp"
#include "inverse/record_estimator.hpp"
#include "inverse/simulated_record.hpp"
#include "pipeline/study.hpp"

using namespace stengmc;

namespace {

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

Study device_study(const char* name) {
  return read_study(std::string(STENGMC_SOURCE_DIR) + "/studies/inverse/" + name, std::nullopt);
}

void invert_once(std::size_t records) {
  (void)records;
  const InverseSetup setup = inverse_setup(device_study("device_vb10.toml"));
  const std::unique_ptr<AtomLibrary> built = build_atom_library(setup);
  std::vector<double> restore_cpu;
  for (int r = 0; r < 3; ++r) {
    const double c0 = cpu_now();
    (void)build_atom_library(setup, built->shapes().data());
    restore_cpu.push_back(cpu_now() - c0);
  }
  std::printf("1. invert a 10^4-sample record after calibration (medians of 3; target 1 s):\n");
  std::printf("   restoring the bank's atom shapes: %.0f ms CPU\n", 1e3 * median(restore_cpu));
  Inverter inverter(setup, *built, nullptr);
  for (int n : {1, 8, 16}) {
    // Stiffnesses spread over the prior's central band, deterministic.
    std::vector<double> k(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) k[static_cast<std::size_t>(i)] = 50.0 * std::pow(3.0, (i + 0.5) / n);
    std::vector<double> v = simulate_record(setup.device, k, setup.grid);
    for (std::size_t j = 0; j < v.size(); ++j) v[j] += 3e-4 * std::sin(0.7 * static_cast<double>(j * j % 1009));
    std::vector<double> cpu;
    std::size_t counted = 0;
    for (int r = 0; r < 3; ++r) {
      const double c0 = cpu_now();
      counted = inverter.invert("bench", v).calibrated.count;
      cpu.push_back(cpu_now() - c0);
    }
    std::printf("   n = %2d: %.0f ms CPU (counted %zu); with the restore %.2f s of the 1 s target\n", n, 1e3 * median(cpu), counted,
                median(cpu) + median(restore_cpu));
  }
}

void calibration_records(const char* name, std::size_t records) {
  const InverseSetup setup = inverse_setup(device_study(name));
  const std::unique_ptr<AtomLibrary> atoms = build_atom_library(setup);
  const std::string text = prior_study_text(setup.device, setup.prior, records, 8, 1e5, 1e7, one_asperity_rms_v(*atoms, setup.prior));
  const StudyFile prior = parse_study_file(text, "bench prior", std::nullopt);
  RecordEstimator estimator(*atoms, setup.prior);
  std::vector<double> simulation, estimation;
  for (std::size_t r = 0; r < records; ++r) {
    double c0 = cpu_now();
    const RealisationRecord record = run_realisation(prior, r, true);
    if (!record.valid) continue;
    simulation.push_back(cpu_now() - c0);
    c0 = cpu_now();
    (void)estimator.estimate(record.measured_voltage_v);
    estimation.push_back(cpu_now() - c0);
  }
  double sim = 0, est = 0;
  for (double s : simulation) sim += s / static_cast<double>(simulation.size());
  for (double s : estimation) est += s / static_cast<double>(estimation.size());
  std::printf("   %-22s %2zu records: simulation %5.0f ms, estimation %6.0f ms (median %6.0f) CPU per record; "
              "estimation / simulation %.1f; a bank of 2000 on 2 cores %.0f min\n",
              name, simulation.size(), 1e3 * sim, 1e3 * est, 1e3 * median(estimation), est / sim, 2000 * (sim + est) / 2.0 / 60.0);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t records = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 12;
  invert_once(records);
  std::printf("\n2. calibration records of each prior (means; target 150 ms per record):\n");
  calibration_records("device_vb10.toml", records);
  calibration_records("device_vb10_real.toml", records);
  return 0;
}
