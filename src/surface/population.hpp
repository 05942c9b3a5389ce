#pragma once
//! One realisation of a surface: the sampled summits, their contact with the counter-face,
//! and the asperities (summits in contact) a simulation runs (MODEL.md §4, §5).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "model/asperity.hpp"
#include "surface/interaction.hpp"
#include "surface/random_surface.hpp"

namespace stengmc {

//! The contact of the sampled summits (only with material data).
struct PopulationContact {
  double summit_radius_m = 0.0;       //!< R_s [m]
  double separation_m = 0.0;          //!< d: flat position on the height axis (hertz) [m]; 0 under fixed load
  std::vector<double> interference_m; //!< delta_i per summit (0 = not in contact) [m]
  std::vector<double> patch_radius_m; //!< a_i per summit [m]
  double total_load_n = 0.0;          //!< sum N_i [N]
  double real_area_m2 = 0.0;          //!< A_r = sum pi a_i^2 [m^2]
  double contact_density = 0.0;       //!< A_r / A0 [-]
  double screening_estimate = 0.0;    //!< (4/3 pi)(A_r/A0)^(3/2), MODEL.md §4 [-]
  SpotInteraction interaction;        //!< Goryacheva estimate for the final loads
  bool hertz_load = false;            //!< loads from the Hertz solve (else a fixed load per summit)
  bool load_carried = true;           //!< false: a Hertz load, but the realisation drew no summit
  int interacting_iterations = 0;     //!< interacting mode: fixed-point iterations (0 otherwise)
  bool interacting_converged = true;  //!< interacting mode: the fixed point was reached
};

//! One realisation's population.
struct Population {
  std::uint64_t realisation = 0;
  // Every sampled summit, in draw order (empty for a fixed list of asperities).
  std::vector<double> height_m;              //!< z_i [m]
  std::vector<double> x_m, y_m;              //!< positions on the nominal area [m]
  std::vector<double> sampled_stiffness_n_per_m;  //!< drawn k_i (sampled rule; empty under mindlin) [N/m]
  std::vector<double> drive_phase_rad;       //!< phi_i [rad]
  std::vector<double> onset_s;               //!< Model 2 contact onsets t_on,i [s] (all 0 without an [onset] law)
  std::vector<double> lifetime_s;            //!< Model 2 contact lifetimes t_off,i - t_on,i [s] (empty without a [lifetime] law)
  std::vector<double> wear_rate_per_ms;      //!< Model 2 wear rates w_i [1/ms] (empty without a [wear] law)
  //! Model 2 stiffness steps, one draw per summit (empty without [steps]): when [s] (its
  //! onset plus the drawn delay) and k after / k before [-], 1 for a summit without a step.
  std::vector<double> step_time_s, step_factor;
  std::vector<double> load_n;                //!< N_i per summit (0 = not in contact) [N]
  std::optional<PopulationContact> contact;  //!< with material data
  //! The asperities a run simulates: the summits in contact, in summit order.
  std::vector<Asperity> asperities;
  std::vector<std::size_t> summit_of_asperity;  //!< index into the summit arrays, per asperity
};

//! Realisation `realisation` of `surface` under `seed`: every random number comes from
//! random_stream(seed, realisation, kind) with one named stream per quantity, so the
//! result depends on (surface, seed, realisation) alone.
//! A Hertz load with no summit drawn has no separation that carries W: the population is
//! returned empty with contact->load_carried = false (a run of it fails, an examination
//! counts it).
//! @throws ModelError when an asperity in contact gets k, m or l <= 0 (a degenerate patch).
Population sample_population(const RandomSurface& surface, std::uint64_t seed, std::uint64_t realisation);

}  // namespace stengmc
