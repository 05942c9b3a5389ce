#pragma once
//! Model 2 for a contact that changes in time (docs/model.md §1.4): the counterface's
//! friction modulation, the asperity's release, wear and stiffness steps. The equation
//!   m x'' + c x' + k(t) x = L(t) F(v_b - x') (1 + eps(t))
//! (L = 1 in contact, 0 after release) is no longer autonomous, so the exact sliding
//! steps of model2_integrator.hpp do not apply; a non-autonomous RODAS4 integrates it
//! instead, its steps never crossing a node of eps's grid, a stiffness step or the release.
#include <span>
#include <vector>

#include "model/asperity.hpp"
#include "tribology/counterface.hpp"
#include "tribology/model2.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

//! True when the asperity's contact evolves (release, wear or stiffness steps) or the
//! counterface modulates its friction; false: the autonomous integrator, unchanged.
bool contact_evolves(const Asperity& asperity, const Model2Params& params);

//! k(t) [N/m] at absolute time t [s]: k0 times the factors of the steps at or before t,
//! times 1 - w (min(t, release) - onset) / 1 ms from the onset on (k0 before it).
double stiffness_at(const Asperity& asperity, double t_s);

//! The largest k(t) [N/m] the asperity reaches from its onset on: k0 times the largest
//! running product of its stiffness steps (wear only lowers k).
double largest_stiffness_n_per_m(const Asperity& asperity);

//! Integrates the asperity from its onset (t = 0 here is the onset) to `t_end_s` [s] after
//! it, in the form integrate_model2 returns (knots and RODAS4 pieces, no oscillator pieces).
//! @throws ModelError if the wear takes k to 0 or below before the release or t_end, on
//!         step size underflow or an exhausted step budget, naming k, v_b and the time.
//! @throws InputError as integrate_model2, and for a modulation grid of more than 5e7 nodes.
void integrate_evolving_contact(const Asperity& asperity, const Model2Params& params, double t_end_s,
                                const CounterfaceStream& stream, Model2Integration& out);

//! The modulation 1 + eps(t) at absolute times `times_s` (increasing) into `factor` (resized):
//! the same linear interpolation of the same nodes the integrator used; 1 before the
//! onset and without modulation.
void modulation_factors(const Asperity& asperity, const Model2Params& params, const CounterfaceStream& stream,
                        std::span<const double> times_s, std::vector<double>& factor);

}  // namespace stengmc
