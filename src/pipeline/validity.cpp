#include "pipeline/validity.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/format.hpp"

namespace stengmc {

namespace {

std::string percent(double fraction) { return format_number(100.0 * fraction) + " %"; }

std::string count_of(std::size_t k, std::size_t n) { return std::to_string(k) + " of " + std::to_string(n); }

void assess_contact(const PopulationContact& c, const ValidityThresholds& th, ValidityReport& r) {
  r.contact_known = true;
  r.load_carried = c.load_carried;
  r.interacting_converged = c.interacting_converged;
  if (!c.load_carried) {
    r.contact_warnings.push_back("no summits drawn: no separation can carry the nominal load W");
    return;
  }
  r.contact_density = c.contact_density;
  r.screening_estimate = c.screening_estimate;
  r.load_redistribution = c.interaction.load_redistribution;
  r.interaction_max_relative = c.interaction.max_relative;
  r.overlapping_pairs = c.interaction.overlapping_pairs;
  for (double a : c.patch_radius_m) r.max_patch_over_radius = std::max(r.max_patch_over_radius, a / c.summit_radius_m);
  r.independence_holds = r.load_redistribution < th.load_redistribution;
  r.beyond_hertz = r.max_patch_over_radius > th.patch_over_radius;
  // What the user can do about it depends on how the loads were set.
  const char* advice = c.interacting_iterations > 0 ? "; the loads include it (interacting mode)"
                       : c.hertz_load ? "; consider [interaction] mode = \"apply\""
                                      : "; a fixed load per asperity ignores it ([load] rule = \"hertz\" with "
                                        "[interaction] mode = \"apply\" would not)";
  if (!r.independence_holds)
    r.contact_warnings.push_back("spots are not independent: their interaction moves " + percent(r.load_redistribution) +
                                 " of the load between spots (threshold " + percent(th.load_redistribution) +
                                 ", contact density A_r/A0 = " + percent(r.contact_density) + ")" + advice);
  if (!c.interacting_converged)
    r.contact_warnings.push_back("interacting mode did not converge in " + std::to_string(c.interacting_iterations) +
                                 " iterations: the loads are not a fixed point of the interaction");
  if (r.overlapping_pairs > 0)
    r.contact_warnings.push_back(std::to_string(r.overlapping_pairs) +
                                 " pairs of contact patches overlap (they would merge into one spot)");
  if (r.beyond_hertz)
    r.contact_warnings.push_back("a patch reaches a/R_s = " + format_number(r.max_patch_over_radius) +
                                 ", beyond Hertz's small-strain range (a << R_s; warning from " +
                                 format_number(th.patch_over_radius) + ")");
}

}  // namespace

ValidityReport assess_validity(const Population& population, const Model1Params& model1, const Model2Params& model2,
                               const ValidityThresholds& th, ModelScope scope) {
  ValidityReport r;
  if (population.contact) assess_contact(*population.contact, th, r);
  const auto& asperities = population.asperities;
  const std::size_t n = asperities.size();
  r.cannot_slip_model1.resize(n);
  r.static_deflection_over_length.resize(n);
  r.near_length_model2.resize(n);
  double worst_ratio = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Asperity& a = asperities[i];
    // Model 1: the spring force k A must beat static friction mu_s N (MODEL.md §1).
    r.cannot_slip_model1[i] =
        scope.model1 && model1.drive_amplitude_m * a.stiffness_n_per_m <= model1.friction.static_coefficient * a.normal_load_n;
    // Model 2: stuck to the belt (x' = v_b) the asperity deflects until k x + c v_b reaches
    // mu_s N; from there it oscillates below that deflection (MODEL.md §1, §2: x < l).
    const double breakaway_m =
        std::max(model2.friction.static_coefficient * a.normal_load_n - model2.damping_n_s_per_m * model2.belt_velocity_m_per_s, 0.0) /
        a.stiffness_n_per_m;
    r.static_deflection_over_length[i] = breakaway_m / a.element.length_m;
    if (!scope.model2) r.static_deflection_over_length[i] = 0.0;
    r.near_length_model2[i] = r.static_deflection_over_length[i] >= th.near_length_fraction;
    r.cannot_slip_count += r.cannot_slip_model1[i];
    r.near_length_count += r.near_length_model2[i];
    worst_ratio = std::max(worst_ratio, r.static_deflection_over_length[i]);
  }
  if (r.cannot_slip_count > 0)
    r.model1_warnings.push_back(count_of(r.cannot_slip_count, n) + " asperities cannot slip under Model 1 (A = " +
                                format_number(model1.drive_amplitude_m) + " m <= mu_s N / k): they never move");
  if (r.near_length_count > 0)
    r.model2_warnings.push_back(count_of(r.near_length_count, n) +
                                " asperities break away under Model 2 at a deflection (mu_s N - c v_b)/k of " +
                                percent(th.near_length_fraction) + " of l or more (worst " + percent(worst_ratio) +
                                "): x is likely to reach l");
  return r;
}

}  // namespace stengmc
