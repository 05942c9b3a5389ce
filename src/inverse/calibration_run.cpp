#include "inverse/calibration_run.hpp"

#include <omp.h>

#include <chrono>
#include <ctime>
#include <cmath>
#include <memory>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "inverse/device_checks.hpp"
#include "inverse/forward_atom.hpp"
#include "inverse/inversion_work.hpp"
#include "inverse/naive_count.hpp"
#include "inverse/prior_study.hpp"
#include "inverse/record_estimator.hpp"

namespace stengmc {

namespace {

// The prior's lines must sit below Nyquist with room for the noise band above them.
constexpr double NYQUIST_MARGIN = 1.25;

double line_frequency_hz(const KnownDevice& device, double k) { return device.angular_frequency(k) / (2.0 * PI); }

//! One estimator and naive counter per thread, made on first use.
struct Worker {
  RecordEstimator estimator;
  NaiveCounter naive;
  Worker(const AtomTable& atoms, const InversePrior& prior, double band_low, double band_high)
      : estimator(atoms, prior), naive(atoms.grid().samples, atoms.grid().sample_rate_hz(), band_low, band_high) {}
};

}  // namespace

InverseSetup inverse_setup(const Study& study, std::optional<RecordGrid> grid) {
  InverseSetup setup;
  setup.device = known_device_from_study(study);
  setup.prior = inverse_prior_of_study(study.text, study.file);
  setup.grid = grid ? *grid : device_grid(setup.device);
  const double k_high = setup.prior.support().second;
  const double f_high = line_frequency_hz(setup.device, k_high);
  if (setup.grid.sample_rate_hz() < 2.0 * NYQUIST_MARGIN * f_high)
    throw InputError("the record's sample rate " + format_number(setup.grid.sample_rate_hz()) +
                     " Hz is too low for the prior's highest line: " + format_number(f_high) + " Hz (k = " +
                     format_number(k_high) + " N/m, the 1 - 1e-4 quantile of the stiffness prior of " + study.file +
                     "); lines and the noise band above them need at least " +
                     format_number(2.0 * NYQUIST_MARGIN * f_high) + " Hz");
  check_device_over_prior(study, setup.device, setup.prior, setup.grid);
  check_prior_over_device(study, setup.device, setup.prior, setup.grid);
  setup.identity = bank_identity(setup.device, setup.prior, setup.grid);
  return setup;
}

double one_asperity_rms_v(const AtomTable& atoms, const InversePrior& prior) {
  const auto [low, high] = prior.support();
  const RecordModel model(atoms);
  std::vector<double> v(atoms.grid().samples);
  model.evaluate(std::vector<double>{std::sqrt(low * high)}, v);
  double square = 0.0;
  for (double x : v) square += x * x / static_cast<double>(v.size());
  return std::sqrt(square);
}

std::pair<double, double> atom_range(const InverseSetup& setup) {
  const auto [lowest, highest] = simulated_stiffness_range(setup.prior);
  const double valid =
      smallest_valid_stiffness(setup.device, setup.grid.at(setup.grid.samples - 1), setup.grid.step_s, lowest, highest);
  if (!(valid < highest)) {
    const auto [first, second] = setup.prior.parameter_keys();
    throw InputError(setup.device.study_file + ": [inverse] " + first + ", " + second + ": every stiffness of the prior (up to " +
                     format_number(highest) + " N/m) is too soft for the known device: its asperity reaches its element's "
                     "length l = " + format_number(setup.device.asperity.element.length_m) + " m (length_m) within the " +
                     format_number(setup.grid.duration_s()) + " s record" +
                     (std::isfinite(valid) ? " below " + format_number(valid) + " N/m" : "") +
                     ". Give a prior of stiffer asperities, or check normal_load_n, static_friction and length_m");
  }
  return {std::max(lowest, valid), highest};
}

CalibrationBank run_calibration(const Study& device_study, const std::string& journal_path, const CalibrationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CalibrationBank bank;
  bank.setup = inverse_setup(device_study);
  InversePrior& prior = bank.setup.prior;
  if (options.records) prior.calibration_records = *options.records;
  if (options.seed) prior.seed = *options.seed;
  bank.device_study_file = device_study.file;
  bank.device_study_text = device_study.text;
  if (bank.setup.grid.start_s != 0.0) throw InputError("a calibration simulates records from t = 0");
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  check_work(estimate_inversion(device_study, bank.setup,
                                {.records = prior.calibration_records, .threads = threads, .simulates_records = true}),
             options.limits,
             device_study.file + ": the calibration's " + std::to_string(prior.calibration_records) + " records of " +
                 std::to_string(bank.setup.grid.samples) + " samples (--records, or [inverse] calibration_records)",
             options.limit_names);

  const auto [k_low, k_high] = atom_range(bank.setup);
  const AtomTable atoms(bank.setup.device, bank.setup.grid, k_low, k_high);
  bank.atoms = atoms.data();
  bank.atom_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const auto [s_low, s_high] = prior.support();
  const double band_low = line_frequency_hz(bank.setup.device, s_low), band_high = line_frequency_hz(bank.setup.device, s_high);
  bank.prior_study_text = prior_study_text(bank.setup.device, prior, prior.calibration_records, prior.seed, band_low,
                                          band_high, one_asperity_rms_v(atoms, prior));
  const StudyFile prior_study = parse_study_file(bank.prior_study_text, device_study.file + " (calibration prior)", std::nullopt);

  std::vector<std::unique_ptr<Worker>> workers(static_cast<std::size_t>(std::max(threads, omp_get_max_threads())));
  RealisationHook hook;
  hook.needs_traces = true;
  // The estimates depend on the atoms (a function of the device, grid and program, all in
  // the identity) and on the estimator's version.
  hook.identity = "inverse calibration\n" + std::to_string(bank.setup.identity.hash);
  hook.apply = [&](RealisationRecord& record) {
    if (record.valid && !record.measured_voltage_v.empty()) {
      auto& worker = workers[static_cast<std::size_t>(omp_get_thread_num())];
      if (!worker) worker = std::make_unique<Worker>(atoms, prior, band_low, band_high);
      try {
        const RecordEstimate estimate = worker->estimator.estimate(record.measured_voltage_v);
        store_estimate(record, estimate, worker->naive.count(record.measured_voltage_v, naive_count_thresholds()));
      } catch (const ModelError& e) {
        // A record the estimator cannot answer is an invalid record of the bank, said with
        // its reason, as one whose asperity reached l: not a calibration that stops.
        record.valid = false;
        record.failure = std::string("the estimator: ") + e.what();
      }
    }
    // The bank keeps the estimates, not the traces (10^4 records x 10^4 samples would not fit):
    // their memory is released, not only their size (clear() keeps the capacity, ~32 bytes
    // per sample of every record until the bank is written).
    for (std::vector<double>* trace : {&record.time_s, &record.voltage_v, &record.charge_c, &record.measured_voltage_v})
      std::vector<double>().swap(*trace);
  };
  EnsembleOptions ensemble_options;
  ensemble_options.progress_label = "calibration";
  ensemble_options.threads = threads;
  ensemble_options.restart = options.restart;
  ensemble_options.show_progress = options.show_progress;
  ensemble_options.limits = options.limits;
  const std::clock_t cpu_start = std::clock();  // process CPU time, all threads
  const EnsembleRun run = run_ensemble(prior_study, journal_path, ensemble_options, hook);
  if (run.worker) {
    bank.worker = true;
    return bank;
  }
  bank.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  bank.resumed = run.resumed;
  bank.threads = run.threads;

  const std::string first_key = std::string("surface.stiffness.") + (prior.family == StiffnessFamily::lognormal ? "median" : "shape");
  const std::string second_key = std::string("surface.stiffness.") + (prior.family == StiffnessFamily::lognormal ? "sigma_log" : "scale");
  for (const RealisationRecord& r : run.records) {
    bank.samples.push_back(calibration_sample(r, first_key, second_key));
    bank.estimation_cpu_seconds += bank.samples.back().seconds;
  }
  bank.maps = fit_calibration_maps(bank.samples, prior);
  bank.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bank;
}

}  // namespace stengmc
