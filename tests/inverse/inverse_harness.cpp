// Development harness for the inverse estimator: simulates records of a known device's
// [inverse] prior exactly as a calibration does (its prior study, realisation by realisation,
// every departure the prior draws), inverts each with RecordEstimator (raw, uncalibrated), and
// prints the count's exact rate and RMSE, the median-k error and the sd(ln k) RMSE, by n bin,
// with the CPU time per record; and for each record the oracle (RecordEstimator's reference
// fit): the search's answer beside the truth refined in full, so a wrong count is told apart
// as the search's failure (the truth, refined, explains the record better at its n) or the
// model's (the truth, refined, does not explain it to the noise). Not a test: a measuring tool whose figures go in the commit
// messages and docs/inverse.md's development notes.
//
//   inverse_harness DEVICE.toml [records] [seed] [verbose] [only record, -1: all] [SIMULATED.toml]
// With SIMULATED.toml the records are drawn from that device's prior instead (e.g. one
// departure alone) and estimated with DEVICE.toml's, as a validation family is.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "ensemble/run_realisation.hpp"
#include "ensemble/study_file.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/prior_study.hpp"
#include "inverse/record_estimator.hpp"
#include "inverse/sample_statistics.hpp"
#include "pipeline/study.hpp"
#include "pipeline/study_realisation.hpp"

using namespace stengmc;

namespace {

struct Outcome {
  bool valid = false;
  std::size_t n = 0, n_hat = 0;
  double median_true = 0, median_hat = 0, sd_true = 0, sd_hat = 0, seconds = 0, simulate_seconds = 0, top_probability = 0;
  double k_error = 0;  // largest |ln k_hat / k| over lines, when counted exactly
  ReferenceFit reference;
};

// The oracle's verdict on a record: its refined truth beside the search's fit of as many atoms.
// A misfit above 1.1 is ~3 standard deviations of a 10^4-sample record's at the noise, counting
// the chi^2 term sqrt(2/M) = 0.014 and the noise level's own estimate (a median over a few
// thousand correlated periodogram bins, ~0.02-0.03): the truth, refined, does not explain the
// record. Misfits are relative to the estimator's sigma, which carries the model's floor, so a
// model failure can hide below it, never the other way.
constexpr double MODEL_FAILS_MISFIT = 1.1;
// search: the truth refined beats the search's fit of its n by more than 1 in chi^2 (with the
// loads' prior term), or the search made none; count: it does not, and the count is still
// wrong (the evidence chose another n among fits as good as the truth's).
enum class Blame { none, search, count, model };
Blame blame(const Outcome& o, std::size_t samples) {
  const ReferenceFit& r = o.reference;
  if (r.misfit > MODEL_FAILS_MISFIT) return Blame::model;
  const double m = static_cast<double>(samples);
  const bool search_worse = r.found_misfit < 0.0 || r.found_misfit * m + r.found_penalty > r.misfit * m + r.penalty + 1.0;
  if (search_worse) return Blame::search;
  return o.n != o.n_hat ? Blame::count : Blame::none;
}

void report(const char* label, const std::vector<Outcome>& all, std::size_t lo, std::size_t hi) {
  double se = 0, sd_se = 0, seconds = 0;
  int exact = 0, count = 0, sd_count = 0;
  std::vector<double> median_errors;
  for (const Outcome& o : all) {
    if (!o.valid || o.n < lo || o.n > hi) continue;
    ++count;
    const double e = static_cast<double>(o.n_hat) - static_cast<double>(o.n);
    se += e * e, exact += e == 0.0, seconds += o.seconds;
    if (o.n > 0 && o.n_hat > 0) median_errors.push_back(std::abs(o.median_hat / o.median_true - 1.0));
    if (o.n >= 2 && o.n_hat >= 2) sd_se += (o.sd_hat - o.sd_true) * (o.sd_hat - o.sd_true), ++sd_count;
  }
  if (count == 0) return;
  std::printf("%-10s %4d  n RMSE %6.3f  exact %5.1f %%  median-k |rel err| median %.2e  sd(ln k) RMSE %.4f  %5.0f ms\n", label,
              count, std::sqrt(se / count), 100.0 * exact / count, median_errors.empty() ? 0.0 : sample_median(median_errors),
              sd_count ? std::sqrt(sd_se / sd_count) : 0.0, 1e3 * seconds / count);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: inverse_harness DEVICE.toml [records] [seed] [verbose] [only record, -1: all] [SIMULATED.toml]\n");
    return 2;
  }
  try {
    const Study device_study = read_study(argv[1], std::nullopt);
    const std::size_t records = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 100;
    const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
    const int verbose = argc > 4 ? std::atoi(argv[4]) : 0;
    // A fifth argument (-1: all) estimates that one record alone (to follow its search with STENGMC_DEBUG_SEARCH).
    const long only = argc > 5 ? std::atol(argv[5]) : -1;
    const InverseSetup setup = inverse_setup(device_study);
    const InverseSetup simulated = argc > 6 ? inverse_setup(read_study(argv[6], std::nullopt)) : setup;
    const double t0 = omp_get_wtime();
    const std::unique_ptr<AtomLibrary> atoms = build_atom_library(setup);
    std::printf("atoms built in %.1f s (%zu shapes, check %.2g)\n", omp_get_wtime() - t0,
                atoms->shapes().data().pi_nodes.size() * atoms->shapes().data().zeta_nodes.size(), atoms->check_error());
    const auto [s_low, s_high] = setup.prior.support();
    const std::string text = prior_study_text(simulated.device, simulated.prior, records, seed, 1e5, 1e7, one_asperity_rms_v(*atoms, simulated.prior));
    const StudyFile prior = parse_study_file(text, "harness prior", std::nullopt);
    (void)s_low, (void)s_high;
    std::vector<Outcome> outcomes(records);
    const double start = omp_get_wtime();
#pragma omp parallel
    {
      RecordEstimator estimator(*atoms, setup.prior);
#pragma omp for schedule(dynamic, 1)
      for (std::size_t r = 0; r < records; ++r) {
        if (only >= 0 && static_cast<long>(r) != only) continue;
        const double s0 = omp_get_wtime();
        const RealisationRecord record = run_realisation(prior, r, true);
        Outcome& o = outcomes[r];
        o.simulate_seconds = omp_get_wtime() - s0;
        if (!record.valid) continue;
        const std::vector<double>& k = record.asperities[static_cast<std::size_t>(AsperityColumn::stiffness_n_per_m)];
        try {
          // The truth's loads and onsets: the realisation's population drawn again.
          std::vector<ParameterOverride> overrides;
          for (const RecordExtra& x : record.extras)
            if (x.name.rfind("draw:", 0) == 0) overrides.push_back({x.name.substr(5), x.values.front()});
          const Study drawn = study_for_realisation(parse_study(text, "harness prior", std::nullopt, overrides), r);
          std::vector<Asperity> truth = drawn.asperities;
          std::sort(truth.begin(), truth.end(), [](const Asperity& a, const Asperity& b) { return a.stiffness_n_per_m < b.stiffness_n_per_m; });
          // The oracle's start: the true atoms, the device's shared parameters as written. A
          // record of the tolerance prior has its own; the refinement moves the damping, the
          // load factor, the amplitude and the offset, not the friction coefficients (which the
          // atoms' shapes hold fixed), so there it is the best the model can do, not the truth.
          FitState reference;
          reference.damping_rate_per_s = estimator.layout().nominal_damping_rate;
          for (const Asperity& a : truth) reference.atoms.push_back({a.stiffness_n_per_m, a.normal_load_n, a.onset_s});
          const RecordEstimate e = estimator.estimate(record.measured_voltage_v, &reference);
          o.reference = *e.reference;
          o.valid = true;
          o.n = k.size();
          o.n_hat = e.count;
          o.median_true = sample_median(k);
          o.median_hat = e.median_stiffness_n_per_m;
          o.sd_true = sample_sd_log(k);
          o.sd_hat = e.sd_log_stiffness;
          o.seconds = e.seconds;
          for (std::size_t j = 0; j < e.posterior.counts.size(); ++j)
            if (e.posterior.counts[j] == e.count) o.top_probability = e.posterior.probability[j];
          if (o.n == o.n_hat) {
            std::vector<double> true_k = k;
            std::sort(true_k.begin(), true_k.end());
            for (std::size_t i = 0; i < true_k.size(); ++i) o.k_error = std::max(o.k_error, std::abs(std::log(e.lines[i].stiffness_n_per_m / true_k[i])));
          }
          if (verbose || o.n != o.n_hat) {
#pragma omp critical
            {
              std::printf("record %zu: n %zu -> %zu (P %.3f, %.0f ms; misfit %.2f, line band %.2f, low %.2f, early %.2f, late %.2f)\n", r,
                          o.n, o.n_hat, o.top_probability, 1e3 * e.seconds, e.checks.misfit, e.checks.line_band,
                          e.checks.low_band, e.checks.early, e.checks.late);
              const ReferenceFit& f = o.reference;
              std::printf("   oracle: truth %.3f, refined %.3f (penalty %.1f, %zu steps); the search's n = %zu: %.3f (penalty %.1f)\n",
                          f.start_misfit, f.misfit, f.penalty, f.iterations, o.n, f.found_misfit, f.found_penalty);
              if (verbose > 1 || o.n != o.n_hat) {
                for (const Asperity& a : truth)
                  std::printf("   true k %8.3f N %.3e on %6.3f us\n", a.stiffness_n_per_m, a.normal_load_n, 1e6 * a.onset_s);
                for (const EstimatedLine& l : e.lines)
                  std::printf("   est  k %8.3f N %.3e on %6.3f us (se ln k %.1e)\n", l.stiffness_n_per_m, l.load_n, 1e6 * l.onset_s,
                              l.log_stiffness_se);
              }
            }
          }
        } catch (const Error& e) {
#pragma omp critical
          std::printf("record %zu: %s\n", r, e.what());
        }
      }
    }
    double simulate = 0;
    int valid = 0;
    for (const Outcome& o : outcomes)
      if (o.valid) simulate += o.simulate_seconds, ++valid;
    std::printf("%zu records (%d valid), seed %llu: wall %.1f s; simulation %.0f ms per record\n", records, valid,
                static_cast<unsigned long long>(seed), omp_get_wtime() - start, valid ? 1e3 * simulate / valid : 0.0);
    report("all", outcomes, 0, 1000);
    int blamed[4] = {0, 0, 0, 0}, wrong_blamed[4] = {0, 0, 0, 0};
    for (const Outcome& o : outcomes) {
      if (!o.valid) continue;
      const auto b = static_cast<std::size_t>(blame(o, setup.grid.samples));
      ++blamed[b];
      if (o.n != o.n_hat) ++wrong_blamed[b];
    }
    std::printf("oracle (the truth refined, misfit > %.1f: the model fails; else better than the search's fit of its n: the search "
                "fails; else a wrong count: the count's rule fails): model fails %d (wrong counts %d), search fails %d (wrong counts %d), "
                "count's rule fails %d, neither %d\n",
                MODEL_FAILS_MISFIT, blamed[3], wrong_blamed[3], blamed[1], wrong_blamed[1], blamed[2], blamed[0]);
    report("n 0", outcomes, 0, 0);
    report("n 1-4", outcomes, 1, 4);
    report("n 5-8", outcomes, 5, 8);
    report("n 9-12", outcomes, 9, 12);
    report("n 13-16", outcomes, 13, 16);
    std::vector<double> k_errors;
    for (const Outcome& o : outcomes)
      if (o.valid && o.n == o.n_hat && o.n > 0) k_errors.push_back(o.k_error);
    if (!k_errors.empty()) std::printf("worst line |ln k error| in exact records: median %.2e\n", sample_median(k_errors));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
