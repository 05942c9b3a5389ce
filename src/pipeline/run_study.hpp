#pragma once
//! One realisation: study -> tribology of every asperity -> domain check -> circuit.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "pipeline/study.hpp"
#include "pipeline/analyse_spectra.hpp"
#include "pipeline/work_estimate.hpp"
#include "pipeline/validity.hpp"
#include "tribology/events.hpp"
#include "tribology/trajectory.hpp"

namespace stengmc {

//! What the summary and the spectra need of one asperity's motion, gathered while it
//! streams through (so the samples themselves need not be kept).
struct AsperityStatistics {
  double slip_fraction = 0.0;         //!< fraction of samples sliding (pipeline/slip_fraction.hpp)
  double max_x_m = 0.0;               //!< max x over the run [m]
  double rms_velocity_m_per_s = 0.0;  //!< root mean square of x' [m/s]
  bool moved = false;                 //!< any x' != 0 or any event
  std::vector<bool> sliding;          //!< per sample: slides (for the spectra's interval)
};

struct RunResult {
  std::vector<double> times_s;                       //!< output grid [s]
  //! One per asperity, same order as the study: motion, samples (x, v, friction), events
  //! and step counts. With RunOptions::keep_traces off only the events and step counts.
  std::vector<Trajectory> trajectories;
  std::vector<AsperityStatistics> statistics;        //!< one per asperity
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
  WorkLimits limits{};        //!< the run is refused (InputError) when its estimate exceeds these
  //! Keep every asperity's motion and the traces the study's [output] asks for (and the
  //! element currents its [spectrum] analyses). Off (an ensemble realisation), each motion
  //! is summed into the circuit and dropped: memory per asperity is a few bytes per sample
  //! instead of ~100, and no element-current spectra are computed (nothing records them).
  bool keep_traces = true;
  //! With keep_traces: also keep every asperity's dense motion (Trajectory::motion) for the
  //! caller (tests, `export-netlist`). Off (`stengmc run`), a motion is dropped once it is
  //! sampled and summed, whatever [output] traces asks for: an excited asperity's dense
  //! output is ~30 MB per ms (a RODAS4 step per node of the modulation's grid), so keeping
  //! all of them is what stops a long run from fitting (docs/output-files.md, "Long runs").
  bool keep_motions = true;
  //! Model 2 asperities solved side by side, one thread each (Model 1: one at a time). The
  //! circuit takes them in their order, so any count gives the same run bit for bit; each
  //! holds its dense output until its turn, so memory grows by one asperity's per thread.
  //! An ensemble runs its realisations in parallel instead: leave it at 1 there.
  std::size_t threads = 1;
};

//! Runs the study's realisation. Throws ModelError when x reaches l under policy `error`,
//! InputError before anything runs when its work estimate (pipeline/work_estimate.hpp)
//! exceeds the limits.
RunResult run_study(const Study& study, const RunOptions& options = {});

}  // namespace stengmc
