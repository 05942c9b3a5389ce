#include "surface/fixed_population.hpp"

#include <cmath>
#include <optional>

#include "core/format.hpp"
#include "model/asperity.hpp"

namespace stengmc {

namespace {

//! Reads the per-asperity keys of `table` over `base` (the defaults). Positivity is
//! checked where the physics needs it: k, m, l, w, d0 > 0 (C_i and the element
//! formulas divide by them); N, h >= 0.
Asperity read_asperity(TomlTable& table, const Asperity& base) {
  Asperity a = base;
  a.stiffness_n_per_m = table.positive("stiffness_n_per_m", base.stiffness_n_per_m);
  a.mass_kg = table.positive("mass_kg", base.mass_kg);
  a.normal_load_n = table.non_negative("normal_load_n", base.normal_load_n);
  a.height_m = table.non_negative("height_m", base.height_m);
  a.drive_phase_rad = table.number("drive_phase_rad", base.drive_phase_rad);
  if (!(std::abs(a.drive_phase_rad) <= MAX_DRIVE_PHASE_RAD))
    table.fail("drive_phase_rad", "= " + std::to_string(a.drive_phase_rad) + " must lie within +-1e6 rad (an angle: "
                                  "omega t + phi would keep no digits of omega t)");
  a.initial_displacement_m = table.number("initial_displacement_m", base.initial_displacement_m);
  a.initial_velocity_m_per_s = table.number("initial_velocity_m_per_s", base.initial_velocity_m_per_s);
  a.onset_s = table.non_negative("onset_s", base.onset_s);
  if (!std::isfinite(a.onset_s)) table.fail("onset_s", "must be a finite time >= 0 [s]");
  if (a.onset_s > 0.0 && a.initial_velocity_m_per_s != 0.0)
    table.fail("onset_s", "> 0 means the asperity is at rest until its onset: initial_velocity_m_per_s must be 0");
  // The evolving contact (docs/model.md §1.4).
  if (table.has("release_s")) {
    a.release_s = table.number("release_s", base.release_s);
    if (!(a.release_s > a.onset_s))
      table.fail("release_s", "= " + format_number(a.release_s) + " must be a finite time > onset_s = " +
                                  format_number(a.onset_s) + " [s] (leave it out: never released)");
  } else if (!(base.release_s > a.onset_s)) {
    table.fail("onset_s", "= " + format_number(a.onset_s) + " must be < the defaults' release_s = " +
                              format_number(base.release_s) + " [s]");
  }
  a.wear_rate_per_ms = table.non_negative("wear_rate_per_ms", base.wear_rate_per_ms);
  if (!(a.wear_rate_per_ms < 1e3))
    table.fail("wear_rate_per_ms", "= " + format_number(a.wear_rate_per_ms) +
                                       " must be < 1000 per ms (the stiffness would vanish within a microsecond)");
  if (table.has("stiffness_steps")) {
    a.stiffness_steps.clear();
    for (const std::vector<double>& row : table.number_rows("stiffness_steps", 2)) {
      const StiffnessStep step{row[0], row[1]};
      if (!(step.time_s >= 0.0))
        table.fail("stiffness_steps", "has a step at t = " + format_number(step.time_s) + " s; expected [t_s >= 0, factor]");
      if (!(step.factor > 0.0))
        table.fail("stiffness_steps", "has factor = " + format_number(step.factor) + " at t = " +
                                          format_number(step.time_s) + " s; a factor (k after / k before) must be > 0");
      if (!a.stiffness_steps.empty() && !(step.time_s > a.stiffness_steps.back().time_s))
        table.fail("stiffness_steps", "has t = " + format_number(step.time_s) + " s after t = " +
                                          format_number(a.stiffness_steps.back().time_s) +
                                          " s; steps must be listed in increasing time");
      a.stiffness_steps.push_back(step);
    }
  }
  a.element.charge_density_c_per_m2 = table.number("charge_density_c_per_m2", base.element.charge_density_c_per_m2);
  a.element.effective_thickness_m = table.positive("effective_thickness_m", base.element.effective_thickness_m);
  a.element.width_m = table.positive("width_m", base.element.width_m);
  a.element.length_m = table.positive("length_m", base.element.length_m);
  if (a.initial_displacement_m >= a.element.length_m)
    table.fail("initial_displacement_m", "must be < length_m = " + std::to_string(a.element.length_m) +
                                             " m (the S-TENG element needs x < l)");
  return a;
}

}  // namespace

namespace {
// A fixed list is written out by hand; anything larger is a typo or belongs to a random
// population, and would exhaust memory before any other check could speak.
constexpr long long MAX_FIXED_ASPERITIES = 100'000;
}  // namespace

std::vector<Asperity> read_fixed_population(TomlTable& surface) {
  Asperity defaults;
  if (auto table = surface.table("defaults")) defaults = read_asperity(*table, defaults);
  std::vector<Asperity> asperities;
  for (TomlTable& entry : surface.table_array("asperity")) {
    const auto count = entry.integer("count", 1, 1);
    if (count > MAX_FIXED_ASPERITIES - static_cast<long long>(asperities.size()))
      entry.fail("count", "= " + std::to_string(count) + " brings the list above " + std::to_string(MAX_FIXED_ASPERITIES) +
                              " asperities, the limit for a fixed list");
    const Asperity a = read_asperity(entry, defaults);
    asperities.insert(asperities.end(), static_cast<std::size_t>(count), a);
  }
  if (asperities.empty())
    surface.fail("asperity", "is missing: give at least one [[asperity]] entry (stiffness_n_per_m = ...)");
  return asperities;
}

}  // namespace stengmc
