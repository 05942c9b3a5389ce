#pragma once
//! One realisation: study -> tribology of every asperity -> domain check -> circuit.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "io/study.hpp"
#include "pipeline/analyse_spectra.hpp"
#include "pipeline/work_estimate.hpp"
#include "surface/validity.hpp"
#include "tribology/events.hpp"
#include "tribology/trajectory.hpp"

namespace stengmc {

struct RunResult {
  std::vector<double> times_s;                       //!< output grid [s]
  std::vector<Trajectory> trajectories;              //!< one per asperity, same order as the study
  std::vector<std::unique_ptr<Motion>> drives;       //!< imposed x0(t) per asperity (Model 1), else empty
  std::vector<Event> events;                         //!< every asperity's events, by time
  CircuitResult circuit;                             //!< on the valid prefix of the grid
  std::size_t circuit_samples = 0;                   //!< length of that prefix (all samples when valid)
  bool valid = true;                                 //!< false when some x reached l (policy `flag`)
  std::vector<std::string> notes;                    //!< plain-language warnings for the user
  ValidityReport validity;                           //!< the population's validity report (MODEL.md §4)
  std::vector<double> measured_voltage_v;            //!< V plus the study's [noise], what the spectra saw (empty without [noise])
  double noise_sigma_v = 0.0;                        //!< that noise's standard deviation [V]
  double tribology_seconds = 0.0;                    //!< wall time of the tribology [s]
  double circuit_seconds = 0.0;                      //!< wall time of the circuit [s]
  std::optional<SpectralResult> spectra;             //!< when the study has [spectrum]
  double spectrum_seconds = 0.0;                     //!< wall time of the spectral analysis [s]
};

struct RunOptions {
  bool show_progress = true;  //!< progress bars on stderr (an ensemble runs many at once: off)
  WorkLimits limits;          //!< the run is refused (InputError) when its estimate exceeds these
};

//! Runs the study's realisation. Throws ModelError when x reaches l under policy `error`,
//! InputError before anything runs when its work estimate (pipeline/work_estimate.hpp)
//! exceeds the limits.
RunResult run_study(const Study& study, const RunOptions& options = {});

}  // namespace stengmc
