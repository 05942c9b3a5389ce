#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/ensemble_summary.hpp"
#include "io/ensemble_file.hpp"

namespace stengmc::app {

void run_ensemble_study(const Study& study, const std::string& out_option, bool figures,
                        const EnsembleCommandOptions& options) {
  std::string out = out_option;
  if (out.empty()) {
    out = study.output_file;
    // --only writes one realisation: never over the full ensemble's result.
    if (options.only)
      out = (std::filesystem::path(out).parent_path() /
             (std::filesystem::path(out).stem().string() + "_r" + std::to_string(*options.only) + ".h5"))
                .string();
  }
  const std::string journal = out + ".journal";
  const EnsembleSettings& e = *study.ensemble;
  std::printf("stengmc run %s: ensemble of %llu realisations%s, seed %llu\n", study.file.c_str(),
              static_cast<unsigned long long>(e.realisations),
              e.target ? (" (or fewer: stop when the 95 % CI half-width of mean " + std::string(scalar_info(*e.target).name) +
                          " <= " + std::to_string(e.target_half_width) + ")")
                             .c_str()
                       : "",
              static_cast<unsigned long long>(study.seed));
  if (!study.title.empty()) std::printf("  %s\n", study.title.c_str());
  if (!options.only && !options.restart && std::filesystem::exists(journal))
    std::printf("  resuming the interrupted run recorded in %s\n", journal.c_str());
  std::fflush(stdout);
  const EnsembleRun run = run_ensemble(study, journal, {.threads = options.threads, .only = options.only,
                                                        .restart = options.restart, .show_progress = true});
  const EnsembleSummary summary = summarise_ensemble(run.records, study.seed);
  write_ensemble_file(out, study, run, summary);
  if (!options.only) std::filesystem::remove(journal);
  std::printf("%s", format_ensemble_summary(summary, run).c_str());
  std::printf("wrote %s\n", out.c_str());
  if (figures && render_figures(out) != 0)
    throw std::runtime_error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

}  // namespace stengmc::app
