#include <omp.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/limit_options.hpp"
#include "app/record_options.hpp"
#include "app/validators.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/progress.hpp"
#include "ensemble/ensemble_runner.hpp"  // MAX_THREADS
#include "inverse/calibration_run.hpp"
#include "inverse/inversion.hpp"
#include "inverse/inversion_work.hpp"
#include "inverse/record_input.hpp"
#include "io/calibration_bank_file.hpp"
#include "io/inverse_file.hpp"
#include "io/inverse_signals.hpp"

namespace stengmc::app {

namespace {

struct InvertOptions {
  std::vector<std::string> signals;
  std::string known;
  std::string bank;
  std::string out;
  bool figures = false;
  FigureOptions figure;
  int threads = 0;
  LimitOptions limits;
  RecordOptions record;
};

std::string default_bank(const std::string& known) {
  return (std::filesystem::path("results") / std::filesystem::path(known).stem()).string() + "_bank.h5";
}

void print_summary(const std::vector<Inversion>& inversions, const std::vector<LawFit>& pooled) {
  std::printf("  %-44s %5s  %-9s  %5s  %-26s %-20s %7s\n", "record", "n", "90 % int.", "FFT", "median k [N/m] (90 %)",
              "sd ln k (90 %)", "SNR dB");
  for (const Inversion& inv : inversions) {
    const CalibratedEstimate& c = inv.calibrated;
    std::string name = inv.name.size() > 44 ? "..." + inv.name.substr(inv.name.size() - 41) : inv.name;
    char interval[32], median[64], sd[48];
    std::snprintf(interval, sizeof interval, "%zu-%zu", c.interval_low, c.interval_high);
    if (c.population_intervals)
      std::snprintf(median, sizeof median, "%.4g [%.4g, %.4g]", c.median, c.median_low, c.median_high);
    else
      std::snprintf(median, sizeof median, "%.4g", c.median);
    if (!c.sd_known) std::snprintf(sd, sizeof sd, "- (one line)");
    else if (c.population_intervals) std::snprintf(sd, sizeof sd, "%.3f [%.3f, %.3f]", c.sd_log, c.sd_log_low, c.sd_log_high);
    else std::snprintf(sd, sizeof sd, "%.3f", c.sd_log);
    std::printf("  %-44s %5zu  %-9s  %5.0f  %-26s %-20s %7.1f\n", name.c_str(), c.count, interval, inv.naive_count, median, sd,
                inv.raw.signal_to_noise_db);
  }
  if (inversions.size() == 1) {
    const Inversion& inv = inversions.front();
    std::printf("  lines (k [N/m] with 90 %% interval, f [MHz]):");
    for (std::size_t i = 0; i < inv.raw.lines.size(); ++i)
      std::printf("%s %.4g [%.4g, %.4g] at %.4f", i ? "," : "", inv.raw.lines[i].stiffness_n_per_m, inv.calibrated.line_low[i],
                  inv.calibrated.line_high[i], inv.raw.lines[i].frequency_hz / 1e6);
    std::printf("\n");
  }
  const std::vector<LawFit>& laws = inversions.size() == 1 ? inversions.front().laws : pooled;
  if (!laws.empty() && laws.front().fitted) {
    std::printf("  stiffness law%s (maximum likelihood, by AIC):", inversions.size() > 1 ? " of all records pooled" : "");
    for (const LawFit& law : laws) {
      if (!law.fitted) continue;
      std::printf("  %s median %.4g N/m, sd ln k %.3f, dAIC %.1f;", std::string(stiffness_family_name(law.family)).c_str(), law.median,
                  law.sd_log, law.aic - laws.front().aic);
    }
    std::printf("\n");
  } else {
    std::printf("  stiffness law: none fitted (fewer than 3 distinct lines, or lines of one stiffness to 0.01 %%)\n");
  }
  for (const Inversion& inv : inversions) {
    if (inversions.size() > 1 && inv.warnings.empty()) continue;  // many records: only those with something to say
    std::printf("%s:\n", inv.name.c_str());
    for (const std::string& line : inv.verdict) std::printf("  %s\n", line.c_str());
    for (const std::string& w : inv.warnings) std::printf("  WARNING: %s\n", w.c_str());
  }
}

void run(const InvertOptions& options) {
  const Study study = read_study(options.known, std::nullopt);
  std::vector<NamedInput> inputs = study_inputs(study);
  for (const std::string& s : options.signals) inputs.push_back({s, "a measured record"});
  if (!options.bank.empty()) inputs.push_back({options.bank, "the calibration bank"});
  check_output_path(options.out, inputs);

  // Every record read and checked before anything is computed; a CSV's size bounds what
  // reading it costs before it is read.
  std::vector<NamedRecord> records;
  for (const std::string& path : options.signals) {
    if (is_record_text(path, options.record.read()))
      check_work(estimate_record_reading(static_cast<double>(check_input_file(path, "the record CSV file"))),
                 options.limits.limits(), path + ": reading it");
    std::vector<std::string> notes;
    std::vector<NamedRecord> more = read_inverse_records(path, options.record.read(), &notes);
    for (const std::string& note : notes) std::printf("note: %s\n", note.c_str());
    for (NamedRecord& r : more) records.push_back(std::move(r));
  }
  std::optional<RecordGrid> grid;
  for (const NamedRecord& r : records) {
    const RecordGrid g = checked_record_grid(r.times_s, r.voltage_v, r.name);
    if (grid && !grid->same_as(g))
      throw InputError(r.name + ": its grid (" + std::to_string(g.samples) + " samples at " + format_number(g.sample_rate_hz()) +
                       " Hz from t = " + format_number(g.start_s) + " s) differs from " + records.front().name +
                       "'s: invert records of one grid together");
    grid = g;
  }
  InverseSetup setup;
  try {
    setup = inverse_setup(study, grid);
  } catch (const InputError& e) {
    // A sample rate too low for the prior is the records' fault as much as the prior's.
    const std::string what = e.what();
    if (what.rfind("the record's sample rate", 0) == 0) throw InputError(records.front().name + ": " + what);
    throw;
  }

  // The bank: given, or the default one if it exists; it must be made for this device.
  std::string bank_path = options.bank;
  if (bank_path.empty() && std::filesystem::exists(default_bank(options.known))) bank_path = default_bank(options.known);
  std::optional<StoredBank> bank;
  if (!bank_path.empty()) {
    bank = read_calibration_bank(bank_path);
    const std::string differences = bank->identity.differences(setup.identity);
    if (!differences.empty())
      throw InputError(bank_path + " was made for other known parameters than " + options.known + " and these records: " +
                       differences + ". Make a bank for them with stengmc calibrate (the study's duration_s and "
                       "sample_rate_hz set the record grid)");
  }
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  check_work(estimate_inversion(study, setup, {.records = records.size(), .threads = threads, .builds_atoms = !bank}),
             options.limits.limits(),
             options.known + ": inverting " + std::to_string(records.size()) + " record(s) of " +
                 std::to_string(grid->samples) + " samples");
  for (const NamedRecord& r : records) check_record_varies(r.voltage_v, r.name);
  std::printf("stengmc invert: %zu record(s) of %zu samples at %g Hz, known device %s, %s\n", records.size(), grid->samples,
              grid->sample_rate_hz(), options.known.c_str(),
              bank ? ("bank " + bank_path).c_str() : "NO calibration bank (uncalibrated answers)");
  std::fflush(stdout);
  std::unique_ptr<AtomLibrary> atoms;
  if (bank) {
    atoms = build_atom_library(setup, bank->atoms);
  } else {
    std::printf("  building the atoms (the forward model over the prior's asperities; a bank keeps them)...\n");
    std::fflush(stdout);
    atoms = build_atom_library(setup);
  }

  std::vector<Inversion> inversions(records.size());
  std::optional<Progress> progress;
  progress.emplace("invert", records.size());
  std::mutex mutex;
  std::exception_ptr failure;
  const auto count = static_cast<std::int64_t>(records.size());
#pragma omp parallel num_threads(threads)
  {
    std::unique_ptr<Inverter> inverter;
    try {
      inverter = std::make_unique<Inverter>(setup, *atoms, bank ? &bank->maps : nullptr);
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
    }
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t i = 0; i < count; ++i) {
      if (!inverter) continue;
      try {
        const auto j = static_cast<std::size_t>(i);
        inversions[j] = inverter->invert(records[j].name, records[j].voltage_v);
        std::lock_guard lock(mutex);
        progress->advance();
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  }
  progress.reset();
  if (failure) std::rethrow_exception(failure);
  const std::vector<LawFit> pooled = pooled_laws(inversions);

  InverseFileContext context;
  context.known_file = options.known;
  context.known_text = study.text;
  if (bank) {
    context.bank_path = bank_path;
    context.bank_identity_hash = bank->identity.hash;
    context.bank_git_revision = bank->git_revision;
  }
  for (const NamedRecord& r : records) {
    context.times.push_back(r.times_s);
    context.voltages.push_back(r.voltage_v);
  }
  write_inverse_file(options.out, context, inversions, pooled);
  print_summary(inversions, pooled);
  std::printf("wrote %s\n", options.out.c_str());
  if (options.figures && render_figures(options.out, options.figure) != 0)
    throw Error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

}  // namespace

void add_invert_command(CLI::App& app) {
  auto options = std::make_shared<InvertOptions>();
  CLI::App* command = app.add_subcommand(
      "invert", "Inverse estimation: how many asperities slide, and their stiffnesses, from measured voltages of a known device");
  command->add_option("signals", options->signals,
                      "Records: CSV files `t,V`, oscilloscope exports (--format), stengmc run files, or ensemble files (every kept trace)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-k,--known", options->known, "The known device's study file (with its [inverse] prior)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-b,--bank", options->bank,
                      "Calibration bank from stengmc calibrate (default results/<known>_bank.h5 if it exists)")
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (/inverse)")
      ->required()
      ->check(non_empty_path());
  CLI::Option* figures = command->add_flag("-f,--figures", options->figures,
                                           "Also render the figure (spectrum with the fitted lines, P(n), stiffness law)");
  add_figure_options(command, figures, options->figure);
  command->add_option("-j,--threads", options->threads, "Threads (default: OMP_NUM_THREADS when set, else every core)")->check(CLI::Range(1, MAX_THREADS));
  add_limit_options(command, options->limits);
  add_record_options(command, options->record);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
