#pragma once
//! The subcommands of `stengmc`; each registers itself on the CLI11 app.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "ensemble/shard_spec.hpp"
#include "ensemble/sweep.hpp"
#include "pipeline/study.hpp"
#include "pipeline/work_estimate.hpp"

namespace stengmc::app {

void add_run_command(CLI::App& app);
void add_circuit_command(CLI::App& app);
void add_plot_command(CLI::App& app);
void add_spectrum_command(CLI::App& app);
void add_surface_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_invert_command(CLI::App& app);
void add_track_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_status_command(CLI::App& app);
void add_export_netlist_command(CLI::App& app);

//! What `run` passes on to an ensemble.
//! How the figure scripts write: `format` png, pdf or svg, `dpi` in 20..1200 (the
//! scripts' --figure-format and --dpi; stengmc_h5.py has the same defaults).
struct FigureOptions {
  std::string format = "png";
  int dpi = 150;
};

//! Adds --figure-format and --dpi to `command`, each needing `figures` (the -f flag).
void add_figure_options(CLI::App* command, CLI::Option* figures, FigureOptions& options);

struct EnsembleCommandOptions {
  int threads = 0;
  std::optional<std::uint64_t> only;
  bool restart = false;
  WorkLimits limits;
  std::optional<ShardSpec> shard;  //!< --shard i/n: run one slice into a shard file
  FigureOptions figure;            //!< how --figures writes
};

//! Runs an [ensemble] study: realisations in parallel, journal, statistics, output file.
void run_ensemble_study(const stengmc::StudyFile& study, const std::string& out, bool figures,
                        const EnsembleCommandOptions& options);

//! The summary table (one point) or grid table (a sweep) and the target lines of a run grid.
void print_ensemble_results(const stengmc::StudyFile& study, const std::vector<GridPoint>& grid, bool only);


//! Renders the figures of an output file with scripts/plot_run.py; returns its exit status.
int render_figures(const std::string& h5_path, const FigureOptions& options = {});

}  // namespace stengmc::app
