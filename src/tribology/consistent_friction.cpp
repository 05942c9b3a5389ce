//! The default friction law (MODEL.md §1): the whole Stribeck coefficient takes the
//! regularised sign, so |F| -> N mu_s as v_r -> 0+ and F(-v_r) = -F(v_r).
#include "tribology/stribeck_terms.hpp"

namespace stengmc {
namespace {

template <bool Series>
double force(const FrictionParameters& p, double v_r) {
  const auto [excess, sign] = stribeck::excess_and_sign<Series>(p, v_r);
  return p.normal_load_n * (p.kinetic_coefficient + excess) * sign;
}

ForceAndSlope force_and_slope(const FrictionParameters& p, double v_r) {
  const stribeck::Terms t = stribeck::terms(p, v_r);
  const double mu = p.kinetic_coefficient + t.excess;
  return {p.normal_load_n * mu * t.sign, p.normal_load_n * (mu * t.sign_slope + t.excess_slope_sign)};
}

}  // namespace

FrictionLaw consistent_friction_law() {
  return {"consistent", "N [mu_k + (mu_s - mu_k) exp(-c_s|v_r|)] (2/pi) atan(s v_r)", force<false>, force_and_slope,
          stribeck::forces_by<force<false>, force<true>>};
}

}  // namespace stengmc
