#include "inverse/inversion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "inverse/sample_statistics.hpp"

namespace stengmc {

namespace {

//! True when the lines' stiffnesses spread by more than the record model resolves: ln k
//! apart by less than its accuracy (MODEL_RELATIVE_ACCURACY), lines are one stiffness found
//! several times (asperities of equal k, whose lines merge: the fit leaves them a few 1e-4
//! apart even on a noise-free record), and no law is fitted to them. The law fits themselves
//! go down to MIN_LAW_SD_LOG (1e-4), a numerical floor, not a physical one.
bool resolved_spread(std::span<const double> k) {
  return has_spread(k) && sample_sd_log(std::vector<double>(k.begin(), k.end())) >= MODEL_RELATIVE_ACCURACY;
}

//! The laws compared on `k`, none fitted when its spread is not resolved.
std::vector<LawFit> laws_of(std::span<const double> k) {
  if (resolved_spread(k)) return compare_stiffness_laws(k);
  std::vector<LawFit> none;
  for (StiffnessFamily f : {StiffnessFamily::lognormal, StiffnessFamily::gamma, StiffnessFamily::weibull}) {
    LawFit fit;
    fit.family = f;
    none.push_back(fit);
  }
  return none;
}

// The default FFT threshold without a bank (the [spectrum] default).
constexpr double DEFAULT_NAIVE_THRESHOLD = 10.0;
// A record's rms more than this factor above what the prior's largest count of atoms gives,
// or below one atom's, is not of this device (or not in volts): a real record's noise at the
// prior's lowest SNR adds a few per cent, a count outside the prior a few times.
constexpr double AMPLITUDE_MARGIN = 10.0;

std::string percent(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g %%", 100.0 * x);
  return text;
}

//! Root mean square, scaled by the largest |v| first so that a record of 1e-200 V does not
//! square to 0.
double rms(std::span<const double> v) {
  double largest = 0.0;
  for (double x : v) largest = std::max(largest, std::abs(x));
  if (largest == 0.0 || v.empty()) return 0.0;
  double sum = 0.0;
  for (double x : v) sum += (x / largest) * (x / largest);
  return largest * std::sqrt(sum / static_cast<double>(v.size()));
}

std::string number(double x, const char* format = "%.4g") {
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

//! Which of the model's assumptions the residual points to: the largest of its checks, each
//! ~1 when the model fits (RecordEstimator::residual_checks).
std::string residual_pointer(const RecordEstimate& e) {
  const ResidualChecks& r = e.checks;
  struct Pointer {
    double ratio;
    const char* where;
    const char* what;
  };
  const Pointer pointers[] = {
      {r.early, "over the breakaways' span", "the asperities' loads or contact onsets, or the breakaway itself (friction "
                                             "coefficients, normal load)"},
      {r.line_band, "in the lines' band", "lines the atoms do not describe: known parameters off, stiffnesses outside the "
                                          "prior, or asperities that stick again"},
      {r.low_band, "below the lines' band", "noise or drift below the lines that the noise model does not describe (1/f, "
                                            "an offset that moves)"},
      {r.late, "over the record's last third", "the sliding's damping (known parameters) or asperities that stick again"}};
  const Pointer* worst = &pointers[0];
  for (const Pointer& p : pointers)
    if (p.ratio > worst->ratio) worst = &p;
  return std::string("The residual is largest ") + worst->where + " (" + number(worst->ratio, "%.2g") +
         " x the noise's share there): it points to " + worst->what + ".";
}

//! What the intervals of a misfitting record rest on.
std::string misfit_interval_note(const CalibrationMaps* maps) {
  if (!maps) return "";
  const ClassMaps& misfits = maps->of(FitClass::misfits);
  if (!misfits.pooled) return "; the intervals above are learnt from the bank's records that fit as badly";
  return "; the bank holds too few such records (" + std::to_string(misfits.records) +
         ") to learn their intervals apart, so the intervals above are those of all its records and likely too narrow: "
         "calibrate with a prior that includes what this device departs by ([inverse] load_cv, onset_s, "
         "parameter_tolerance, noise, offset)";
}

}  // namespace

Inverter::Inverter(const InverseSetup& setup, const AtomLibrary& atoms, const CalibrationMaps* maps)
    : setup_(&setup),
      atoms_(&atoms),
      maps_(maps),
      estimator_(atoms, setup.prior),
      naive_(atoms.grid().samples, atoms.grid().sample_rate_hz(),
             atoms.device().angular_frequency(setup.prior.support().first) / (2.0 * PI),
             atoms.device().angular_frequency(setup.prior.support().second) / (2.0 * PI)) {
  atom_rms_v_ = one_asperity_rms_v(atoms, setup.prior);
}

Inversion Inverter::invert(const std::string& name, std::span<const double> voltage) {
  Inversion out;
  out.name = name;
  try {
    out.raw = estimator_.estimate(voltage);
  } catch (const ModelError& e) {
    throw ModelError(name + ": " + e.what());  // which record, among many
  }
  out.calibrated = calibrate_estimate(out.raw, maps_, setup_->prior);
  const double threshold = maps_ ? maps_->naive_threshold : DEFAULT_NAIVE_THRESHOLD;
  out.naive_count = naive_.count(voltage, std::vector<double>{threshold}).front();
  std::vector<double> k;
  for (const EstimatedLine& line : out.raw.lines) k.push_back(line.stiffness_n_per_m);
  out.laws = laws_of(k);
  out.model_v.resize(voltage.size());
  estimator_.model().voltage(out.raw.state, out.model_v);

  // ---- the verdict
  const RecordEstimate& e = out.raw;
  const CalibratedEstimate& c = out.calibrated;
  const KnownDevice& device = setup_->device;
  const double width_hz = device.damping_rate_per_s() / PI;  // a line's full width at half maximum
  std::size_t p_index = c.count - c.counts.front();
  char count_line[256];
  std::snprintf(count_line, sizeof count_line, "%zu sliding asperities (90 %% interval %zu-%zu, P = %.3f, %s); an FFT peak count says %.0f.",
                c.count, c.interval_low, c.interval_high, c.probability[p_index],
                c.calibrated ? "calibrated" : "raw posterior: no bank", out.naive_count);
  out.verdict.push_back(count_line);
  std::size_t blended = 0;
  for (const EstimatedLine& line : e.lines)
    if (e.lines.size() > 1 && line.nearest_separation_hz < width_hz) ++blended;
  const std::size_t clear = e.lines.size() - blended;
  if (!e.lines.empty()) {
    std::string lines = std::to_string(clear) + " of " + std::to_string(e.lines.size()) +
                        " lines stand clear of their neighbours (more than one line width, " + number(width_hz / 1e3, "%.3g") +
                        " kHz): their stiffnesses are trustworthy";
    double worst = 0.0;
    for (const EstimatedLine& line : e.lines)
      if (e.lines.size() == 1 || line.nearest_separation_hz >= width_hz) worst = std::max(worst, line.log_stiffness_se);
    if (clear > 0) lines += " (to " + percent(1.6448536269514722 * worst * (maps_ ? maps_->of(out.calibrated.fit_class).line_error_scale : 1.0)) + " or better, 90 %)";
    out.verdict.push_back(lines + ".");
  }
  if (blended > 0)
    out.verdict.push_back(std::to_string(blended) + " lines lie within one line width of another: resolution limits them. "
                          "Their number is sure (two coinciding asperities give twice one atom), their individual "
                          "stiffnesses less so (see each line's interval).");
  if (k.size() >= 3 && !resolved_spread(k)) {
    // One stiffness found several times: its estimate is the lines' mean in ln k (their
    // median would pick one line's share of the model's error).
    double mean_log = 0.0;
    for (double x : k) mean_log += std::log(x) / static_cast<double>(k.size());
    out.verdict.push_back("The " + std::to_string(k.size()) + " lines share one stiffness, " + number(std::exp(mean_log)) +
                          " N/m (sd of ln k " + number(sample_sd_log(k), "%.2g") +
                          "): asperities of equal k, whose lines merge. No stiffness law is fitted to one stiffness.");
  }
  out.verdict.push_back("Signal-to-noise " + number(e.signal_to_noise_db, "%.1f") + " dB" +
                        (e.signal_to_noise_db < 25.0 ? ": noise widens every interval" : ": noise is not what limits") + ".");
  if (e.onset_steps > 0) {
    // The onsets the record shows as steps (inverse/onset_steps.hpp): one asperity each, so a
    // count below them contradicts the record; above them, the others were in contact from its start.
    std::string steps = std::to_string(e.onset_steps) + " contact onset(s) show as steps of R sigma w v_b in the record";
    if (out.calibrated.count < e.onset_steps)
      steps += ", more than the " + std::to_string(out.calibrated.count) + " asperities counted: the count is likely low";
    out.verdict.push_back(steps + ".");
  }
  if (c.misfit > (maps_ ? maps_->misfit_ratio : DEFAULT_MISFIT_RATIO)) out.verdict.push_back(residual_pointer(e));
  if (atoms_->check_error() > 1e-2)
    out.verdict.push_back("The atoms match the forward model to " + percent(atoms_->check_error()) +
                          " only (stick modulation at this belt velocity): expect biased stiffnesses.");

  // ---- warnings
  if (!maps_) out.warnings.push_back("no calibration bank: P(n) is the raw Laplace posterior, the population has no intervals (run stengmc calibrate)");
  if (e.lines_outside_prior > 0)
    out.warnings.push_back(std::to_string(e.lines_outside_prior) + " line(s) lie outside the prior's stiffness range: the record is outside the prior the calibration describes");
  if (e.more_than_prior_allows)
    out.warnings.push_back("the record seems to hold more sliding asperities than the prior's largest count (" +
                           std::to_string(setup_->prior.count_max) + "): the count is cut at that limit");
  // The warnings on the fit: what the bank shows to go with wrong counts (docs/inverse.md,
  // "warnings"), one per reason the record falls in the second fit class. The residual's
  // shape, which does not tell right from wrong, is in the verdict.
  const double misfit_ratio = maps_ ? maps_->misfit_ratio : DEFAULT_MISFIT_RATIO;
  const double line_se_bound = maps_ ? maps_->line_se_bound : DEFAULT_LINE_SE_BOUND;
  if (c.misfit > misfit_ratio)
    out.warnings.push_back("the fit's residual (" + number(e.residual_sigma_v, "%.3g") + " V rms) is " + number(c.misfit, "%.3g") +
                           " x the noise above the lines (" + number(e.noise.sigma_v, "%.3g") + " V), more than " +
                           number(misfit_ratio, "%.3g") +
                           (maps_ ? " (what 85 % of the bank's records counted right stay below)" : " (no bank: 10 %)") +
                           ": the model does not fit to the noise, and counts of such records are wrong far more often" +
                           misfit_interval_note(maps_));
  if (c.worst_line_se > line_se_bound)
    out.warnings.push_back("a line's stiffness is known to " + percent(c.worst_line_se) + " (1 sigma in ln k), more than " +
                           percent(line_se_bound) +
                           (maps_ ? " (what 95 % of the bank's records counted right that fit stay below)" : " (no bank: 0.1 %)") +
                           ": the record does not pin it, as it pins the lines of real asperities; such a line is often "
                           "one the search added to absorb what the model does not describe, and counts of such records "
                           "are wrong far more often" + misfit_interval_note(maps_));
  // A record whose amplitude no count of this device's atoms can give: other units (mV, uV,
  // an ADC's counts) or other known parameters. n atoms give at most n times one atom's rms
  // (all in phase) and, with the plateau every atom shares, not much below one atom's.
  const double record_rms = rms(voltage);
  const double ratio = record_rms / atom_rms_v_;
  const std::string amplitude = "the record's rms voltage (" + number(record_rms, "%.3g") + " V) is " + number(ratio, "%.2g") +
                                " x what one sliding asperity of this device gives (" + number(atom_rms_v_, "%.3g") +
                                " V rms, R sigma w v_b = " + number(device.voltage_scale_v(), "%.3g") + " V)";
  if (ratio > AMPLITUDE_MARGIN * static_cast<double>(setup_->prior.count_max))
    out.warnings.push_back(amplitude + ", more than the prior's " + std::to_string(setup_->prior.count_max) +
                           " asperities could give: is the record in other units (mV, an ADC's counts), or are the known "
                           "parameters (load_resistance_ohm, charge_density_c_per_m2, width_m, belt_velocity_m_per_s) "
                           "not this device's? The answer above is not to be trusted");
  else if (ratio < 1.0 / AMPLITUDE_MARGIN)
    out.warnings.push_back(amplitude + ": nothing of this device slides in it, or it is in other units (kV?) or the known "
                           "parameters are not this device's. The answer above is not to be trusted");
  const double snr_margin = 3.0;
  if (e.signal_to_noise_db < setup_->prior.snr_db[0] - snr_margin || e.signal_to_noise_db > setup_->prior.snr_db[1] + snr_margin)
    out.warnings.push_back("the signal-to-noise ratio (" + number(e.signal_to_noise_db, "%.1f") + " dB) lies outside the prior's " +
                           number(setup_->prior.snr_db[0], "%.0f") + "-" + number(setup_->prior.snr_db[1], "%.0f") +
                           " dB: the calibration was not made for it");
  return out;
}

std::vector<LawFit> pooled_laws(const std::vector<Inversion>& inversions) {
  std::vector<double> k;
  for (const Inversion& inv : inversions)
    for (const EstimatedLine& line : inv.raw.lines) k.push_back(line.stiffness_n_per_m);
  return laws_of(k);
}

}  // namespace stengmc
