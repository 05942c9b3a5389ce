#include <omp.h>

#include <cstdio>
#include <limits>
#include <memory>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/limit_options.hpp"
#include "core/error.hpp"
#include "ensemble/ensemble_runner.hpp"  // MAX_THREADS
#include "ensemble/process_world.hpp"
#include "ensemble/shard.hpp"
#include "inverse/inverse_prior.hpp"
#include "io/run_file.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/run_summary.hpp"
#include "pipeline/spectral_summary.hpp"

namespace stengmc::app {

namespace {

struct RunOptions {
  std::string study_file;
  std::string out;
  std::uint64_t realisation = 0;
  bool realisation_given = false;
  bool figures = false;
  FigureOptions figure;
  EnsembleCommandOptions ensemble;
  std::string shard;  //!< --shard i/n as given
  LimitOptions limits;
};

void run_single(const RunOptions& options) {
  const StudyFile study = read_study_file(options.study_file, options.realisation);
  const std::string out = options.out.empty() ? study.output.file : options.out;
  check_output_path(out, study_inputs(study), output_option(options.out, study));
  // Model 2 asperities side by side: -j threads, or as many as the cores and the memory
  // limit allow (each holds one asperity's dense output); the run is the same bit for bit.
  const std::size_t threads = options.ensemble.threads > 0
      ? static_cast<std::size_t>(options.ensemble.threads)
      : run_threads_within(study, static_cast<std::size_t>(omp_get_max_threads()), options.limits.limits());
  check_work(estimate_run(study, -1.0, true, false, threads), options.limits.limits(), study.file + ": the run");
  std::printf("stengmc run %s: %s, %zu asperities, %.4g s at %.4g Hz\n", study.file.c_str(),
              std::string(model_name(study.model)).c_str(), study.asperities.size(), study.duration_s,
              study.sample_rate_hz);
  if (!study.title.empty()) std::printf("  %s\n", study.title.c_str());
  if (study.surface->random_surface())
    std::printf("  realisation %llu of %s (seed %llu): %zu summits drawn, %zu in contact\n",
                static_cast<unsigned long long>(study.realisation),
                study.surface_file.empty() ? "the inline surface" : study.surface_file.c_str(),
                static_cast<unsigned long long>(study.seed), study.population.height_m.size(), study.asperities.size());
  // The file holds samples, not dense motions: each is dropped once summed (a long run fits).
  const RunResult result = run_study(study, stengmc::RunOptions{.show_progress = true,
                                                                 .limits = options.limits.limits(),
                                                                 .keep_motions = false,
                                                                 .threads = threads});
  const RunSummary summary = summarise(study, result);
  write_run_file(out, study, result, summary);
  std::printf("%s", format_summary(study, result, summary).c_str());
  if (result.spectra) std::printf("%s", format_spectral_summary(*result.spectra).c_str());
  for (const std::string& note : result.notes) std::printf("NOTE: %s\n", note.c_str());
  std::printf("wrote %s\n", out.c_str());
  if (options.figures && render_figures(out, options.figure) != 0)
    throw std::runtime_error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

void run(const RunOptions& options) {
  // An [ensemble] study runs as an ensemble unless one realisation is asked for.
  const std::optional<ShardSpec> shard =
      options.shard.empty() ? std::nullopt : std::optional<ShardSpec>(parse_shard_spec(options.shard));
  const StudyFile base = read_study_file(options.study_file, std::nullopt);
  // [inverse] plays no part in a run, but a misspelt key there must not pass unseen: the
  // same study goes to calibrate and invert, which would refuse it only then.
  (void)inverse_prior_of_study(base.text, base.file);
  if (base.ensemble && !options.realisation_given) {
    EnsembleCommandOptions ensemble = options.ensemble;
    ensemble.limits = options.limits.limits();
    ensemble.shard = shard;
    ensemble.figure = options.figure;
    run_ensemble_study(base, options.out, options.figures, ensemble);
    return;
  }
  if (process_world().distributed())
    throw InputError("an MPI launch distributes the realisations of an [ensemble] study; " +
                     (base.ensemble ? std::string("--realisation runs one realisation: run it without mpirun")
                                    : options.study_file + " has no [ensemble] table: run it without mpirun"));
  if (shard)
    throw InputError(base.ensemble ? std::string("--shard splits an ensemble run; --realisation runs one realisation: use "
                                                 "one or the other")
                                   : options.study_file + " has no [ensemble] table: --shard applies to ensembles only");
  if (options.ensemble.only || options.ensemble.restart)
    throw InputError(base.ensemble ? std::string("--realisation runs one realisation as an ordinary run; --only and "
                                                 "--restart belong to the ensemble run: use one or the other")
                                   : options.study_file + " has no [ensemble] table: --only and --restart apply to "
                                                          "ensembles only");
  run_single(options);
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* command = app.add_subcommand("run", "Run a study: surface -> tribology -> S-TENG circuit -> spectra -> HDF5 output;\n"
                                                 "a study with [ensemble] runs its realisations in parallel and reports statistics");
  command->add_option("study", options->study_file, "Study file (TOML; see studies/ and docs/study-files.md)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (default: [output] file, else results/<study>.h5)")
      ->check(non_empty_path());
  CLI::Option* realisation = command->add_option(
      "-r,--realisation", options->realisation,
      "Run this one realisation of a random surface and write its full run file (also for an [ensemble] "
      "study; default 0, and an ensemble study without it runs the ensemble)")
      ->check(CLI::Range(std::uint64_t{0}, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
  CLI::Option* figures = command->add_flag("-f,--figures", options->figures,
                                           "Also render figures beside the output (needs python3-h5py, matplotlib)");
  add_figure_options(command, figures, options->figure);
  command->add_option("-j,--threads", options->ensemble.threads, "Threads: an ensemble's realisations, or a single Model 2 run's asperities, the run the same for any count "
                      "(default 0: OMP_NUM_THREADS when set, else every core; a single run: as many as fit --max-memory-gb)")
      ->capture_default_str()
      ->check(CLI::Range(0, MAX_THREADS));
  command->add_option("--only", options->ensemble.only,
                      "Ensemble: run realisation R alone into an ensemble file (to check it against a batch)")
      ->check(CLI::Range(std::uint64_t{0}, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
  command->add_flag("--restart", options->ensemble.restart,
                    "Ensemble: discard the journal of an interrupted run instead of resuming it");
  command->add_option("--shard", options->shard,
                      "Ensemble: run only slice i of n (realisations r with r mod n = i, every grid point) into a "
                      "shard file (default <output>.shard<i>of<n>); `stengmc merge` makes the output of all n")
      ->type_name("I/N");
  add_limit_options(command, options->limits);
  command->callback([options, realisation] {
    options->realisation_given = realisation->count() > 0;
    run(*options);
  });
}

}  // namespace stengmc::app
