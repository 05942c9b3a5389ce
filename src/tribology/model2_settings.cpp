#include "tribology/model2_settings.hpp"

#include <cmath>

#include "core/format.hpp"
#include "tribology/friction_settings.hpp"

namespace stengmc {
namespace {

// Model 2's atan sharpness s at most [s/m]: sharper than a 0.1 nm/s transition is the sign
// function itself at double precision, and the stiff friction makes RODAS4 run into its
// step budget (1e11 took ~5x the steps of 1e3, 1e15 exhausted 5e7 steps: found by the
// fuzz tests).
constexpr double MAX_ATAN_SHARPNESS_S_PER_M = 1e10;

}  // namespace

Model2Params read_model2_params(TomlTable& model) {
  Model2Params p;
  p.friction = read_friction_coefficients(model);
  p.belt_velocity_m_per_s = model.number("belt_velocity_m_per_s", p.belt_velocity_m_per_s);
  p.damping_n_s_per_m = model.non_negative("damping_n_s_per_m", p.damping_n_s_per_m);
  p.stribeck_decay_s_per_m = model.non_negative("stribeck_decay_s_per_m", p.stribeck_decay_s_per_m);
  p.atan_sharpness_s_per_m = model.positive("atan_sharpness_s_per_m", p.atan_sharpness_s_per_m);
  if (p.atan_sharpness_s_per_m > MAX_ATAN_SHARPNESS_S_PER_M)
    model.fail("atan_sharpness_s_per_m", "= " + format_number(p.atan_sharpness_s_per_m) + " must be <= " +
                                             format_number(MAX_ATAN_SHARPNESS_S_PER_M) +
                                             " (a friction transition narrower than 0.1 nm/s)");
  p.friction_law = find_friction_law(model.choice("friction_form", p.friction_law->name, friction_law_names()));
  p.relative_tolerance = model.positive("relative_tolerance", p.relative_tolerance);
  if (p.relative_tolerance >= 1e-2 || p.relative_tolerance < 1e-14)
    model.fail("relative_tolerance", "= " + format_number(p.relative_tolerance) + " must lie in [1e-14, 1e-2)");
  return p;
}

std::vector<Setting> model2_settings(const Model2Params& p) {
  std::vector<Setting> settings = friction_settings(p.friction);
  settings.insert(settings.end(), {{"belt_velocity_m_per_s", p.belt_velocity_m_per_s},
                                   {"damping_n_s_per_m", p.damping_n_s_per_m},
                                   {"stribeck_decay_s_per_m", p.stribeck_decay_s_per_m},
                                   {"atan_sharpness_s_per_m", p.atan_sharpness_s_per_m},
                                   {"friction_form", std::string(p.friction_law->name)},
                                   {"relative_tolerance", p.relative_tolerance}});
  return settings;
}

CounterfaceParams read_counterface(TomlTable& table, double belt_velocity_m_per_s) {
  CounterfaceParams c;
  c.friction_modulation_rms = table.non_negative("friction_modulation_rms", c.friction_modulation_rms);
  if (!(c.friction_modulation_rms <= MAX_FRICTION_MODULATION_RMS))
    table.fail("friction_modulation_rms", "= " + format_number(c.friction_modulation_rms) + " must be <= " +
                                              format_number(MAX_FRICTION_MODULATION_RMS) +
                                              " (a larger modulation makes the friction reverse, 1 + eps < 0, too often)");
  if (!table.has("correlation_length_m")) {
    if (c.active())
      table.fail("correlation_length_m", "is missing: friction_modulation_rms > 0 needs the counterface's correlation "
                                         "length lambda [m] (e.g. 1e-6)");
  } else {
    c.correlation_length_m = table.positive("correlation_length_m", c.correlation_length_m);
    if (!std::isfinite(c.correlation_length_m))
      table.fail("correlation_length_m", "must be a finite length > 0 [m]");
  }
  if (c.active() && belt_velocity_m_per_s == 0.0)
    table.fail("friction_modulation_rms", "> 0 needs a moving belt: [model] belt_velocity_m_per_s = 0 leaves the "
                                          "counterface still (an infinite correlation time)");
  return c;
}

std::vector<Setting> counterface_settings(const CounterfaceParams& c) {
  return {{"friction_modulation_rms", c.friction_modulation_rms}, {"correlation_length_m", c.correlation_length_m}};
}

}  // namespace stengmc
