#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "core/error.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/ensemble_summary.hpp"
#include "ensemble/process_world.hpp"
#include "ensemble/shard.hpp"
#include "ensemble/sweep.hpp"
#include "io/ensemble_file.hpp"

namespace stengmc::app {

namespace {

std::string default_output(const StudyFile& study, const EnsembleCommandOptions& options) {
  if (options.shard)
    return study.output.file + ".shard" + std::to_string(options.shard->index) + "of" + std::to_string(options.shard->count);
  if (!options.only) return study.output.file;
  // --only writes one realisation: never over the full ensemble's result.
  const std::filesystem::path out(study.output.file);
  return (out.parent_path() / (out.stem().string() + "_r" + std::to_string(*options.only) + ".h5")).string();
}

void print_header(const StudyFile& study, std::size_t grid_points) {
  const EnsembleSettings& e = *study.ensemble;
  std::printf("stengmc run %s: ensemble of %llu realisations", study.file.c_str(),
              static_cast<unsigned long long>(e.realisations));
  if (e.target)
    std::printf(" (or fewer: stop when the 95 %% CI half-width of mean %s <= %g)", std::string(scalar_info(*e.target).name).c_str(),
                e.target_half_width);
  if (grid_points > 1) std::printf(" at each of %zu grid points", grid_points);
  std::printf(", seed %llu\n", static_cast<unsigned long long>(study.seed));
  if (!study.title.empty()) std::printf("  %s\n", study.title.c_str());
}

//! One line per grid point: the few statistics a sweep is usually about.
std::string format_grid_table(const std::vector<GridPoint>& grid) {
  std::size_t width = 10;
  for (const GridPoint& point : grid) width = std::max(width, describe_grid_point(point, true).size());
  const int w = static_cast<int>(width);
  char line[512];
  std::snprintf(line, sizeof line, "  %5s  %-*s %9s  %-36s %-17s %s\n", "point", w, "parameters", "valid",
                "V_rms [V] mean [95 % CI]", "final charge [C]", "FFT pooled ratio [95 % CI]");
  std::string out = line;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const EnsembleSummary& s = grid[g].summary;
    const Interval& v = s.scalars[static_cast<std::size_t>(Scalar::voltage_rms_v)].mean;
    const Interval& q = s.scalars[static_cast<std::size_t>(Scalar::final_charge_c)].mean;
    const Interval& r = s.fft_pooled_ratio;
    char voltage[64], ratio[64];
    if (s.valid > 0) std::snprintf(voltage, sizeof voltage, "%.4g [%.4g, %.4g]", v.estimate, v.low, v.high);
    else std::snprintf(voltage, sizeof voltage, "- (no valid realisation)");
    // A study without [spectrum] has no lines to identify.
    if (r.known && s.valid > 0) std::snprintf(ratio, sizeof ratio, "%.3f [%.3f, %.3f]", r.estimate, r.low, r.high);
    else std::snprintf(ratio, sizeof ratio, "-");
    char charge[32];
    if (s.valid > 0) std::snprintf(charge, sizeof charge, "%.4g", q.estimate);
    else std::snprintf(charge, sizeof charge, "-");
    std::snprintf(line, sizeof line, "  %5zu  %-*s %4zu/%-4zu  %-36s %-17s %s\n", g + 1, w,
                  describe_grid_point(grid[g], true).c_str(), s.valid, s.realisations, voltage, charge, ratio);
    out += line;
  }
  return out;
}

//! What `--shard` cannot be combined with, said before anything runs.
void check_shard_options(const StudyFile& study, const EnsembleCommandOptions& options, bool figures) {
  if (!options.shard) return;
  const std::string shard = "--shard " + options.shard->text();
  if (process_world().distributed())
    throw InputError(shard + ": shards and an MPI launch are two ways of splitting one run; use one of them");
  if (options.only) throw InputError(shard + ": --only runs one realisation; use one or the other");
  if (figures) throw InputError(shard + ": a shard has no figures; merge the shards, then plot the merged file");
  if (study.ensemble->target)
    throw InputError(study.file + ": [ensemble] target_statistic: " + shard +
                     ": a study that stops at a target cannot run in shards (a slice cannot know where the whole run "
                     "would stop); run it whole, or over MPI");
}

void write_shard(const std::string& out, const StudyFile& study, const ShardSpec& shard, const std::vector<GridPoint>& grid) {
  write_shard_file(out, study, shard, grid);
  std::size_t run = 0, resumed = 0;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    run += grid[g].run.records.size();
    resumed += grid[g].run.resumed;
    std::filesystem::remove(journal_path(out, g, grid.size()));
  }
  std::printf("shard %s: %zu realisations over %zu grid point(s)%s\n", shard.text().c_str(), run, grid.size(),
              resumed > 0 ? (" (" + std::to_string(resumed) + " resumed from an interrupted run)").c_str() : "");
  std::printf("wrote %s\nwhen all %llu shards are done: stengmc merge <the %llu shard files> --out <file.h5>\n", out.c_str(),
              static_cast<unsigned long long>(shard.count), static_cast<unsigned long long>(shard.count));
}

}  // namespace

void print_ensemble_results(const StudyFile& study, const std::vector<GridPoint>& grid, bool only) {
  const EnsembleSettings& settings = *study.ensemble;
  if (grid.size() == 1) {
    std::printf("%s", format_ensemble_summary(grid[0].summary, grid[0].run).c_str());
  } else {
    std::printf("%s", format_grid_table(grid).c_str());
    std::size_t invalid = 0;
    for (const GridPoint& point : grid) invalid += point.summary.invalid.size();
    if (invalid > 0)
      std::printf("%zu invalid realisations in all, kept out of the statistics (which and why: /realisations/failure)\n",
                  invalid);
  }
  if (settings.target && !only)
    for (std::size_t g = 0; g < grid.size(); ++g) {
      const EnsembleRun& run = grid[g].run;
      std::printf("%starget: 95 %% CI half-width of mean %s = %.4g (goal %.4g): %s\n",
                  grid.size() > 1 ? ("point " + std::to_string(g + 1) + ": ").c_str() : "",
                  std::string(scalar_info(*settings.target).name).c_str(), run.target_half_width_reached,
                  settings.target_half_width,
                  run.target_met ? (run.stopped_at_target ? "met, stopped early" : "met at the cap")
                                 : "NOT met: the cap of realisations came first");
    }
}

void run_ensemble_study(const StudyFile& study, const std::string& out_option, bool figures,
                        const EnsembleCommandOptions& options) {
  const std::string out = out_option.empty() ? default_output(study, options) : out_option;
  check_output_path(out, study_inputs(study), output_option(out_option, study));
  const EnsembleSettings& settings = *study.ensemble;
  if (options.only && *options.only >= settings.realisations)
    throw InputError("--only " + std::to_string(*options.only) + ": the study has realisations 0.." +
                     std::to_string(settings.realisations - 1) + " ([ensemble] realisations = " +
                     std::to_string(settings.realisations) + ")");
  check_shard_options(study, options, figures);
  // In an MPI run every rank reads and prepares the same grid; rank 0 alone prints,
  // journals and writes (the other ranks compute what it hands out).
  const bool root = process_world().root();
  std::vector<GridPoint> grid = prepare_grid(study, options.limits);
  if (root) {
    print_header(study, grid.size());
    if (options.shard) std::printf("  shard %s: realisations r with r mod %llu = %llu\n", options.shard->text().c_str(),
                                   static_cast<unsigned long long>(options.shard->count),
                                   static_cast<unsigned long long>(options.shard->index));
    if (process_world().distributed())
      std::printf("  %d MPI processes\n", process_world().size);
    // A [counterface] modulation is random too: its own stream per realisation and asperity.
    if (!study.surface->random_surface() && !study.noise && !study.model2.counterface.active())
      std::printf("NOTE: the study's surface is a fixed list and it has no [noise]: nothing is random, every realisation "
                  "is the same run and the intervals have zero width\n");
  }
  std::fflush(stdout);
  const auto job_start = std::chrono::steady_clock::now();
  for (std::size_t g = 0; g < grid.size(); ++g) {
    EnsembleOptions run_options{.threads = options.threads, .only = options.only, .restart = options.restart,
                                .show_progress = root, .limits = options.limits, .shard = options.shard};
    if (grid.size() > 1) {
      run_options.progress_label = "point " + std::to_string(g + 1) + "/" + std::to_string(grid.size());
      run_options.job_start = job_start;
      run_options.job_before = static_cast<double>(g) / static_cast<double>(grid.size());
      run_options.job_share = 1.0 / static_cast<double>(grid.size());
    }
    grid[g].run = run_ensemble(grid[g].study, journal_path(out, g, grid.size()), run_options);
    if (root && !options.shard) grid[g].summary = summarise_ensemble(grid[g].run.records, study.seed);
  }
  if (!root) return;
  if (options.shard) {
    write_shard(out, study, *options.shard, grid);
    return;
  }
  write_ensemble_file(out, study, grid);
  if (!options.only)
    for (std::size_t g = 0; g < grid.size(); ++g) std::filesystem::remove(journal_path(out, g, grid.size()));
  print_ensemble_results(study, grid, options.only.has_value());
  std::printf("wrote %s\n", out.c_str());
  if (figures && render_figures(out, options.figure) != 0)
    throw std::runtime_error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

}  // namespace stengmc::app
