#include "inverse/device_checks.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"
#include "pipeline/study_realisation.hpp"
#include "pipeline/validity.hpp"
#include "spectral/analysed_voltage.hpp"

namespace stengmc {

std::pair<double, double> simulated_stiffness_range(const InversePrior& prior) {
  const auto [low, high] = prior.support();
  return {low / ATOM_RANGE_MARGIN, high * ATOM_RANGE_MARGIN};
}

Study device_study_at(const Study& known, const KnownDevice& device, std::span<const double> stiffness_n_per_m,
                      const RecordGrid& grid) {
  Study study = known;
  std::string which;
  study.asperities.clear();
  for (double k : stiffness_n_per_m) {
    Asperity a = device.asperity;
    a.stiffness_n_per_m = k;
    study.asperities.push_back(a);
    which += (which.empty() ? "" : ", ") + format_number(k);
  }
  study.population = Population{};
  study.population.asperities = study.asperities;
  study.duration_s = grid.duration_s();
  study.sample_rate_hz = grid.sample_rate_hz();
  study.spectrum.reset();
  study.noise.reset();
  study.file = known.file + " (its device with asperities of k = " + which + " N/m, as the inversion simulates it)";
  return study;
}

void fail_at_study_key(const Study& known, const std::string& dotted_path, const std::string& what) {
  auto document = TomlDocument::from_string(known.text, known.file);
  if (document->has_path(dotted_path)) {
    TomlTable table = document->root();
    std::string key = dotted_path;
    for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.')) {
      std::optional<TomlTable> inner = table.table(key.substr(0, dot));
      if (!inner) break;
      table = *inner;
      key = key.substr(dot + 1);
    }
    table.fail(key, what);
  }
  throw InputError(known.file + ": " + dotted_path + " " + what);
}

void check_device_over_prior(const Study& known, const KnownDevice& device, const InversePrior& prior,
                             const RecordGrid& grid) {
  const auto [softest, stiffest] = simulated_stiffness_range(prior);
  const Asperity& a = device.asperity;

  // What the analyses square: one asperity gives ~R sigma w v_b.
  const double scale_v = device.voltage_scale_v();
  if (!(std::abs(scale_v) <= MAX_ANALYSED_VOLTAGE_V))
    fail_at_study_key(known, "circuit.load_resistance_ohm",
                      "= " + format_number(device.circuit.load_resistance_ohm) +
                          " Ohm gives one asperity a voltage R sigma w v_b = " + format_number(scale_v) +
                          " V (with charge_density_c_per_m2, width_m and belt_velocity_m_per_s): beyond what inverse "
                          "estimation can square and sum (|V| <= " + format_number(MAX_ANALYSED_VOLTAGE_V) + " V)");

  // run's own check, on the fastest run the inversion makes.
  const double k_stiffest[] = {stiffest};
  check_sample_rate(device_study_at(known, device, k_stiffest, grid));

  // A line needs an oscillation: the softest asperity is the most damped relative to k.
  const double rate = device.damping_rate_per_s();
  const double natural = std::sqrt(softest / a.mass_kg);
  if (!(device.angular_frequency(softest) > 0.0))
    fail_at_study_key(known, "model.damping_n_s_per_m",
                      "= " + format_number(device.model.damping_n_s_per_m) + " N s/m over-damps the prior's softest "
                      "asperity (k = " + format_number(softest) + " N/m, mass_kg = " + format_number(a.mass_kg) +
                          " kg: c/2m = " + format_number(rate) + " 1/s >= sqrt(k/m) = " + format_number(natural) +
                          " 1/s): it would not oscillate, and inverse estimation finds asperities by their lines");

  // run's validity report at the stiffest asperity, the least deflected before breakaway:
  // beyond l there, no asperity of the prior ever slides on this device.
  Population stiffest_only;
  stiffest_only.asperities = device_study_at(known, device, k_stiffest, grid).asperities;
  const ValidityReport validity = assess_validity(stiffest_only, Model1Params{}, device.model, {}, ModelScope{false, true});
  const double reach = validity.static_deflection_over_length.front();
  if (!(reach < 1.0))
    fail_at_study_key(known, "surface.defaults.normal_load_n",
                      "= " + format_number(a.normal_load_n) + " N: even the prior's stiffest asperity (k = " +
                          format_number(stiffest) + " N/m) would be dragged " + format_number(reach) +
                          " x its element's length l = " + format_number(a.element.length_m) +
                          " m before it breaks away ((mu_s N - c v_b)/k): no asperity of the prior slides on this "
                          "device. Check normal_load_n, static_friction and length_m, or give [inverse] a prior of "
                          "stiffer asperities (" + prior.parameter_keys().first + ", " + prior.parameter_keys().second + ")");

  // An atom is belt-carried until it breaks away at ~F / (k v_b) (the stiffest first), and
  // only then rings at its line: a record that ends before holds no line to invert.
  const double breakaway_s = device.sliding_friction_n() / (stiffest * device.model.belt_velocity_m_per_s);
  const double end_s = grid.at(grid.samples - 1);
  if (!(breakaway_s < end_s))
    fail_at_study_key(known, "model.belt_velocity_m_per_s",
                      "= " + format_number(device.model.belt_velocity_m_per_s) + " m/s: even the prior's stiffest asperity (k = " +
                          format_number(stiffest) + " N/m) is carried by the belt until t = F/(k v_b) = " +
                          format_number(breakaway_s) + " s, after the record ends (t = " + format_number(end_s) +
                          " s): the record would hold no line to invert. A faster belt or a longer record (duration_s) "
                          "would");
}

void check_prior_over_device(const Study& known, const KnownDevice& device, const InversePrior& prior,
                             const RecordGrid& grid) {
  const double tau = prior.parameter_tolerance;
  const auto& f = device.model.friction;
  if (f.static_coefficient * (1.0 - tau) < f.kinetic_coefficient * (1.0 + tau))
    fail_at_study_key(known, "inverse.parameter_tolerance",
                      "= " + format_number(tau) + " lets static_friction (" + format_number(f.static_coefficient) +
                          ") fall below kinetic_friction (" + format_number(f.kinetic_coefficient) +
                          "): mu_s (1 - tau) must stay >= mu_k (1 + tau)");
  const double end_s = grid.at(grid.samples - 1);
  if (prior.onset_s[1] >= end_s)
    fail_at_study_key(known, "inverse.onset_s",
                      "= [" + format_number(prior.onset_s[0]) + ", " + format_number(prior.onset_s[1]) +
                          "] s reaches the end of the record (t = " + format_number(end_s) +
                          " s): an asperity that comes into contact after it leaves nothing to find");
}

}  // namespace stengmc
