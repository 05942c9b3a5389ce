#include <omp.h>

#include <algorithm>
#include <filesystem>
#include <cstdio>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/record_options.hpp"
#include "app/validators.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/progress.hpp"
#include "ensemble/ensemble_runner.hpp"  // MAX_THREADS
#include "inverse/calibration_run.hpp"
#include "inverse/record_input.hpp"
#include "inverse/regime_check.hpp"
#include "inverse/track_lines.hpp"
#include "inverse/tracking.hpp"
#include "io/instrument_csv.hpp"
#include "io/inverse_signals.hpp"
#include "io/tracking_file.hpp"

namespace stengmc::app {

namespace {

struct TrackOptions {
  std::string record;
  std::string known;
  std::string out;
  double window_s = 0.0;
  double hop_s = 0.0;
  double max_wear_per_ms = 0.30;
  std::size_t max_missed = 2;
  bool figures = false;
  FigureOptions figure;
  int threads = 0;
  RecordOptions record_options;
};

std::string default_out(const std::string& record) {
  return std::filesystem::path(record).replace_extension().string() + "_track.h5";
}

void print_summary(const TrackingResult& r) {
  std::size_t onsets = 0, releases = 0, steps = 0;
  for (const TrackEvent& e : r.events)
    (e.kind == TrackEventKind::onset ? onsets : e.kind == TrackEventKind::release ? releases : steps)++;
  const auto [count_min, count_max] = std::minmax_element(r.count.begin(), r.count.end());
  const auto [naive_min, naive_max] = std::minmax_element(r.naive_count.begin(), r.naive_count.end());
  std::printf("  %zu windows of %s s every %s s (%s regime), noise %s V, band %.3f-%.3f MHz, %.2f s\n", r.windows.size(),
              format_number(r.windows.front().end_s - r.windows.front().start_s).c_str(),
              format_number(r.windows.size() > 1 ? r.windows[1].start_s - r.windows[0].start_s : 0.0).c_str(),
              r.excited ? "excited" : "unexcited", format_number(r.noise_sigma_v).c_str(), r.band_low_hz / 1e6,
              r.band_high_hz / 1e6, r.seconds);
  std::printf("  count n(t): %.0f-%.0f (naive FFT peaks %.0f-%.0f); %zu tracks; events: %zu onsets, %zu releases, %zu steps\n",
              *count_min, *count_max, *naive_min, *naive_max, r.tracks.size(), onsets, releases, steps);
  if (r.asperities_at_start > 0)
    std::printf("  at the start: %zu asperities from its plateau (%.2f x R sigma w v_b)\n", r.asperities_at_start, r.start_level);
  else if (!r.excited)
    std::printf("  at the start: not read (no flat plateau of whole asperities after the belt starts)\n");
  std::printf("  %5s  %-26s %-26s %s\n", "track", "onset [us] (interval)", "release [us] (interval)",
              "stiffness [N/m] between events (90 %)");
  for (std::size_t t = 0; t < r.tracks.size(); ++t) {
    std::string onset = "-", release = "-", k;
    char buffer[96];
    for (const TrackEvent& e : r.events) {
      if (e.track != t || e.kind == TrackEventKind::step) continue;
      std::snprintf(buffer, sizeof buffer, "%.1f [%.1f, %.1f]", e.time_s * 1e6, e.time_low_s * 1e6, e.time_high_s * 1e6);
      (e.kind == TrackEventKind::onset ? onset : release) = buffer;
    }
    for (const TrackSegment& s : r.segments) {
      if (s.track != t) continue;
      std::snprintf(buffer, sizeof buffer, "%s%.4g [%.4g, %.4g]", k.empty() ? "" : " | ", s.stiffness_n_per_m, s.stiffness_low,
                    s.stiffness_high);
      k += buffer;
    }
    std::printf("  %5zu  %-26s %-26s %s\n", t, onset.c_str(), release.c_str(), k.c_str());
  }
}

void run(const TrackOptions& options) {
  const Study study = read_study(options.known, std::nullopt);
  std::vector<NamedInput> inputs = study_inputs(study);
  inputs.push_back({options.record, "the record"});
  const std::string out = options.out.empty() ? default_out(options.record) : options.out;
  check_output_path(out, inputs);

  if (is_record_text(options.record, options.record_options.read()))
    check_input_file(options.record, "the record CSV file");
  std::vector<NamedRecord> records = read_inverse_records(options.record, options.record_options.read());
  if (records.size() != 1)
    throw InputError(options.record + ": holds " + std::to_string(records.size()) +
                     " records; track follows one (give an ensemble's record with --dataset, or split it)");
  const NamedRecord& record = records.front();
  const RecordGrid grid = checked_record_grid(record.times_s, record.voltage_v, record.name);
  InverseSetup setup;
  try {
    setup = inverse_setup(study, grid);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind("the record's sample rate", 0) == 0) throw InputError(record.name + ": " + what);
    throw;
  }
  check_record_varies(record.voltage_v, record.name);
  // The device's plausible lines: the prior's stiffnesses (1e-4 .. 1 - 1e-4 quantiles) widened
  // by 1.25 each way, as the inversion's atoms are.
  const auto [k_low, k_high] = setup.prior.support();
  const std::pair<double, double> band{frequency_at(setup.device, k_low / 1.25), frequency_at(setup.device, k_high * 1.25)};

  TrackingSettings settings;
  settings.window_s = options.window_s;
  settings.hop_s = options.hop_s;
  settings.max_wear_per_ms = options.max_wear_per_ms;
  settings.max_missed = options.max_missed;
  settings.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const std::size_t windows = track_windows(grid, track_windowing(setup.device, grid, options.window_s, options.hop_s)).size();
  std::printf("stengmc track: %s, %zu samples at %g Hz, known device %s\n", record.name.c_str(), grid.samples,
              grid.sample_rate_hz(), options.known.c_str());
  std::fflush(stdout);
  std::optional<Progress> progress;
  progress.emplace("track", windows);
  const TrackingResult result = track_record(setup.device, band, grid, record.voltage_v, settings, &*progress);
  progress.reset();

  TrackingFileContext context;
  context.known_file = options.known;
  context.known_text = study.text;
  context.record = record.name;
  context.max_wear_per_ms = settings.max_wear_per_ms;
  context.max_missed = settings.max_missed;
  context.threshold_snr = settings.threshold_snr;
  context.naive_threshold = settings.naive_threshold;
  context.times_s = record.times_s;
  context.voltage_v = record.voltage_v;
  write_tracking_file(out, context, result);
  print_summary(result);
  if (looks_excited(result))
    std::printf("  NOTE: %.0f %% of the clear lines grow across their window (a free ringing only decays): the record "
                "looks excited; does %s need [counterface] friction_modulation_rms > 0?\n",
                100.0 * growing_line_share(result), options.known.c_str());
  std::printf("wrote %s\n", out.c_str());
  if (options.figures && render_figures(out, options.figure) != 0)
    throw Error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

}  // namespace

void add_track_command(CLI::App& app) {
  auto options = std::make_shared<TrackOptions>();
  CLI::App* command = app.add_subcommand(
      "track",
      "Tracking a contact that changes: a long record of a known device followed window by window -- how many asperities "
      "slide now (n(t), 90 % band), each one's stiffness k(t) with its interval, and the onsets, releases and stiffness "
      "steps (docs/tracking.md)");
  command->add_option("record", options->record,
                      "The record: a CSV file `t,V`, an oscilloscope export (--format), a stengmc run file, or an HDF5 "
                      "dataset (--dataset)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-k,--known", options->known,
                      "The known device's study file (every device key written out, with its [inverse] prior: the band "
                      "of plausible lines; its [counterface] says whether lines stay alive)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (/tracking; default <record>_track.h5)")
      ->check(non_empty_path());
  command->add_option("--window-s", options->window_s,
                      "Window length [s] (default from the device: m/c = tau/2 unexcited, tau = 2m/c excited; 10 and 20 us "
                      "with Table 1 values)")
      ->check(CLI::PositiveNumber);
  command->add_option("--hop-s", options->hop_s, "Hop between window starts [s] (default tau/4 = 5 us, at most the window)")
      ->check(CLI::PositiveNumber);
  command->add_option("--max-wear-per-ms", options->max_wear_per_ms,
                      "Largest wear rate the prior allows [1/ms]: widens held stiffness intervals and the frequency gate")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--max-missed", options->max_missed,
                      "G: windows a track may go unheard before it ends (excited regime; at least a window's overlap)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  CLI::Option* figures =
      command->add_flag("-f,--figures", options->figures, "Also render the figure (spectrogram with tracks, n(t), k(t), events)");
  add_figure_options(command, figures, options->figure);
  command->add_option("-j,--threads", options->threads, "Threads (default: OMP_NUM_THREADS when set, else every core)")
      ->check(CLI::Range(1, MAX_THREADS));
  add_record_options(command, options->record_options);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
