// Ensemble throughput benchmark (not a micro-benchmark: prints medians and ratios itself).
// A random surface with a fixed count of asperities (surfaces/lognormal_count.toml, its
// count rewritten), Model 2, v_b = 10 m/s, 100 MHz, FFT spectra only, run by run_ensemble:
//   1. parallel efficiency at 2 threads: T1 / (2 T2) on the same ensemble, medians of 3;
//   2. the headline: 1000 realisations x 20 asperities x 50 us on 2 threads
//      (--quick or STENGMC_BENCH_QUICK=1: 100 realisations, extrapolated x10);
//   3. cost growth: time per realisation against the asperity count and the duration,
//      with fitted log-log slopes;
// and where one realisation's time goes (draw, tribology, circuit, spectra, record).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "bench_support.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/run_realisation.hpp"
#include "pipeline/study_realisation.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"

#ifndef STENGMC_BUILD_TYPE
#define STENGMC_BUILD_TYPE "unknown"
#endif

namespace {

namespace fs = std::filesystem;
using bench::Clock;
using bench::loglog_slope;
using bench::machine_busy_seconds;
using bench::median;

constexpr int REPETITIONS = 3;
constexpr double HEADLINE_TARGET_S = 10.0;
constexpr double EFFICIENCY_TARGET = 0.85;

struct Timing {
  double wall_s = 0.0;  //!< wall time of run_ensemble
  double cpu_s = 0.0;   //!< process CPU time over it (all threads)
  double others_s = 0.0;  //!< CPU time other processes took meanwhile (machine busy - ours) [s]
  std::size_t records = 0;
  std::size_t valid = 0;
  double mean_asperities = 0.0;  //!< mean asperity_count over the records
};

//! One run_ensemble from scratch (the journal is removed before and after: a leftover
//! journal would be resumed and the run would do nothing).
Timing run_once(const stengmc::StudyFile& study, const fs::path& scratch, int threads) {
  const fs::path journal = scratch / "journal.bin";
  fs::remove(journal);
  const double busy0 = machine_busy_seconds();
  const std::clock_t cpu0 = std::clock();
  const auto start = Clock::now();
  const stengmc::EnsembleRun run =
      stengmc::run_ensemble(study, journal.string(), stengmc::EnsembleOptions{.threads = threads, .show_progress = false});
  Timing t;
  t.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  t.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  t.others_s = std::max(0.0, machine_busy_seconds() - busy0 - t.cpu_s);
  fs::remove(journal);
  if (run.resumed != 0) throw std::runtime_error("a journal was resumed: the timing is meaningless");
  t.records = run.records.size();
  double asperities = 0.0;
  for (const stengmc::RealisationRecord& r : run.records) {
    t.valid += r.valid ? 1 : 0;
    asperities += r.scalar(stengmc::Scalar::asperity_count);
  }
  t.mean_asperities = t.records ? asperities / static_cast<double>(t.records) : 0.0;
  return t;
}

//! Median wall time of `repetitions` runs (and the last run's counts).
Timing run_median(const stengmc::StudyFile& study, const fs::path& scratch, int threads, int repetitions) {
  std::vector<double> wall, cpu, others;
  Timing last;
  for (int r = 0; r < repetitions; ++r) {
    last = run_once(study, scratch, threads);
    wall.push_back(last.wall_s);
    cpu.push_back(last.cpu_s);
    others.push_back(last.others_s);
  }
  last.wall_s = median(wall);
  last.cpu_s = median(cpu);
  last.others_s = median(others);
  return last;
}

bool quick_requested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--quick") return true;
  const char* env = std::getenv("STENGMC_BENCH_QUICK");
  return env && *env && std::string(env) != "0";
}

}  // namespace

int main(int argc, char** argv) try {
  const bool quick = quick_requested(argc, argv);
  const auto program_start = Clock::now();
  const unsigned cores = std::thread::hardware_concurrency();
  bench::ScratchDir scratch("bench_ensemble");
  const bench::StudyFactory factory(STENGMC_SOURCE_DIR, scratch.path);

  std::printf("Ensemble benchmark: lognormal_count surface (fixed count n), Model 2, v_b = 10 m/s, 100 MHz,\n"
              "FFT spectra only (Hann, no ESPRIT), domain policy flag; run_ensemble without progress.\n");
  std::printf("Machine: %u hardware threads; build type %s; compiler %s; OpenMP max threads %d\n\n", cores,
              STENGMC_BUILD_TYPE, __VERSION__, omp_get_max_threads());

  // Warm-up: page faults, FFTW plans, allocator pools.
  run_once(factory.make(20, 50e-6, 4), scratch.path, 2);

  // 1. Parallel efficiency.
  constexpr std::uint64_t EFF_REALISATIONS = 40;
  const stengmc::StudyFile eff_study = factory.make(20, 50e-6, EFF_REALISATIONS);
  std::vector<double> t1s, t2s, c1s, c2s, o2s;
  for (int r = 0; r < REPETITIONS; ++r) {  // interleaved, so drift hits both alike
    const Timing one = run_once(eff_study, scratch.path, 1);
    const Timing two = run_once(eff_study, scratch.path, 2);
    t1s.push_back(one.wall_s);
    c1s.push_back(one.cpu_s);
    t2s.push_back(two.wall_s);
    c2s.push_back(two.cpu_s);
    o2s.push_back(two.others_s / (cores * two.wall_s));
  }
  const double t1 = median(t1s), t2 = median(t2s);
  const double efficiency = t1 / (2.0 * t2);
  std::printf("1. Parallel efficiency (%llu realisations x n = 20 x 50 us, median of %d)\n",
              static_cast<unsigned long long>(EFF_REALISATIONS), REPETITIONS);
  std::printf("   T1 = %.2f s, T2 = %.2f s, speed-up %.2f, efficiency T1/(2 T2) = %.1f %% (target >= %.0f %%: %s)\n", t1,
              t2, t1 / t2, 100.0 * efficiency, 100.0 * EFFICIENCY_TARGET,
              efficiency >= EFFICIENCY_TARGET ? "met" : "MISSED");
  std::printf("   CPU: %.2f s at 1 thread, %.2f s at 2 (x%.2f: per-realisation cost under sharing); 2 threads busy\n"
              "   %.0f %% of the wall time; other processes took %.0f %% of the machine meanwhile\n\n",
              median(c1s), median(c2s), median(c2s) / median(c1s), 100 * median(c2s) / (2 * t2), 100 * median(o2s));

  // 2. Headline.
  const std::uint64_t headline_realisations = quick ? 100 : 1000;
  const double scale = 1000.0 / static_cast<double>(headline_realisations);
  const Timing head = run_once(factory.make(20, 50e-6, headline_realisations), scratch.path, 2);
  const double head_total = head.wall_s * scale;
  std::printf("2. Headline: 1000 realisations x n = 20 x 50 us, 2 threads%s\n",
              quick ? " (--quick: 100 run, extrapolated x10)" : "");
  std::printf("   wall %.1f s (/ %.0f s target = %.2f: %s); CPU %.1f s, %.1f ms CPU per realisation;\n"
              "   %zu of %zu realisations valid, mean %.1f asperities simulated; other processes took %.0f %% of the machine\n\n",
              head_total, HEADLINE_TARGET_S, head_total / HEADLINE_TARGET_S,
              head_total <= HEADLINE_TARGET_S ? "met" : "MISSED", head.cpu_s * scale,
              1e3 * head.cpu_s / static_cast<double>(head.records), head.valid, head.records, head.mean_asperities,
              100 * head.others_s / (cores * head.wall_s));

  // 3. Cost growth.
  constexpr std::uint64_t GROWTH_REALISATIONS = 20;
  std::printf("3. Cost growth: wall time per realisation, 2 threads, %llu realisations, median of %d\n",
              static_cast<unsigned long long>(GROWTH_REALISATIONS), REPETITIONS);
  std::printf("   %-6s %-10s %14s %14s %10s %8s\n", "n", "duration", "ms / real.", "CPU ms / real.", "valid", "others");
  const std::vector<int> counts{1, 2, 4, 8, 16, 32, 64};
  std::vector<double> n_x, n_y;
  for (int n : counts) {
    const Timing t = run_median(factory.make(n, 50e-6, GROWTH_REALISATIONS), scratch.path, 2, REPETITIONS);
    const double per = t.wall_s / static_cast<double>(GROWTH_REALISATIONS);
    n_x.push_back(t.mean_asperities > 0 ? t.mean_asperities : n);
    n_y.push_back(per);
    std::printf("   %-6d %-10s %14.2f %14.2f %5zu/%zu %7.0f%%\n", n, "50 us", 1e3 * per,
                1e3 * t.cpu_s / static_cast<double>(GROWTH_REALISATIONS), t.valid, t.records,
                100 * t.others_s / (cores * t.wall_s));
  }
  const std::vector<double> durations{10e-6, 25e-6, 50e-6, 100e-6};
  std::vector<double> d_x, d_y;
  for (double d : durations) {
    const Timing t = run_median(factory.make(20, d, GROWTH_REALISATIONS), scratch.path, 2, REPETITIONS);
    const double per = t.wall_s / static_cast<double>(GROWTH_REALISATIONS);
    d_x.push_back(d);
    d_y.push_back(per);
    char label[16];
    std::snprintf(label, sizeof label, "%g us", 1e6 * d);
    std::printf("   %-6d %-10s %14.2f %14.2f %5zu/%zu %7.0f%%\n", 20, label, 1e3 * per,
                1e3 * t.cpu_s / static_cast<double>(GROWTH_REALISATIONS), t.valid, t.records,
                100 * t.others_s / (cores * t.wall_s));
  }
  const double slope_n = loglog_slope(n_x, n_y);
  const double slope_n_upper = loglog_slope(std::vector<double>(n_x.begin() + 3, n_x.end()),
                                            std::vector<double>(n_y.begin() + 3, n_y.end()));
  const double slope_d = loglog_slope(d_x, d_y);
  std::printf("   ('others': share of the machine other processes took during the runs; high values distort the timing)\n");
  std::printf("   log-log slope: cost ~ n^%.2f over n = 1..64 (n^%.2f over n = 8..64); cost ~ T^%.2f over T = 10..100 us\n\n",
              slope_n, slope_n_upper, slope_d);

  // Where one realisation's time goes: n = 20, 50 us, one thread, realisations 0..9.
  constexpr std::uint64_t STAGE_REALISATIONS = 10;
  const stengmc::StudyFile base = factory.make(20, 50e-6, STAGE_REALISATIONS);
  double draw = 0, trib = 0, circ = 0, spec = 0, run_total = 0, realisation_total = 0;
  std::size_t ran = 0;
  for (std::uint64_t id = 0; id < STAGE_REALISATIONS; ++id) {
    try {
      const auto a = Clock::now();
      const stengmc::Study study = stengmc::study_for_realisation(base, id);
      const auto b = Clock::now();
      const stengmc::RunResult result =
          stengmc::run_study(study, stengmc::RunOptions{.show_progress = false, .keep_traces = false});
      const auto c = Clock::now();
      stengmc::run_realisation(base, id, false);
      const auto d = Clock::now();
      draw += std::chrono::duration<double>(b - a).count();
      run_total += std::chrono::duration<double>(c - b).count();
      realisation_total += std::chrono::duration<double>(d - c).count();
      trib += result.tribology_seconds;
      circ += result.circuit_seconds;
      spec += result.spectrum_seconds;
      ++ran;
    } catch (const std::exception& e) {
      std::printf("   (realisation %llu skipped: %s)\n", static_cast<unsigned long long>(id), e.what());
    }
  }
  const double k = ran ? 1e3 / static_cast<double>(ran) : 0.0;
  const double other = run_total - trib - circ - spec;
  const double reduce = realisation_total - draw - run_total;
  std::printf("Stages of one realisation (n = 20, 50 us, one thread, mean of %zu): ms and share of run_realisation\n", ran);
  std::printf("   draw %.2f (%.0f %%) | tribology %.2f (%.0f %%) | circuit %.2f (%.0f %%) | spectra %.2f (%.0f %%) |\n"
              "   rest of run_study (domain check, etc.) %.2f (%.0f %%) | record (summary) %.2f (%.0f %%) | run_realisation %.2f\n\n",
              k * draw, 100 * draw / realisation_total, k * trib, 100 * trib / realisation_total, k * circ,
              100 * circ / realisation_total, k * spec, 100 * spec / realisation_total, k * other, 100 * other / realisation_total,
              k * reduce, 100 * reduce / realisation_total, k * realisation_total);

  // README table.
  std::printf("README table (%u hardware threads, %s build):\n\n", cores, STENGMC_BUILD_TYPE);
  std::printf("| measure | value | target |\n|---|---|---|\n");
  std::printf("| parallel efficiency, 2 threads (40 x n = 20 x 50 us) | %.0f %% (T1 %.2f s, T2 %.2f s) | >= 85 %% |\n",
              100 * efficiency, t1, t2);
  std::printf("| 1000 realisations x n = 20 x 50 us, 2 threads | %.1f s wall%s, %.0f ms CPU / realisation | <= 10 s |\n",
              head_total, quick ? " (extrapolated from 100)" : "", 1e3 * head.cpu_s / static_cast<double>(head.records));
  std::printf("| cost vs asperity count n (1..64, 50 us) | ~ n^%.2f (n^%.2f for n >= 8); %.1f ms at n = 1, %.1f ms at n = 64 | |\n",
              slope_n, slope_n_upper, 1e3 * n_y.front(), 1e3 * n_y.back());
  std::printf("| cost vs duration T (10..100 us, n = 20) | ~ T^%.2f; %.1f ms at 10 us, %.1f ms at 100 us | |\n", slope_d,
              1e3 * d_y.front(), 1e3 * d_y.back());
  std::printf("| stages (n = 20, 50 us, 1 thread) | tribology %.0f %%, circuit %.0f %%, spectra %.0f %%, other %.0f %% | |\n",
              100 * trib / realisation_total, 100 * circ / realisation_total, 100 * spec / realisation_total,
              100 * (realisation_total - trib - circ - spec) / realisation_total);
  std::printf("\nTotal benchmark time %.0f s\n",
              std::chrono::duration<double>(Clock::now() - program_start).count());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_ensemble: %s\n", e.what());
  return 1;
}
