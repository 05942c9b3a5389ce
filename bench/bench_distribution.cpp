// What distributing an ensemble costs (issue 13; README "Ensembles", docs/cluster.md).
// Not a micro-benchmark: prints medians and ratios itself.
//   1. the cost of a realisation and its spread, on one thread: the quick identifiability
//      sweep (studies/ensembles/identifiability_quick.toml, 4 realisations of each of its 12
//      grid points; costs differ by ~10x between 1 and 32 asperities) and the count study
//      (identifiability_vs_count.toml, 1 of each of its 28 points, 1 to 64 asperities);
//   2. the serial work of rank 0 per record in an MPI run (decode the frame a worker sent,
//      append it durably to the journal: one write and one fsync), on synthetic records of
//      the measured mean size: 10^5 decodes in memory, 2000 journal appends (scaled);
//   3. the merge of shard files: 10^5 synthetic records written as 8 shard files, read
//      back and checked;
//   4. the scaling model (README): efficiency at 64, 1024 and 16384 ranks from 1-2.
// The MPI throughput (P = 1, 2 ranks x 1 thread, 1 rank x 2 threads) is bench/bench_mpi.sh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <tuple>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "ensemble/journal.hpp"
#include "ensemble/run_realisation.hpp"
#include "ensemble/shard.hpp"
#include "ensemble/sweep.hpp"
#include "pipeline/study.hpp"

namespace {

using bench::Clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

//! A record of `asperities` asperities with random contents (the size is what costs).
stengmc::RealisationRecord synthetic_record(std::uint64_t id, std::size_t asperities, std::mt19937_64& engine) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  stengmc::RealisationRecord r;
  r.realisation = id;
  for (double& s : r.scalars) s = u(engine);
  for (auto& column : r.asperities) {
    column.resize(asperities);
    for (double& v : column) v = u(engine);
  }
  return r;
}

struct Cost {
  double mean_s = 0, median_s = 0, cv = 0, max_over_min = 0;
  double mean_asperities = 0;
};

//! `per_point` realisations of every grid point of a shipped study, one thread.
Cost measure_realisations(const std::string& study, std::uint64_t per_point) {
  const stengmc::StudyFile base = stengmc::read_study_file(std::string(STENGMC_SOURCE_DIR) + "/studies/ensembles/" + study,
                                                  std::nullopt);
  const std::vector<stengmc::GridPoint> grid = stengmc::prepare_grid(base);
  std::vector<double> times;
  double asperities = 0;
  for (const stengmc::GridPoint& point : grid)
    for (std::uint64_t r = 0; r < per_point; ++r) {
      const auto start = Clock::now();
      const stengmc::RealisationRecord record = stengmc::run_realisation(point.study, r, false);
      times.push_back(seconds_since(start));
      asperities += static_cast<double>(record.asperity_count());
    }
  Cost c;
  const double n = static_cast<double>(times.size());
  for (double t : times) c.mean_s += t / n;
  double variance = 0;
  for (double t : times) variance += (t - c.mean_s) * (t - c.mean_s) / (n - 1);
  c.cv = std::sqrt(variance) / c.mean_s;
  c.median_s = bench::median(times);
  c.max_over_min = *std::max_element(times.begin(), times.end()) / *std::min_element(times.begin(), times.end());
  c.mean_asperities = asperities / n;
  return c;
}

//! Efficiency of P ranks on `points` grid points of `per_point` realisations each: rank 0
//! hands out one realisation at a time, so within a point the ranks stay busy until the
//! queue runs dry; then the last realisations finish (on average half a realisation's
//! time, stretched by the spread: c (1 + cv^2) / 2, the mean residual of a renewal
//! process), and the next point starts when the last one has. With fewer realisations
//! than ranks the point lasts about its longest realisation (c (1 + 2 cv)). Rank 0
//! absorbs records serially at g each: the point cannot take less than per_point * g.
double efficiency(double ranks, double points, double per_point, const Cost& c, double g) {
  const double busy = per_point >= ranks ? per_point * c.mean_s / ranks : c.mean_s * (1.0 + 2.0 * c.cv);
  const double point_time = std::max(busy, per_point * g) + c.mean_s * (1.0 + c.cv * c.cv) / 2.0;
  return points * per_point * c.mean_s / (ranks * points * point_time);
}

}  // namespace

int main() {
  bench::ScratchDir scratch("distribution");
  std::printf("stengmc distribution benchmark (one thread; medians where repeated)\n\n");

  const Cost cost = measure_realisations("identifiability_quick.toml", 4);
  const Cost count_cost = measure_realisations("identifiability_vs_count.toml", 1);
  for (const auto& [name, c] : {std::pair{"identifiability_quick (4 of each of its 12 grid points)", cost},
                                std::pair{"identifiability_vs_count (1 of each of its 28 grid points)", count_cost}})
    std::printf("1. realisation cost, %s, 1 thread:\n"
                "   mean %.1f ms, median %.1f ms, coefficient of variation %.2f, slowest / fastest %.1f; mean %.1f "
                "asperities per record\n",
                name, 1e3 * c.mean_s, 1e3 * c.median_s, c.cv, c.max_over_min, c.mean_asperities);
  std::printf("\n");

  const auto asperities = static_cast<std::size_t>(std::lround(std::max(1.0, cost.mean_asperities)));
  constexpr std::size_t RECORDS = 100'000;
  std::mt19937_64 engine(1);
  std::vector<stengmc::RealisationRecord> records;
  records.reserve(RECORDS);
  for (std::size_t i = 0; i < RECORDS; ++i) records.push_back(synthetic_record(i, asperities, engine));

  // 2. Rank 0's serial work per record: decode (the worker encoded in parallel) + journal.
  std::vector<std::string> frames;
  frames.reserve(RECORDS);
  auto start = Clock::now();
  for (const auto& r : records) frames.push_back(stengmc::encode_record_frame(r, "bench"));
  const double encode_s = seconds_since(start) / RECORDS;
  start = Clock::now();
  std::size_t checksum = 0;
  for (const std::string& f : frames) checksum += stengmc::decode_record_frame(f, "bench").asperity_count();
  const double decode_s = seconds_since(start) / RECORDS;
  // Journal appends in the working folder, where outputs and their journals go (/tmp may
  // be a tmpfs, whose fsync costs nothing): one record per fsync (a lightly loaded rank 0),
  // and groups of 64 (rank 0 journals what arrived together: a loaded rank 0).
  constexpr std::size_t APPENDS = 2000, GROUP = 64;
  std::vector<std::vector<stengmc::RealisationRecord>> groups;
  for (std::size_t i = 0; i < APPENDS; i += GROUP)
    groups.emplace_back(records.begin() + static_cast<long>(i), records.begin() + static_cast<long>(i + GROUP));
  std::vector<double> single_rounds, group_rounds;
  for (int round = 0; round < 3; ++round) {
    const std::string path = (std::filesystem::current_path() / ("bench_distribution.journal" + std::to_string(round))).string();
    {
      stengmc::Journal journal(path, {1, "bench"});
      start = Clock::now();
      for (std::size_t i = 0; i < APPENDS; ++i) journal.append(records[i]);
      single_rounds.push_back(seconds_since(start) / APPENDS);
      journal.remove();
    }
    stengmc::Journal journal(path, {1, "bench"});
    start = Clock::now();
    for (const auto& group : groups) journal.append(group);
    group_rounds.push_back(seconds_since(start) / static_cast<double>(groups.size() * GROUP));
    journal.remove();
  }
  const double append_single_s = bench::median(single_rounds), append_group_s = bench::median(group_rounds);
  const double gather_s = decode_s + append_group_s;
  std::printf("2. rank 0 per record (%zu asperities, %zu bytes a frame): decode %.2f us (10^5 records); journal append "
              "%.1f us alone (one fsync each), %.1f us in groups of %zu (median of 3 x %zu); the workers encode in "
              "parallel: %.2f us\n",
              asperities, frames.front().size(), 1e6 * decode_s, 1e6 * append_single_s, 1e6 * append_group_s, GROUP,
              APPENDS, 1e6 * encode_s);
  for (const auto& [name, c] : {std::pair{"identifiability_quick", cost}, std::pair{"identifiability_vs_count", count_cost}})
    std::printf("   gather of 10^5 records on rank 0 (decode + grouped journal): %.2f s against %.0f s of %s compute: "
                "%.3f %% (required < 2 %%); with one fsync per record: %.3f %%\n",
                gather_s * RECORDS, c.mean_s * RECORDS, name, 100.0 * gather_s / c.mean_s,
                100.0 * (decode_s + append_single_s) / c.mean_s);
  std::printf("\n");

  // 3. Merging shard files: 8 files of 12 500 records, written and read back.
  constexpr int SHARDS = 8;
  start = Clock::now();
  for (int s = 0; s < SHARDS; ++s) {
    const std::vector<stengmc::RealisationRecord> part(records.begin() + s * (RECORDS / SHARDS),
                                                       records.begin() + (s + 1) * (RECORDS / SHARDS));
    stengmc::write_journal_file((scratch.path / ("shard" + std::to_string(s))).string(), {2, "bench shard"}, part);
  }
  const double write_shards_s = seconds_since(start);
  start = Clock::now();
  for (int s = 0; s < SHARDS; ++s)
    checksum += stengmc::read_journal_file((scratch.path / ("shard" + std::to_string(s))).string(), "bench shard", "")
                    .records.size();
  const double read_shards_s = seconds_since(start);
  std::printf("3. shards: writing 10^5 records as %d shard files %.2f s (in parallel on the array's nodes), reading "
              "them back in merge %.2f s: %.3f %% of the compute\n\n",
              SHARDS, write_shards_s, read_shards_s, 100.0 * read_shards_s / (cost.mean_s * RECORDS));

  std::printf("4. scaling model (README, \"Ensembles\"): efficiency = compute / (ranks x wall), g = %.1f us per "
              "record on rank 0 (grouped journal)\n",
              1e6 * gather_s);
  for (const auto& [name, c] : {std::pair{"identifiability_quick", cost}, std::pair{"identifiability_vs_count", count_cost}}) {
    std::printf("   %s realisations (c = %.1f ms, cv = %.2f): rank 0 saturates at c / g = %.0f ranks\n", name,
                1e3 * c.mean_s, c.cv, c.mean_s / gather_s);
    std::printf("   %-32s %10s %10s %10s\n", "10^5 realisations as", "64 ranks", "1024", "16384");
    for (const auto& [label, points, per_point] :
         {std::tuple{"one ensemble of 10^5", 1.0, 1e5}, std::tuple{"100 grid points x 1000", 100.0, 1000.0},
          std::tuple{"1000 grid points x 100", 1000.0, 100.0}})
      std::printf("   %-32s %9.1f%% %9.1f%% %9.1f%%\n", label, 100 * efficiency(64, points, per_point, c, gather_s),
                  100 * efficiency(1024, points, per_point, c, gather_s), 100 * efficiency(16384, points, per_point, c, gather_s));
  }
  std::printf("(checksum %zu)\n", checksum);
  return 0;
}
