#pragma once
//! Greenwood–Williamson contact of a rough surface with a rigid flat: each summit is a
//! Hertz sphere of radius R_s, the flat sits at separation d, and d is solved so that the
//! summit loads add up to the nominal load (MODEL.md §4; Greenwood & Williamson 1966;
//! Johnson 1985, §4.2 and §13.2).
#include <cstddef>
#include <vector>

namespace stengmc {

//! The state of a population pressed by a rigid flat at one separation.
struct HertzContact {
  double separation_m = 0.0;              //!< d, flat position on the height axis [m]
  std::vector<double> interference_m;     //!< delta_i = max(z_i - d, 0) [m]
  std::vector<double> load_n;             //!< N_i = (4/3) E* R_s^(1/2) delta_i^(3/2) [N]
  std::vector<double> patch_radius_m;     //!< a_i = sqrt(R_s delta_i) [m]
  double total_load_n = 0.0;              //!< sum of N_i (compensated sum) [N]
  double real_area_m2 = 0.0;              //!< A_r = sum of pi a_i^2 [m^2]
  std::size_t contact_count = 0;          //!< asperities with delta_i > 0
  double load_relative_error = 0.0;       //!< |sum N_i - W| / W after a load solve [-]
  int solver_iterations = 0;              //!< TOMS 748 iterations of the load solve
};

//! Relative load error the load solve guarantees; solve_hertz_contact verifies it.
inline constexpr double HERTZ_LOAD_RELATIVE_TOLERANCE = 1e-12;

//! Hertz load of one summit, (4/3) E* R_s^(1/2) delta^(3/2) [N] (0 for delta <= 0).
double hertz_load(double interference_m, double summit_radius_m, double effective_modulus_pa);

//! The interference one summit needs to carry `load_n` alone, (3 W / (4 E* sqrt(R_s)))^(2/3)
//! [m], computed without overflow or underflow in between (inf or 0 when the result itself
//! is beyond a double).
double hertz_interference_for_load(double load_n, double summit_radius_m, double effective_modulus_pa);

//! Interferences the load solve works with [m]: far beyond any physical contact on both
//! sides, and far inside a double's range so loads, areas and sums of thousands of summits
//! stay finite. A surface whose nominal load needs more or less is refused when read.
inline constexpr double MIN_HERTZ_INTERFERENCE_M = 1e-50;
inline constexpr double MAX_HERTZ_INTERFERENCE_M = 1e50;

//! The population at a given separation d (no solve). Inputs are validated as below.
HertzContact hertz_contact_at_separation(const std::vector<double>& heights_m, double summit_radius_m,
                                         double effective_modulus_pa, double separation_m);

//! Solves sum_i N_i(d) = W for d with Boost.Math TOMS 748 (Alefeld, Potra & Shi 1995)
//! and verifies |sum N_i - W| <= 1e-12 W.
//! @throws InputError for R_s <= 0, E* <= 0 or non-finite heights
//! @throws ModelError for a load no separation can carry: W not finite, W <= 0
//!         (an adhesionless flat carries no tension, and W = 0 fixes no separation),
//!         or W > 0 with no asperities; also if the verified error exceeds 1e-12.
HertzContact solve_hertz_contact(const std::vector<double>& heights_m, double summit_radius_m,
                                 double effective_modulus_pa, double nominal_load_n);

//! MODEL.md §4 screening number for the independence error: (4 / 3 pi) (A_r/A0)^(3/2) [-]
//! (a derived estimate, not Goryacheva's own criterion; ~1 % at A_r/A0 = 8 %).
double screening_interaction_estimate(double contact_density);

}  // namespace stengmc
