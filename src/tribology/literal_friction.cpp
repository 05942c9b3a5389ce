//! Paper Eq. 2 as printed (MODEL.md §1): only the Stribeck excess takes the regularised
//! sign, so F(0) = N mu_k and the kinetic part never changes sign (kept to reproduce the
//! paper's figures; `consistent` is the default).
#include "tribology/stribeck_terms.hpp"

namespace stengmc {
namespace {

template <bool Series>
double force(const FrictionParameters& p, double v_r) {
  const auto [excess, sign] = stribeck::excess_and_sign<Series>(p, v_r);
  return p.normal_load_n * (p.kinetic_coefficient + excess * sign);
}

ForceAndSlope force_and_slope(const FrictionParameters& p, double v_r) {
  const stribeck::Terms t = stribeck::terms(p, v_r);
  return {p.normal_load_n * (p.kinetic_coefficient + t.excess * t.sign),
          p.normal_load_n * (t.excess * t.sign_slope + t.excess_slope_sign)};
}

}  // namespace

FrictionLaw literal_friction_law() {
  return {"literal", "N [mu_k + (mu_s - mu_k) exp(-c_s|v_r|) (2/pi) atan(s v_r)]", force<false>, force_and_slope,
          stribeck::forces_by<force<false>, force<true>>};
}

}  // namespace stengmc
