// Development harness for the inverse estimator (issue 11, milestone 1): simulates records
// in the regime with the forward model (n asperities of the known device with
// stiffnesses drawn from a lognormal law, Model 2, the circuit, white noise at a drawn SNR),
// inverts each with RecordEstimator (raw, uncalibrated), and prints n RMSE, the exact rate,
// the median-k error and the sd(ln k) RMSE, by n bin and SNR bin. Not a test: a measuring
// tool whose figures go in the commit messages and the README's development notes.
//
//   inverse_harness [records] [seed] [belt_velocity_m_per_s]
#include <omp.h>

#include <algorithm>
#include <boost/random/lognormal_distribution.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_int_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "core/random_stream.hpp"
#include "inverse/atom_table.hpp"
#include "inverse/forward_atom.hpp"
#include "inverse/record_estimator.hpp"
#include "inverse/sample_statistics.hpp"
#include "inverse/simulated_record.hpp"

using namespace stengmc;

namespace {

struct Outcome {
  int n = 0;
  double snr_db = 0.0;
  std::size_t n_hat = 0;
  double median_true = 0.0, median_hat = 0.0;
  double sd_true = 0.0, sd_hat = 0.0;
  double seconds = 0.0;
  double simulate_seconds = 0.0;
  bool valid = false;
};

void report(const char* label, const std::vector<Outcome>& all, bool (*keep)(const Outcome&)) {
  double se = 0.0, sd_se = 0.0;
  int exact = 0, count = 0, sd_count = 0;
  std::vector<double> median_errors;
  for (const Outcome& o : all) {
    if (!o.valid || !keep(o)) continue;
    ++count;
    const double e = static_cast<double>(o.n_hat) - o.n;
    se += e * e;
    exact += e == 0.0;
    median_errors.push_back(std::abs(o.median_hat / o.median_true - 1.0));
    if (o.n >= 2 && o.n_hat >= 2) {
      sd_se += (o.sd_hat - o.sd_true) * (o.sd_hat - o.sd_true);
      ++sd_count;
    }
  }
  if (count == 0) return;
  std::printf("%-12s %5d  n RMSE %6.3f  exact %5.1f %%  median-k |rel err| median %.4f  sd(ln k) RMSE %.4f\n", label, count,
              std::sqrt(se / count), 100.0 * exact / count, sample_median(median_errors),
              sd_count ? std::sqrt(sd_se / sd_count) : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  const int records = argc > 1 ? std::atoi(argv[1]) : 200;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  KnownDevice device;
  device.model.belt_velocity_m_per_s = argc > 3 ? std::atof(argv[3]) : 10.0;
  device.asperity.element.length_m = 50e-6;  // the regime; everything else Table 1-2
  const RecordGrid grid{0.0, 1e-8, 10001};
  InversePrior prior;  // n 1..16, lognormal median U(40, 120), sigma_log U(0.2, 0.6), SNR U(20, 40)
  const auto [k_low, k_high] = prior.support();
  const auto t0 = std::chrono::steady_clock::now();
  const double k_valid = smallest_valid_stiffness(device, grid.duration_s(), grid.step_s, k_low / 1.25, k_high * 1.25);
  const AtomTable atoms(device, grid, std::max(k_low / 1.25, k_valid), k_high * 1.25);
  std::printf("atom table [%.3g, %.3g] N/m built in %.2f s, check error %.3g\n", atoms.min_stiffness(), atoms.max_stiffness(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), atoms.data().check_error);

  std::vector<Outcome> outcomes(static_cast<std::size_t>(records));
  const auto start = std::chrono::steady_clock::now();
#pragma omp parallel
  {
    RecordEstimator estimator(atoms, prior);
#pragma omp for schedule(dynamic, 1)
    for (int r = 0; r < records; ++r) {
      // Every draw of record r from its own stream: the outcome does not depend on threads.
      RandomEngine engine = random_stream(seed, static_cast<std::uint64_t>(r), StreamKind::noise);
      Outcome& o = outcomes[static_cast<std::size_t>(r)];
      o.n = boost::random::uniform_int_distribution<int>(static_cast<int>(prior.count_min), static_cast<int>(prior.count_max))(engine);
      const double median_k = boost::random::uniform_real_distribution<double>(prior.first[0], prior.first[1])(engine);
      const double sigma_log = boost::random::uniform_real_distribution<double>(prior.second[0], prior.second[1])(engine);
      o.snr_db = boost::random::uniform_real_distribution<double>(prior.snr_db[0], prior.snr_db[1])(engine);
      boost::random::lognormal_distribution<double> law(std::log(median_k), sigma_log);
      std::vector<double> k(static_cast<std::size_t>(o.n));
      for (double& x : k) x = law(engine);
      std::vector<double> v;
      const auto s0 = std::chrono::steady_clock::now();
      try {
        v = simulate_record(device, k, grid);
      } catch (const ModelError&) {
        continue;  // an asperity reached l: the forward model's invalid realisation
      }
      o.simulate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - s0).count();
      double mean = 0.0, var = 0.0;
      for (double x : v) mean += x / static_cast<double>(v.size());
      for (double x : v) var += (x - mean) * (x - mean) / static_cast<double>(v.size());
      boost::random::normal_distribution<double> noise(0.0, std::sqrt(var / std::pow(10.0, o.snr_db / 10.0)));
      for (double& x : v) x += noise(engine);
      const RecordEstimate e = estimator.estimate(v);
      o.n_hat = e.count;
      o.median_true = sample_median(k);
      o.median_hat = e.median_stiffness_n_per_m > 0 ? e.median_stiffness_n_per_m : 1.0;
      o.sd_true = sample_sd_log(k);
      o.sd_hat = e.sd_log_stiffness;
      o.seconds = e.seconds;
      o.valid = true;
      if (static_cast<double>(o.n_hat) != o.n)
#pragma omp critical
        std::printf("record %d: n %d -> %zu (SNR %.1f dB, median %.1f, sigma_log %.2f)\n", r, o.n, o.n_hat, o.snr_db, median_k, sigma_log);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double estimate_s = 0.0, simulate_s = 0.0;
  int valid = 0;
  for (const Outcome& o : outcomes)
    if (o.valid) estimate_s += o.seconds, simulate_s += o.simulate_seconds, ++valid;
  std::printf("%d records (%d valid), v_b = %g m/s, seed %llu: wall %.1f s; per record: simulation %.0f ms, estimation %.0f ms\n",
              records, valid, device.model.belt_velocity_m_per_s, static_cast<unsigned long long>(seed), wall,
              1e3 * simulate_s / valid, 1e3 * estimate_s / valid);
  report("all", outcomes, [](const Outcome&) { return true; });
  report("n 1-4", outcomes, [](const Outcome& o) { return o.n <= 4; });
  report("n 5-8", outcomes, [](const Outcome& o) { return o.n >= 5 && o.n <= 8; });
  report("n 9-12", outcomes, [](const Outcome& o) { return o.n >= 9 && o.n <= 12; });
  report("n 13-16", outcomes, [](const Outcome& o) { return o.n >= 13; });
  report("SNR 20-30", outcomes, [](const Outcome& o) { return o.snr_db < 30.0; });
  report("SNR 30-40", outcomes, [](const Outcome& o) { return o.snr_db >= 30.0; });
  return 0;
}
