#pragma once
//! Model 2's friction laws F(v_r) (MODEL.md §1): `[model] friction_form` names one. A new
//! law is one file defining its FrictionLaw and one line in friction_laws.cpp; the
//! integrator calls it through the law's function pointers, looked up once per asperity.
#include <cstddef>
#include <string_view>
#include <vector>

namespace stengmc {

//! What a law is evaluated with: the couple, the regularisation and one normal load.
struct FrictionParameters {
  double normal_load_n = 0.0;             //!< N [N]
  double kinetic_coefficient = 0.0;       //!< mu_k
  double static_coefficient = 0.0;        //!< mu_s
  double stribeck_decay_s_per_m = 0.0;    //!< c_s [s/m]
  double atan_sharpness_s_per_m = 0.0;    //!< s [s/m]
};

//! F(v_r) [N] with its slope dF/dv_r [N s/m] (the integrator's Jacobian and the sliding
//! propagator's linearisation need both).
struct ForceAndSlope {
  double force_n;
  double slope_n_s_per_m;
};

struct FrictionLaw {
  std::string_view name;     //!< `friction_form = "..."` in study and run files
  std::string_view formula;  //!< F(v_r) as MODEL.md writes it, for messages and docs
  //! F(v_r) [N] for relative velocity v_r = v_b - x' [m/s]; continuous, bounded by
  //! N max(mu_s, mu_k) in magnitude, and odd-signed (F has the sign of v_r).
  double (*force)(const FrictionParameters& p, double v_r);
  //! The same with dF/dv_r, C^1 in v_r (the integrator's Jacobian must be exact on both
  //! sides of v_r = 0).
  ForceAndSlope (*force_and_slope)(const FrictionParameters& p, double v_r);
  //! force() at `count` relative velocities at once (force_n may be v_r itself: each
  //! element is read before it is written), the same values one by one: one loop
  //! over the law's inlined formula, whose independent evaluations the processor overlaps
  //! (the sliding propagator's collocation nodes; a call each through the pointer above
  //! costs more there; stribeck::forces_by).
  void (*forces)(const FrictionParameters& p, const double* v_r, double* force_n, std::size_t count);
};

//! Every law, in the order error messages list them; the first is the default.
const std::vector<FrictionLaw>& friction_laws();
//! The law named `name`, or nullptr.
const FrictionLaw* find_friction_law(std::string_view name);
//! The default law (`consistent`).
const FrictionLaw& default_friction_law();
//! Every law's name (what an error message lists as allowed).
std::vector<std::string_view> friction_law_names();

}  // namespace stengmc
