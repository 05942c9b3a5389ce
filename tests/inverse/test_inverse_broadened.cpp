// The inverse estimation under a broadened prior (issue 23: per-asperity loads and contact
// onsets, a device known within a tolerance, coloured noise and an offset, counts from 0),
// on records simulated by the forward model end to end (tribology of every asperity, the
// shared circuit): what the estimator never saw but the truth it is compared with.
#include <gtest/gtest.h>

#include <array>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/random_stream.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/inversion.hpp"
#include "inverse/fit_layout.hpp"
#include "inverse/load_prior.hpp"
#include "inverse/nested_search.hpp"
#include "inverse/noise_judge.hpp"
#include "inverse/record_fit.hpp"
#include "inverse/record_model.hpp"
#include "inverse/simulated_record.hpp"
#include "pipeline/measurement_noise.hpp"
#include "pipeline/study.hpp"
#include "support/cli_runner.hpp"
#include "support/held_out_coverage.hpp"
#include "support/inverse_device.hpp"
#include "support/must_show_record.hpp"

namespace stengmc {
namespace {

using testing::known_device_study;
using testing::ScratchDir;

//! `record` with white Gaussian noise of `sigma_v` added from stream `seed` [V].
void add_white_noise(std::vector<double>& record, double sigma_v, std::uint64_t seed) {
  RandomEngine engine = random_stream(seed, 0, StreamKind::noise);
  boost::random::normal_distribution<double> noise(0.0, sigma_v);
  for (double& v : record) v += noise(engine);
}

double rms(const std::vector<double>& v) {
  double mean = 0.0, s = 0.0;
  for (double x : v) mean += x / static_cast<double>(v.size());
  for (double x : v) s += (x - mean) * (x - mean) / static_cast<double>(v.size());
  return std::sqrt(s);
}

//! The broadened prior of studies/inverse/device_vb10_real.toml (counts 0-16, loads spread by
//! a CV up to 0.6, onsets within 20 us, +-5 % parameters, coloured noise and an offset) on the
//! known device's 100 us records.
InverseSetup broadened_vb10_setup() {
  return inverse_setup(parse_study(known_device_study("100e-6", "count = [0, 16]\nload_cv = [0, 0.6]\nonset_s = [0, 20e-6]\n"
                                                                "parameter_tolerance = 0.05\nnoise = \"coloured\"\noffset = true\n"),
                                   "broadened_vb10.toml", std::nullopt));
}

//! The raw inversion of the forward model's record of `truth` with white noise at `snr_db`
//! (of the record's rms) drawn from stream `seed`.
Inversion invert_simulated(const InverseSetup& setup, const AtomLibrary& library, const std::vector<SimulatedAsperity>& truth,
                           double snr_db, std::uint64_t seed) {
  std::vector<double> record = simulate_record(setup.device, truth, setup.grid);
  add_white_noise(record, std::pow(10.0, -snr_db / 20.0) * rms(record), seed);
  Inverter inverter(setup, library, nullptr);
  return inverter.invert("simulated record", record);
}

//! The count exact and each line's k within 1 % of its asperity's (`truth` ascending in k).
void expect_count_and_stiffnesses(const Inversion& result, const std::vector<SimulatedAsperity>& truth) {
  EXPECT_EQ(result.raw.count, truth.size());
  ASSERT_EQ(result.raw.lines.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_NEAR(result.raw.lines[i].stiffness_n_per_m / truth[i].stiffness_n_per_m, 1.0, 1e-2) << "line " << i;
}

//! A loads-family record under the broadened prior: asperities of stiffness k [N/m] and load
//! factor x the device's load, all from t = 0, white noise at `snr_db` from stream `seed`;
//! the count exact and each k within 1 %.
void expect_loads_record_counted(const std::vector<std::pair<double, double>>& k_and_load_factor, double snr_db,
                                 std::uint64_t seed) {
  const InverseSetup setup = broadened_vb10_setup();
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  std::vector<SimulatedAsperity> truth;
  for (const auto& [k, factor] : k_and_load_factor) truth.push_back({k, factor * setup.device.asperity.normal_load_n, 0.0});
  expect_count_and_stiffnesses(invert_simulated(setup, *library, truth, snr_db, seed), truth);
}

TEST(InverseBroadened, FourAsperitiesOfUnequalLoadsAndOnsets) {
  // The must-show record (support/must_show_record.hpp).
  const InverseSetup setup = inverse_setup(testing::unequal_loads_and_onsets_study());
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  const std::vector<SimulatedAsperity> truth = testing::four_unequal_loads_and_onsets(setup.device.asperity.normal_load_n);
  // 40 dB: the prior's highest SNR.
  expect_count_and_stiffnesses(invert_simulated(setup, *library, truth, 40.0, 3), truth);
}

// The twelve asperities (stiffnesses and loads, all from t = 0) of the loads family's held-out
// realisation 1, on another noise draw. Two of them lie a quarter of a line width apart (72.55
// and 72.99 N/m; a line width, d / pi in Hz, is 4 d / omega = 2.3 % in ln k there) with loads
// 0.74 and 1.42 x the device's. Their sum is one line that no single atom of any load fits: the
// search fitted one atom of load 1.09 x and patched its misfit with weak atoms (16 atoms, on this
// draw as on the held-out one). Split a quarter of a width apart where the residual's power
// around a line is largest, the refit finds both (LineSearch::split's narrow splits).
TEST(InverseBroadened, TwoAsperitiesAQuarterLineWidthApartWithUnequalLoadsAreBothFound) {
  expect_loads_record_counted({{50.03, 0.415}, {51.33, 1.112}, {52.72, 1.148}, {64.89, 0.811}, {72.55, 0.744}, {72.99, 1.42},
                               {76.35, 0.679}, {87.15, 1.339}, {105.82, 1.549}, {112.11, 0.954}, {114.89, 1.016}, {120.82, 0.877}},
                              25.2, 11);
}

// The fourteen asperities (stiffnesses and loads, all from t = 0) of the loads family's
// held-out realisation 5, on another noise draw at its SNR. Estimator version 5 counted 16, on
// the held-out draw and on this one: its re-seating left two atoms on one asperity's line (one's
// breakaway and amplitude patched by the other, a local minimum no refit leaves) while another
// line went without its atom, and patched the misfit with weak atoms. Merging such a pair to
// free an atom for the missing line (LineSearch::merge; LineSearch::cross also runs) reaches
// the fit of the truth. With both moves switched off this record still gets 16 (checked).
TEST(InverseBroadened, FourteenUnequalLoadsAreCountedOnceAtomsSharingALineAreMerged) {
  expect_loads_record_counted({{36.6764, 1.10178},
                               {40.9726, 0.978608},
                               {61.2235, 0.863717},
                               {62.5241, 1.16465},
                               {66.1927, 1.20662},
                               {67.9633, 1.57179},
                               {71.7745, 0.739067},
                               {77.0988, 0.331769},
                               {95.3438, 0.488244},
                               {102.3538, 1.70997},
                               {103.7783, 0.704793},
                               {106.6511, 0.671262},
                               {119.9542, 1.16248},
                               {206.5409, 1.48663}},
                              21.96, 12);
}

// Records of the ideal device under the broadened prior of studies/inverse/device_vb10_real.toml
// (loads spread by a CV up to 0.6, onsets within 20 us, +-5 % parameters, coloured noise and an
// offset): asperities of the device's load, all from t = 0. Such a record is a point of the
// broadened model, so its count must stay what the ideal device's estimator finds. The
// stiffnesses and SNRs are those of the held-out ideal family's records 26 and 12, which the
// broadened search alone counted as 12 and 16 (it left atoms a tail period off and patched them
// with weak low-load ones; on this noise draw the second still gets 16 without the nested
// model's starts, inverse/nested_search.hpp).
TEST(InverseBroadened, AnIdealRecordKeepsItsCountUnderTheBroadenedPrior) {
  const InverseSetup setup = broadened_vb10_setup();
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  struct Case {
    std::vector<double> k;
    double snr_db;
  };
  for (const Case& c : {Case{{78.19, 79.2, 90.42, 97.23, 127.29}, 24.0},
                        Case{{78.48, 81.38, 95.34, 113.53, 127.39, 141.36, 158.69}, 32.9}}) {
    SCOPED_TRACE(std::to_string(c.k.size()) + " asperities");
    std::vector<double> record = simulate_record(setup.device, c.k, setup.grid);
    add_white_noise(record, std::pow(10.0, -c.snr_db / 20.0) * rms(record), c.k.size());
    Inverter inverter(setup, *library, nullptr);
    const Inversion result = inverter.invert("ideal record", record);
    EXPECT_EQ(result.raw.count, c.k.size());
    if (result.raw.lines.size() != c.k.size()) continue;
    for (std::size_t i = 0; i < c.k.size(); ++i)
      EXPECT_NEAR(result.raw.lines[i].stiffness_n_per_m / c.k[i], 1.0, 1e-2) << "line " << i;
  }
}

// The loads family's held-out realisation 32 (seed 2102; loads of a Greenwood-Williamson law of CV 0.51):
// three asperities from t = 0 whose loads are 0.40, 1.35 and 0.48 x the device's. The model fits
// the truth to the noise, yet the broadened search alone gave 16 atoms: its first atoms took
// onsets of 5 and 7 us with low loads (a late plateau for an early breakaway) and weak atoms
// patched the rest. The search with loads alone free (nested_search.hpp) finds the three.
TEST(InverseBroadened, ThreeUnequalLoadsFromTheStartAreCountedExactly) {
  const InverseSetup setup = broadened_vb10_setup();
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  const double n0 = setup.device.asperity.normal_load_n;
  const std::vector<SimulatedAsperity> truth = {{54.0, 0.395 * n0, 0.0}, {57.9, 1.348 * n0, 0.0}, {66.6, 0.479 * n0, 0.0}};
  const Inversion result = invert_simulated(setup, *library, truth, 28.3, 5);
  expect_count_and_stiffnesses(result, truth);
  if (result.raw.lines.size() != truth.size()) return;
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_NEAR(result.raw.lines[i].load_n / truth[i].normal_load_n, 1.0, 0.1) << "line " << i;
}

// The loads family's held-out realisation 2: eleven asperities from t = 0 whose
// Greenwood-Williamson loads lie 0.21-1.96 x the device's, two pairs of lines within 0.3-0.8 %
// in k, at 23.6 dB. The truth, refined, fits to the noise (RSS 0.97 M sigma^2), but the loads-
// alone search stopped at 1.09 M sigma^2 with 13 atoms and the estimate had 15: one atom had a
// load a few breakaway periods off (its tail in phase, its plateau not), and the search re-
// seated atoms only of orders above 1.5 M sigma^2, a bound far above "fits to the noise"
// (1.07 M). Re-seated below it, the eleven are found.
TEST(InverseBroadened, ElevenUnequalLoadsAreFoundByReseatingOrdersThatDoNotFitTheNoise) {
  const InverseSetup setup = broadened_vb10_setup();
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  const std::vector<SimulatedAsperity> truth = {
      {37.8025, 1.95993e-3, 0.0}, {41.4391, 2.10464e-4, 0.0}, {52.7106, 7.22485e-4, 0.0}, {53.1211, 2.19371e-4, 0.0},
      {55.0688, 8.82966e-4, 0.0}, {55.2149, 6.50663e-4, 0.0}, {57.8553, 8.96691e-4, 0.0}, {76.3395, 1.06679e-3, 0.0},
      {88.6729, 6.03115e-4, 0.0}, {103.3423, 1.11711e-3, 0.0}, {115.6991, 1.31947e-3, 0.0}};
  expect_count_and_stiffnesses(invert_simulated(setup, *library, truth, 23.6, 2), truth);
}

// Which simpler models a prior contains (nested_search.hpp): the ideal device's whenever it
// frees loads or onsets, loads alone and onsets alone when it frees both, none otherwise; the
// tolerance, noise and offset kept as written.
TEST(NestedPriors, AreTheSimplerModelsThePriorContains) {
  InversePrior ideal;
  EXPECT_TRUE(nested_priors(ideal).empty());
  InversePrior both = ideal;
  both.load_cv = {0.2, 0.6};
  both.onset_s = {1e-6, 20e-6};
  both.parameter_tolerance = 0.05;
  both.noise = NoiseColour::coloured;
  both.offset = true;
  const std::vector<InversePrior> nested = nested_priors(both);
  ASSERT_EQ(nested.size(), 3u);
  EXPECT_EQ(nested[0].load_cv, (std::array<double, 2>{0.0, 0.0}));
  EXPECT_EQ(nested[0].onset_s, (std::array<double, 2>{1e-6, 1e-6}));
  EXPECT_EQ(nested[1].load_cv, both.load_cv);
  EXPECT_EQ(nested[1].onset_s, (std::array<double, 2>{1e-6, 1e-6}));
  EXPECT_EQ(nested[2].load_cv, (std::array<double, 2>{0.0, 0.0}));
  EXPECT_EQ(nested[2].onset_s, both.onset_s);
  for (const InversePrior& p : nested) {
    EXPECT_EQ(p.parameter_tolerance, 0.05);
    EXPECT_EQ(p.noise, NoiseColour::coloured);
    EXPECT_TRUE(p.offset);
    EXPECT_EQ(p.count_max, both.count_max);
  }
  InversePrior loads_only = ideal;
  loads_only.load_cv = {0.0, 0.3};
  ASSERT_EQ(nested_priors(loads_only).size(), 1u);
  EXPECT_EQ(nested_priors(loads_only)[0].load_cv, (std::array<double, 2>{0.0, 0.0}));
}

//! An ideal record (the five asperities of the held-out ideal family's record 26, the device's
//! load, all from t = 0) in 70 % 1/f noise at 26 dB with a 10 mV offset (noise stream 7), and
//! what fitting it under broadened_vb10_setup's prior needs.
struct ColouredIdealRecord {
  InverseSetup setup = broadened_vb10_setup();
  std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  std::vector<double> k = {78.19, 79.2, 90.42, 97.23, 127.29};
  std::vector<double> voltage_v;
  double white_sigma_v = 0.0;  //!< the level of the noise's white part [V]
  RecordModel model{*library};
  LoadPrior loads{setup.prior};
  FitLayout layout = fit_layout(setup.prior, setup.device, loads);

  ColouredIdealRecord() {
    const std::vector<double> clean = simulate_record(setup.device, k, setup.grid);
    const NoiseSettings settings{.snr_db = 26.0, .coloured_share = 0.7, .coloured_exponent = 1.0, .offset_v = 0.01};
    RandomEngine white = random_stream(7, 0, StreamKind::noise, 0), coloured = random_stream(7, 0, StreamKind::noise, 1);
    NoisyVoltage noisy = measure_voltage(clean, 0, clean.size(), setup.grid.sample_rate_hz(), settings, white, coloured);
    voltage_v = std::move(noisy.voltage_v);
    white_sigma_v = std::sqrt(1.0 - settings.coloured_share) * noisy.sigma_v;
  }
};

// Whether a nested model fits a record to its noise is judged against the noise the estimator
// will assume. An ideal record (five asperities of the held-out ideal family's record 26) under
// 70 % 1/f noise and an offset is a point of the ideal model: whitened by the spectrum fitted to
// its residual, the ideal model's RSS is chi^2_M, so the ideal level fits and the broadened
// search is not needed. Against the white part alone (the level above the lines) the same fit
// is ~3 x the noise and no level would fit: every such record then paid for all three nested
// searches and the broadened one (a held-out coloured-noise record took 300 s, now 38 s).
TEST(NestedSearch, AnIdealRecordInColouredNoiseFitsTheIdealModelOnceWhitened) {
  const ColouredIdealRecord r;
  const InverseSetup& setup = r.setup;
  const std::vector<double>& k = r.k;
  ASSERT_TRUE(r.layout.coloured_noise);
  NestedSearch nested(r.model, setup.prior, setup.device, LineSearchOptions{});
  const auto innovation = [](const Whitener& w) { return w.innovation_sigma_v(); };
  const NestedFits whitened = nested.search(r.voltage_v, r.white_sigma_v, r.layout, 9, 0, innovation);
  ASSERT_GT(whitened.fitted_orders.size(), k.size()) << "no nested model fitted the whitened record";
  const std::vector<AtomParameters>& atoms = whitened.fitted_orders[k.size()].atoms;
  for (std::size_t i = 0; i < k.size(); ++i) EXPECT_NEAR(atoms[i].stiffness_n_per_m / k[i], 1.0, 1e-2) << "line " << i;
  EXPECT_TRUE(nested.search(r.voltage_v, r.white_sigma_v, r.layout, 9, 0).fitted_orders.empty())
      << "judged against the white part alone, a model fitted the coloured record";
}

// The judge behind both (noise_judge.hpp), on the same kind of record fitted from the truth:
// whitened by its residual's spectrum, the truth's fit of five lines in 70 % 1/f noise fits to
// the noise, and against the white part alone it does not; the fit that lacks one of the
// lines must not fit whitened either (a whitener fitted to a residual holding a line could
// swallow it: the spectrum's band medians must leave it out).
TEST(NoiseJudge, JudgesAColouredRecordWhitenedWithoutHidingAMissingLine) {
  const ColouredIdealRecord r;
  const InverseSetup& setup = r.setup;
  const std::vector<double>& k = r.k;
  RecordFit fit(r.model, r.layout, r.loads, r.voltage_v);
  fit.set_noise(Whitener(), r.white_sigma_v);
  FitState truth;
  truth.damping_rate_per_s = r.layout.nominal_damping_rate;
  for (double ki : k) truth.atoms.push_back({ki, setup.device.asperity.normal_load_n, 0.0});
  FitState missing = truth;
  missing.atoms.erase(missing.atoms.begin() + 2);
  const OrderFit full = fit.refine(truth, {}, true, false), lacking = fit.refine(missing, {}, true, false);

  const NoiseJudge whitened([](const Whitener& w) { return w.innovation_sigma_v(); }), white_only;
  const auto m = static_cast<double>(r.voltage_v.size());
  std::printf("chi2 / M: the truth's fit whitened %.3f, white %.3f; without the 90 N/m line whitened %.3f (fits below %.3f)\n",
              whitened.chi2(fit, full) / m, white_only.chi2(fit, full) / m, whitened.chi2(fit, lacking) / m,
              fitting_chi2(r.voltage_v.size()) / m);
  EXPECT_TRUE(whitened.fits(fit, full));
  EXPECT_FALSE(white_only.fits(fit, full));
  EXPECT_FALSE(whitened.fits(fit, lacking));
  EXPECT_TRUE(fit.whitener().identity()) << "the judge left its whitener on the fit";
  EXPECT_EQ(fit.sigma_v(), r.white_sigma_v);
}

// The judge asks more than a chi^2 within its bound: that the residual be noise throughout the
// record (residual_segments.hpp). The same five lines under white noise at 26 dB, fitted from
// the truth, fit. With a transient added in the first microseconds, where a wrong load or onset
// leaves its misfit (a 4 MHz ringing, away from the lines so that no refit of them absorbs it,
// decaying in 1 us, energy 0.03 M sigma^2: chi^2 / M ~1.03, inside the bound of 1.07), the
// truth's fit no longer explains the record, and the judge must say so though the global
// chi^2 alone would not.
TEST(NoiseJudge, AMisfitAtTheBreakawayDoesNotFitThoughItsChiSquareDoes) {
  const ColouredIdealRecord r;  // for its device, prior and lines; the noise is drawn here
  const std::vector<double> clean = simulate_record(r.setup.device, r.k, r.setup.grid);
  const double sigma = 0.05 * rms(clean);  // 26 dB
  std::vector<double> record = clean;
  add_white_noise(record, sigma, 3);
  const auto m = static_cast<double>(record.size());
  // A transient at the breakaway: a 4 MHz ringing decaying with tau = 1 us, 0.03 M sigma^2.
  std::vector<double> burst(record.size());
  double energy = 0.0;
  for (std::size_t t = 0; t < record.size(); ++t) {
    const double time_s = static_cast<double>(t) / r.setup.grid.sample_rate_hz();
    burst[t] = std::exp(-time_s / 1e-6) * std::sin(2.0 * std::numbers::pi * 4e6 * time_s);
    energy += burst[t] * burst[t];
  }
  std::vector<double> transient = record;
  for (std::size_t t = 0; t < record.size(); ++t) transient[t] += std::sqrt(0.03 * m * sigma * sigma / energy) * burst[t];
  FitState truth;
  truth.damping_rate_per_s = r.layout.nominal_damping_rate;
  for (double ki : r.k) truth.atoms.push_back({ki, r.setup.device.asperity.normal_load_n, 0.0});
  const NoiseJudge white;
  for (const bool misfit : {false, true}) {
    RecordFit fit(r.model, r.layout, r.loads, misfit ? transient : record);
    fit.set_noise(Whitener(), sigma);
    const OrderFit f = fit.refine(truth, {}, true, false);
    const NoiseJudge::Judgement j = white.judge(fit, f);
    std::printf("%s: chi2 / M %.4f (bound %.4f), worst segment %zu-%zu p %.3g (bound %.3g)\n", misfit ? "with a transient" : "without",
                j.chi2 / m, fitting_chi2(record.size()) / m, j.worst.first_sample, j.worst.last_sample, j.worst.p_value,
                bonferroni_p_bound(FITS_SIGMAS, j.worst.segments));
    EXPECT_LE(j.chi2, fitting_chi2(record.size())) << "the misfit is not diluted: the test tests nothing";
    EXPECT_EQ(j.fits, !misfit);
  }
}

TEST(InverseBroadened, PureNoiseHasNoSlidingAsperity) {
  // Noise alone, white and with the broadened prior's coloured noise and offset in mind: no
  // atom explains it better than the noise does, so n = 0. The noise is that of a record at
  // 30 dB with one asperity (the record's scale is the device's).
  for (const char* extra : {"", "noise = \"coloured\"\noffset = true\nparameter_tolerance = 0.05\n"}) {
    SCOPED_TRACE(extra);
    const Study study = parse_study(
        known_device_study("30e-6", std::string("count = [0, 6]\nload_cv = [0.2, 0.6]\nonset_s = [0, 5e-6]\n") + extra),
        "noise.toml", std::nullopt);
    const InverseSetup setup = inverse_setup(study);
    const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
    const std::vector<double> one = simulate_record(setup.device, std::vector<double>{75.0}, setup.grid);
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      std::vector<double> record(setup.grid.samples, 0.0);
      add_white_noise(record, 0.0316 * rms(one), seed);
      Inverter inverter(setup, *library, nullptr);
      EXPECT_EQ(inverter.invert("noise", record).raw.count, 0u) << "seed " << seed;
    }
  }
}

TEST(InverseBroadened, NinetyPercentIntervalsCoverHeldOutRecords) {
  // A small calibration of the broadened prior (200 records, seed 21) and 400 held-out
  // records of the same prior with another seed (22): the held-out records' 90 % intervals,
  // calibrated by the first bank's maps, must cover their truths in 0.83-0.97 of the records
  // (one sd of a true 0.90 over 400 records is 0.015). Cheap records (30 us, 0-5
  // asperities) keep it to a few minutes on two cores. 400, not 200: the warnings need ten
  // wrong counts to be judged on; estimator version 5 got 9 of the first 200 wrong, version 7
  // 9 of the first 300.
  const std::string prior =
      "count = [0, 5]\nmedian_n_per_m = [50, 100]\nsigma_log = [0.2, 0.5]\nload_cv = [0.2, 0.6]\nonset_s = [0, 5e-6]\n"
      "parameter_tolerance = 0.05\nnoise = \"coloured\"\noffset = true\n";
  const std::string inverse = prior + "calibration_records = 200\n";
  ScratchDir scratch("inverse-broadened-coverage");
  CalibrationOptions options;
  options.show_progress = false;
  options.seed = 21;
  const Study study = parse_study(known_device_study("30e-6", inverse), "broadened.toml", std::nullopt);
  const CalibrationBank bank = run_calibration(study, scratch.file("bank.journal"), options);
  options.seed = 22;
  const Study held_out_study =
      parse_study(known_device_study("30e-6", prior + "calibration_records = 400\n"), "broadened_held_out.toml", std::nullopt);
  const CalibrationBank held_out = run_calibration(held_out_study, scratch.file("held_out.journal"), options);

  const testing::HeldOutCoverage coverage = testing::held_out_coverage(bank, held_out);
  ASSERT_GE(coverage.records, 380u);
  const double count_coverage = coverage.count(), median_coverage = coverage.median(), sd_coverage = coverage.sd();
  std::printf("broadened prior, held-out coverage of the 90 %% intervals: n %.3f (%zu records), median %.3f (%zu), "
              "sd(ln k) %.3f (%zu)\n",
              count_coverage, coverage.records, median_coverage, coverage.median_records, sd_coverage, coverage.sd_records);
  // The warnings on the fit are the misfit class's (Inverter::invert): a residual above the
  // noise, or a line the record does not pin.
  std::size_t wrong = 0, wrong_flagged = 0, right = 0, right_flagged = 0, top_right = 0, top_right_flagged = 0;
  for (const CalibrationSample& s : held_out.samples) {
    if (!s.valid) continue;
    const bool flagged = calibrate_estimate(s.raw_estimate(), &bank.maps, bank.setup.prior).fit_class == FitClass::misfits;
    if (s.count != s.true_count()) ++wrong, wrong_flagged += flagged;
    else if (s.count < bank.setup.prior.count_max) ++right, right_flagged += flagged;
    else ++top_right, top_right_flagged += flagged;
  }
  std::printf("the misfit warnings (residual > %.3g x the noise, or a line's ln k error > %.2g) on %zu of %zu wrong counts, "
              "%zu of %zu right ones below the prior's top count, %zu of %zu right ones at it; bank classes: %zu fit, %zu do "
              "not\n",
              bank.maps.misfit_ratio, bank.maps.line_se_bound, wrong_flagged, wrong, right_flagged, right, top_right_flagged, top_right,
              bank.maps.of(FitClass::fits).records, bank.maps.of(FitClass::misfits).records);
  // The count's interval is a run of whole counts: where the estimator is right in ~90 % of a
  // bin's records, the interval holds a neighbour too and covers ~0.99 (measured 0.990). That
  // over-coverage is what this bank size gives (docs/inverse.md, "Limits"); under-coverage
  // is what must not happen.
  EXPECT_GE(count_coverage, 0.83);
  EXPECT_GE(median_coverage, 0.83);
  EXPECT_LE(median_coverage, 0.97);
  EXPECT_GE(sd_coverage, 0.83);
  EXPECT_LE(sd_coverage, 0.97);
  // The test of the warnings: on >= 80 % of the wrong counts, <= 20 % of the right ones
  // (below the prior's top count: a count at the top can be right only because the prior
  // stops there, and a misfitting record there is warned about on purpose; docs/inverse.md).
  ASSERT_GE(wrong, 10u);
  EXPECT_GE(static_cast<double>(wrong_flagged) / static_cast<double>(wrong), 0.8);
  EXPECT_LE(static_cast<double>(right_flagged) / static_cast<double>(right), 0.2);
}

}  // namespace
}  // namespace stengmc
