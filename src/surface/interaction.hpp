#pragma once
//! Mutual influence of contact spots by Goryacheva's localisation principle
//! (Goryacheva 1998, "Contact Mechanics in Tribology", ch. 2): the loads of spots within a
//! localisation radius R_loc are summed exactly (Boussinesq), the rest of the nominal
//! area is replaced by the nominal pressure p = W/A0 acting outside R_loc (MODEL.md §4).
#include <cstddef>
#include <vector>

#include "surface/hertz_contact.hpp"

namespace stengmc {

//! How a neighbour's load displaces the surface at distance r.
enum class InteractionKernel {
  point_load,      //!< Boussinesq, both bodies: N / (pi E* r) (Johnson 1985, §3.2)
  hertz_pressure,  //!< the Hertz pressure of the patch (Johnson 1985, §3.4); = point load as r/a -> inf, finite at r -> 0
};

//! Settings of the interaction estimate.
struct InteractionSettings {
  double localisation_radius_m = 0.0;   //!< R_loc [m]; 0 = localisation_spacings * sqrt(A0 / n_contact)
  double localisation_spacings = 3.0;   //!< R_loc in mean spot spacings when R_loc is not given [-]
  //! The patch pressure by default: it equals the point load beyond a few patch radii and
  //! stays finite for overlapping patches, where N / (pi E* r) diverges and a single close
  //! pair would dominate the interaction.
  InteractionKernel kernel = InteractionKernel::hertz_pressure;
};

//! Extra normal surface displacement of every asperity caused by the contacting spots.
struct SpotInteraction {
  std::vector<double> extra_displacement_m;  //!< near_field_m[i] + far_field_m, every asperity [m]
  std::vector<double> near_field_m;          //!< sum over other spots within R_loc [m]
  double far_field_m = 0.0;                  //!< nominal pressure outside R_loc, same for every spot [m]
  std::vector<double> relative;              //!< extra_i / delta_i for spots in contact, 0 otherwise [-]
  double localisation_radius_m = 0.0;        //!< R_loc used [m]
  double outer_radius_m = 0.0;               //!< R_out = sqrt(A0 / pi) [m]
  double nominal_pressure_pa = 0.0;          //!< p = sum N_i / A0 [Pa]
  double max_relative = 0.0;                 //!< max over spots of extra_i / delta_i [-]
  double rms_relative = 0.0;                 //!< rms over spots of extra_i / delta_i: the "interaction magnitude" [-]
  //! The interaction magnitude the validity report uses [-]: the fraction of the total load
  //! the interaction moves between spots, to first order,
  //!   sum_i s_i |u_i - u_bar| / sum_i N_i,  s_i = dN_i/d delta_i = 2 E* a_i (Hertz),
  //! where u_bar = sum s_i u_i / sum s_i is the uniform part a fixed W absorbs into the
  //! separation. Unlike extra_i / delta_i it stays bounded for barely touching spots
  //! (s_i -> 0), so one grazing summit cannot dominate it. It is linear in u: where
  //! close pairs push each other hard it overestimates what the interacting mode moves,
  //! and with the point-load kernel an overlapping pair makes it diverge.
  double load_redistribution = 0.0;
  std::size_t contact_count = 0;             //!< spots with load > 0
  std::size_t overlapping_pairs = 0;         //!< spot pairs closer than a_i + a_j (patches would merge) [-]
};

//! Extra displacement at every asperity from the loads of the spots in contact.
//! Neighbours are found with a uniform cell list, O(n x neighbours).
//! @param x_m, y_m asperity positions on the nominal area [m]
//! @param load_n, patch_radius_m, interference_m per asperity, as from solve_hertz_contact
//! @param effective_modulus_pa E* [Pa]; @param nominal_area_m2 A0 [m^2]
//! @throws InputError on mismatched sizes or non-positive E*, A0, settings;
//!         ModelError for two loaded spots at the same point with the point-load kernel.
SpotInteraction spot_interaction(const std::vector<double>& x_m, const std::vector<double>& y_m,
                                 const std::vector<double>& load_n, const std::vector<double>& patch_radius_m,
                                 const std::vector<double>& interference_m, double effective_modulus_pa,
                                 double nominal_area_m2, const InteractionSettings& settings = {});

//! Result of the interacting-mode solve.
struct InteractingContact {
  HertzContact contact;          //!< loads with the interaction applied (heights lowered by the extra displacement)
  SpotInteraction interaction;   //!< interaction of the final loads
  int iterations = 0;            //!< fixed-point iterations done
  bool converged = false;        //!< the residual's load error fell below tolerance W
  double last_change = 0.0;      //!< max_i 2 E* a_i |G(u)_i - u_i| / W at the last iterate: the load error of the fixed point [-]
};

//! Interacting mode: fixed point z_i^eff = z_i - u_i(N), N = Hertz solve at load W, by
//! Anderson-accelerated iteration on u (see the .cpp). The uniform far-field term only moves d; the
//! near field redistributes the loads.
InteractingContact solve_interacting_contact(const std::vector<double>& heights_m, const std::vector<double>& x_m,
                                             const std::vector<double>& y_m, double summit_radius_m,
                                             double effective_modulus_pa, double nominal_load_n,
                                             double nominal_area_m2, const InteractionSettings& settings = {},
                                             int max_iterations = 200, double tolerance = 1e-10);

}  // namespace stengmc
