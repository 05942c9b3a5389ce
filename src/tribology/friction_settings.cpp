#include "tribology/friction_settings.hpp"

#include "core/format.hpp"

namespace stengmc {
namespace {

// No known pair of materials comes near 1e3 (clean metals in vacuum reach ~10); beyond it
// the forces only drive the integrators into their step budgets (found by the fuzz tests:
// mu_s = 2e9 ran Model 2 for a minute).
constexpr double MAX_FRICTION_COEFFICIENT = 1e3;

}  // namespace

FrictionCoefficients read_friction_coefficients(TomlTable& model) {
  FrictionCoefficients f;
  f.static_coefficient = model.positive("static_friction", f.static_coefficient);
  f.kinetic_coefficient = model.non_negative("kinetic_friction", f.kinetic_coefficient);
  if (f.static_coefficient > MAX_FRICTION_COEFFICIENT)
    model.fail("static_friction", "= " + format_number(f.static_coefficient) + " must be <= " +
                                      format_number(MAX_FRICTION_COEFFICIENT));
  if (f.static_coefficient < f.kinetic_coefficient)
    model.fail("static_friction", "= " + format_number(f.static_coefficient) + " must be >= kinetic_friction = " +
                                      format_number(f.kinetic_coefficient));
  return f;
}

std::vector<Setting> friction_settings(const FrictionCoefficients& friction) {
  return {{"static_friction", friction.static_coefficient}, {"kinetic_friction", friction.kinetic_coefficient}};
}

}  // namespace stengmc
