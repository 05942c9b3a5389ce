#pragma once
//! The validity report of a population: does the paper's picture (independent spots, an
//! asperity that can slip, an element whose x stays below l) hold for it? (MODEL.md §1, §2, §4)
#include <cstddef>
#include <string>
#include <vector>

#include "surface/population.hpp"
#include "tribology/model1.hpp"
#include "tribology/model2.hpp"

namespace stengmc {

//! Where a check turns into a warning (docs/study-files.md, validity report).
struct ValidityThresholds {
  //! Spots count as independent while their interaction would move less than this
  //! fraction of the load between them (SpotInteraction::load_redistribution) [-].
  double load_redistribution = 0.05;
  //! Model 2's largest static deflection counts as "near l" from this fraction of l [-].
  double near_length_fraction = 0.9;
  //! Hertz (small strain) is doubtful from this a / R_s [-] (Johnson 1985, §4.2: a << R).
  double patch_over_radius = 0.3;
};

//! Which tribology models a report speaks about: a run checks its own model only, the
//! `surface` command both (against the defaults unless --study gives parameters).
struct ModelScope {
  bool model1 = true;
  bool model2 = true;
};

//! The report. Per-asperity arrays follow Population::asperities.
struct ValidityReport {
  bool contact_known = false;            //!< the population has contact data (material data given)
  bool load_carried = true;              //!< false: a Hertz load with no summit to carry it
  bool interacting_converged = true;     //!< interacting mode reached its fixed point (true when not applied)
  bool beyond_hertz = false;             //!< some patch beyond Hertz's small-strain range
  double contact_density = 0.0;          //!< A_r / A0 [-]
  double screening_estimate = 0.0;       //!< (4/3 pi)(A_r/A0)^(3/2) [-]
  double load_redistribution = 0.0;      //!< fraction of the load the interaction moves between spots [-]
  double interaction_max_relative = 0.0; //!< max extra displacement over delta [-]
  std::size_t overlapping_pairs = 0;     //!< patches that would merge
  bool independence_holds = true;        //!< load_redistribution below its threshold
  double max_patch_over_radius = 0.0;    //!< largest a / R_s [-]

  // Per asperity; all zero for a model outside the report's scope.
  std::vector<unsigned char> cannot_slip_model1;   //!< A <= mu_s N / k: never moves under Model 1
  std::vector<double> static_deflection_over_length;  //!< Model 2 breakaway deflection (mu_s N - c v_b)/k over l [-]
  std::vector<unsigned char> near_length_model2;   //!< that ratio >= near_length_fraction
  std::size_t cannot_slip_count = 0;
  std::size_t near_length_count = 0;

  //! One sentence per failed check, for the screen and the file, by what they concern:
  //! the contact picture, and each tribology model (a run prints its own model's only).
  std::vector<std::string> contact_warnings;
  std::vector<std::string> model1_warnings;
  std::vector<std::string> model2_warnings;
};

//! Checks `population` against the Model 1 and Model 2 parameters (the study's, or the
//! defaults when a surface is examined on its own).
ValidityReport assess_validity(const Population& population, const Model1Params& model1, const Model2Params& model2,
                               const ValidityThresholds& thresholds = {}, ModelScope scope = {});

}  // namespace stengmc
