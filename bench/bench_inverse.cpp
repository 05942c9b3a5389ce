// Inverse estimation's costs (issue 11's benchmark): prints medians itself.
//  1. `invert` after calibration on a 10^4-sample record (the regime: 100 us at
//     100 MHz, v_b = 10 m/s): the bank's atom table restored, then one record inverted (n = 1,
//     8, 16), median of 5 each; thread CPU time (what the machine's other load does not
//     inflate) and wall time. Target: <= 1 s.
//  2. A calibration bank of 10^4 records on 2 cores: per record, the forward simulation of a
//     prior realisation (run_study: tribology + circuit) and its estimation, measured on 30
//     records of the prior (n = 1..16), extrapolated as 10^4 x (simulation + estimation) / 2
//     (the ensemble runner's parallel efficiency on 2 threads is 99 %, README). Target: 15 min.
//
//   bench_inverse [records]
#include <time.h>

#include <algorithm>
#include <boost/random/lognormal_distribution.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_int_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/random_stream.hpp"
#include "inverse/atom_table.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/inversion.hpp"
#include "inverse/simulated_record.hpp"
#include "pipeline/study.hpp"

using namespace stengmc;

namespace {

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int records = argc > 1 ? std::atoi(argv[1]) : 30;
  const Study study = read_study(std::string(STENGMC_SOURCE_DIR) + "/studies/inverse/device_vb10.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(study);
  const auto [low, high] = atom_range(setup);
  double t0 = wall_now();
  const AtomTable built(setup.device, setup.grid, low, high);
  std::printf("atom table (part of a calibration, kept in the bank): %.2f s wall\n", wall_now() - t0);

  // 1. invert after calibration
  std::vector<double> restore_cpu;
  for (int r = 0; r < 5; ++r) {
    const double c0 = cpu_now();
    const AtomTable restored(setup.device, setup.grid, built.data());
    restore_cpu.push_back(cpu_now() - c0);
  }
  const AtomTable atoms(setup.device, setup.grid, built.data());
  std::printf("\n1. invert a 10^4-sample record after calibration (medians of 5; target 1 s):\n");
  std::printf("   restoring the bank's atom table: %.0f ms CPU\n", 1e3 * median(restore_cpu));
  RandomEngine engine = random_stream(7, 0, StreamKind::noise);
  for (int n : {1, 8, 16}) {
    boost::random::lognormal_distribution<double> law(std::log(80.0), 0.4);
    std::vector<double> k(static_cast<std::size_t>(n));
    for (double& x : k) x = law(engine);
    std::vector<double> v = simulate_record(setup.device, k, setup.grid);
    boost::random::normal_distribution<double> noise(0.0, 3e-4);
    for (double& x : v) x += noise(engine);
    std::vector<double> cpu, wall;
    Inverter inverter(setup, atoms, nullptr);
    for (int r = 0; r < 5; ++r) {
      const double c0 = cpu_now(), w0 = wall_now();
      const Inversion result = inverter.invert("bench", v);
      cpu.push_back(cpu_now() - c0);
      wall.push_back(wall_now() - w0);
      if (result.calibrated.count != static_cast<std::size_t>(n)) std::printf("   (n = %d counted %zu)\n", n, result.calibrated.count);
    }
    std::printf("   n = %2d: %.0f ms CPU, %.0f ms wall; with the table's restore %.2f s of the 1 s target\n", n, 1e3 * median(cpu),
                1e3 * median(wall), median(cpu) + median(restore_cpu));
  }

  // 2. calibration bank of 10^4 records
  std::vector<double> simulation, estimation;
  RecordEstimator estimator(atoms, setup.prior);
  for (int r = 0; r < records; ++r) {
    RandomEngine e = random_stream(8, static_cast<std::uint64_t>(r), StreamKind::noise);
    const int n = boost::random::uniform_int_distribution<int>(1, 16)(e);
    const double median_k = boost::random::uniform_real_distribution<double>(40, 120)(e);
    const double sigma_log = boost::random::uniform_real_distribution<double>(0.2, 0.6)(e);
    boost::random::lognormal_distribution<double> law(std::log(median_k), sigma_log);
    std::vector<double> k(static_cast<std::size_t>(n));
    for (double& x : k) x = law(e);
    double c0 = cpu_now();
    std::vector<double> v;
    try {
      v = simulate_record(setup.device, k, setup.grid);
    } catch (const std::exception&) {
      continue;
    }
    simulation.push_back(cpu_now() - c0);
    const double snr = boost::random::uniform_real_distribution<double>(20, 40)(e);
    double mean = 0, var = 0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    for (double x : v) var += (x - mean) * (x - mean) / static_cast<double>(v.size());
    boost::random::normal_distribution<double> noise(0.0, std::sqrt(var / std::pow(10.0, snr / 10.0)));
    for (double& x : v) x += noise(e);
    c0 = cpu_now();
    (void)estimator.estimate(v);
    estimation.push_back(cpu_now() - c0);
  }
  double sim = 0, est = 0;
  for (double s : simulation) sim += s / static_cast<double>(simulation.size());
  for (double s : estimation) est += s / static_cast<double>(estimation.size());
  std::printf("\n2. a calibration bank of 10^4 records on 2 cores (means over %zu records of the prior; target 15 min):\n",
              simulation.size());
  std::printf("   per record: forward simulation %.0f ms CPU, estimation %.0f ms CPU (%s dominates)\n", 1e3 * sim, 1e3 * est,
              sim > est ? "the simulation" : "the estimation");
  std::printf("   10^4 records / 2 cores: %.1f min (simulation %.1f, estimation %.1f) + the atom table\n",
              1e4 * (sim + est) / 2.0 / 60.0, 1e4 * sim / 2.0 / 60.0, 1e4 * est / 2.0 / 60.0);
  return 0;
}
