#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/limit_options.hpp"
#include "app/validators.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "ensemble/ensemble_runner.hpp"  // MAX_THREADS
#include "ensemble/process_world.hpp"
#include "inverse/calibration_run.hpp"
#include "io/calibration_bank_file.hpp"

namespace stengmc::app {

namespace {

struct CalibrateOptions {
  std::string study_file;
  std::string out;
  int threads = 0;
  bool restart = false;
  long long records = 0;  // 0: the study's [inverse] calibration_records
  bool refit = false;     // refit the maps of an existing bank from its records
  LimitOptions limits;
};

//! In-bank figures by bin of the true count: what the estimator did on the records it was
//! calibrated on (in-sample; held-out figures come from a validation study).
std::string bank_table(const CalibrationBank& bank) {
  struct Bin {
    const char* label;
    std::size_t low, high;
  };
  const Bin bins[] = {{"all", 0, 1000}, {"n 0", 0, 0}, {"n 1-4", 1, 4}, {"n 5-8", 5, 8}, {"n 9-12", 9, 12}, {"n 13-16", 13, 16}};
  std::string out = "  records     n RMSE   exact    naive FFT RMSE   naive exact\n";
  const std::size_t t = bank.maps.naive_threshold_index;
  for (const Bin& b : bins) {
    double se = 0, exact = 0, naive_se = 0, naive_exact = 0;
    std::size_t count = 0;
    for (const CalibrationSample& s : bank.samples) {
      if (!s.valid || s.true_count() < b.low || s.true_count() > b.high) continue;
      const double e = static_cast<double>(s.count) - static_cast<double>(s.true_count());
      const double ne = s.naive_counts[t] - static_cast<double>(s.true_count());
      se += e * e, exact += e == 0, naive_se += ne * ne, naive_exact += ne == 0, ++count;
    }
    if (count == 0) continue;
    char line[160];
    const double n = static_cast<double>(count);
    std::snprintf(line, sizeof line, "  %-9s %5zu  %6.3f  %5.1f %%   %6.3f           %5.1f %%\n", b.label, count, std::sqrt(se / n),
                  100 * exact / n, std::sqrt(naive_se / n), 100 * naive_exact / n);
    out += line;
  }
  return out;
}

void run(const CalibrateOptions& options) {
  const Study study = read_study(options.study_file, std::nullopt);
  const std::string out = options.out.empty()
                              ? (std::filesystem::path("results") / std::filesystem::path(options.study_file).stem()).string() + "_bank.h5"
                              : options.out;
  // The bank itself is this command's input only with --refit, where rewriting it is the point.
  check_output_path(out, study_inputs(study), options.out.empty() ? "the default bank path" : "--out");
  CalibrationOptions calibration;
  calibration.threads = options.threads;
  calibration.restart = options.restart;
  calibration.limits = options.limits.limits();
  if (options.records > 0) calibration.records = static_cast<std::size_t>(options.records);
  // Everything the bank would be made from is checked before the long run starts.
  const InverseSetup setup = inverse_setup(study);
  const std::size_t records = calibration.records.value_or(setup.prior.calibration_records);
  // Under MPI every rank builds the atoms and computes records; rank 0 alone prints and writes.
  const bool root = process_world().root();
  if (options.refit && process_world().distributed())
    throw InputError("--refit fits the maps of an existing bank without simulating: run it without mpirun");
  if (root) {
    std::printf("stengmc calibrate %s: %zu simulated records of the prior, seed %llu\n", options.study_file.c_str(), records,
                static_cast<unsigned long long>(setup.prior.seed));
    std::printf("  prior: %zu-%zu sliding asperities, %s stiffnesses, SNR %g-%g dB; records of %zu samples at %g Hz\n",
                setup.prior.count_min, setup.prior.count_max, std::string(stiffness_family_name(setup.prior.family)).c_str(),
                setup.prior.snr_db[0], setup.prior.snr_db[1], setup.grid.samples, setup.grid.sample_rate_hz());
    if (!options.refit) std::printf("  building the atoms (the forward model on a grid of stiffnesses)...\n");
  }
  std::fflush(stdout);
  const std::string journal = out + ".journal";
  CalibrationBank bank;
  if (options.refit) {
    // The records stay, the maps are fitted afresh: only for a bank of this very setup.
    bank = read_calibration_bank_records(out, setup);
    const std::string differences = bank_identity_of(out).differences(setup.identity);
    if (!differences.empty())
      throw InputError("--refit: " + out + " was made for something else: " + differences + "; make it afresh without --refit");
    bank.setup.prior.calibration_records = bank.samples.size();
    bank.maps = fit_calibration_maps(bank.samples, bank.setup.prior);
    std::printf("  refitted the maps on the bank's %zu records (no new simulation)\n", bank.samples.size());
  } else {
    bank = run_calibration(study, journal, calibration);
    if (bank.worker) return;
  }
  if (const auto folder = std::filesystem::path(out).parent_path(); !folder.empty()) std::filesystem::create_directories(folder);
  write_calibration_bank(out, bank);
  // The journal of this run, now in the bank; --refit ran none, and what sits at its path
  // (an interrupted calibration's journal, or anything else) is not its to remove.
  if (!options.refit) std::filesystem::remove(journal);

  const std::size_t invalid = bank.samples.size() - bank.maps.records;
  std::printf("  atoms: %zu shapes over Pi %.3g-%.3g (belt-carried stretch) and zeta %.2g-%.2g, worst check against the "
              "forward model %.2g (relative L2), built in %.1f s\n",
              bank.atoms.pi_nodes.size() * bank.atoms.zeta_nodes.size(), bank.atoms.range.min_pi, bank.atoms.range.max_pi,
              bank.atoms.range.min_zeta, bank.atoms.range.max_zeta, bank.atoms.check_error, bank.atom_seconds);
  std::printf("  records: %zu valid, %zu invalid (an asperity reached l, outside the device's range, or the estimator "
              "could not answer)%s\n", bank.maps.records,
              invalid, bank.resumed ? (", " + std::to_string(bank.resumed) + " resumed from the journal").c_str() : "");
  {
    const ClassMaps& fits = bank.maps.of(FitClass::fits);
    const ClassMaps& misfits = bank.maps.of(FitClass::misfits);
    std::printf("  fit classes: %zu records fit their noise (residual <= %.3g x the noise above the lines) and pin every "
                "line (ln k error <= %.2g), %zu do not%s\n",
                fits.records, bank.maps.misfit_ratio, bank.maps.line_se_bound, misfits.records,
                fits.pooled || misfits.pooled ? " (a class of fewer than 60 records takes every record's maps)" : "");
  }
  std::printf("On the bank's own records (in-sample; the naive FFT count at its best threshold, %g x the local floor):\n%s",
              bank.maps.naive_threshold, bank_table(bank).c_str());
  if (!options.refit && bank.resumed == 0 && bank.maps.records > 0) {
    const double per_record = bank.cpu_seconds / static_cast<double>(bank.samples.size());
    const double estimation = bank.estimation_cpu_seconds / static_cast<double>(bank.samples.size());
    std::printf("Time: %.1f s wall on %d threads (atoms %.1f s); per record %.0f ms CPU: estimation %.0f ms, forward "
                "simulation and the rest %.0f ms (%s dominates)\n",
                bank.seconds, bank.threads, bank.atom_seconds, 1e3 * per_record, 1e3 * estimation,
                1e3 * std::max(0.0, per_record - estimation), per_record - estimation > estimation ? "the simulation" : "the estimation");
  }
  std::printf("wrote %s\n", out.c_str());
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto options = std::make_shared<CalibrateOptions>();
  CLI::App* command = app.add_subcommand(
      "calibrate", "Calibration bank for inverse estimation: simulate the [inverse] prior of a known device, invert each record");
  command->add_option("study", options->study_file, "The known device's study file, with its [inverse] prior")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Bank file (default results/<study>_bank.h5)")
      ->check(non_empty_path());
  command->add_option("-j,--threads", options->threads, "Threads (default: OMP_NUM_THREADS when set, else every core)")->check(CLI::Range(1, MAX_THREADS));
  command->add_flag("--restart", options->restart, "Discard an interrupted calibration's journal instead of resuming it");
  command->add_option("--records", options->records, "Simulated records (default: [inverse] calibration_records)")
      ->check(CLI::Range(50LL, 1000000LL));
  command->add_flag("--refit", options->refit,
                    "Refit the maps of the existing bank (--out) from its records, without simulating again");
  add_limit_options(command, options->limits);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
