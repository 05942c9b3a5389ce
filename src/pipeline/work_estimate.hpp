#pragma once
//! What a computation will cost, estimated before it starts, and the limits it must stay
//! within (docs/faults.md, "Limits"). Every command estimates its work here and refuses, naming the
//! quantity, its estimate, the limit and the factor, what cannot fit or finish: one value
//! (drive_frequency_hz = 1e12, a swept sample_rate_hz = 1e15) must never grow memory until
//! the machine gives up, or loop for ever.
//!
//! The estimate is a sum of named contributions, each a count (samples, asperities,
//! events, steps) times a per-item cost. The per-item costs are the named constants below,
//! measured on this code (docs/faults.md, "Limits"); whoever changes what a solver keeps or does
//! per sample, asperity, event or step updates them here, in one place.
#include <cstddef>
#include <string>
#include <vector>

#include "core/child_process.hpp"
#include "pipeline/study.hpp"
#include "spectral/spectrum_settings.hpp"
#include "surface/random_surface.hpp"

namespace stengmc {

// ---------------------------------------------------------------- per-item costs

//! Memory of one kept trace (an `[output] traces` entry) per asperity and output sample
//! [bytes]: the array a run keeps until it writes the file.
inline constexpr double TRACE_BYTES_PER_SAMPLE = 8;
//! Memory per asperity and output sample of the circuit input a run keeps for the element
//! currents and charges (x, x' and its left limits) when any of them is kept [bytes].
inline constexpr double CURRENT_INPUT_BYTES_PER_SAMPLE = 24;
//! Memory per asperity and output sample whatever is kept [bytes]: its per-sample sliding
//! flags (a bit each, for the spectra) and, for Model 1, the solver's own x, x' and friction
//! while the asperity is in turn, with growth slack.
inline constexpr double RUN_BYTES_PER_ASPERITY_SAMPLE = 1;
inline constexpr double MODEL1_BYTES_PER_ASPERITY_SAMPLE = 64;
//! Memory per output sample shared by all asperities [bytes]: times, V, Q, V' and the
//! measured V; the circuit's sums (ten per sample, circuit/element_sums.hpp) and the grid
//! they copy; the samples of the asperity in turn (x, x', its left limits, midpoints).
inline constexpr double RUN_BYTES_PER_SAMPLE = 192;
//! Memory per output sample of one asperity's samples (x, x', left limits, midpoints) [bytes]:
//! each further asperity solved at once (RunOptions::threads) holds its own.
inline constexpr double SAMPLES_BYTES_PER_SAMPLE = 48;
//! Memory of an output file per value written [bytes]: the file is built in memory and
//! copied once while it is written out (core/hdf5_file.hpp).
inline constexpr double FILE_BYTES_PER_VALUE = 16;
//! Memory per stick/slip event [bytes]: Model 1's phase (its closed-form coefficients),
//! the event in the trajectory and in the run's sorted list, its row in the file.
inline constexpr double BYTES_PER_EVENT = 256;
//! Memory per Model 2 integrator step [bytes]: a dense-output knot (t, x, x', x'': 32) and
//! its piece (80), with the vectors' growth slack (measured: 36 MB per excited asperity and
//! ms at ~3e5 steps per ms, 120 bytes a step).
inline constexpr double MODEL2_BYTES_PER_STEP = 192;
//! The same for a modulated friction ([counterface]), whose integrator reserves its steps
//! once (a step per node of the modulation's grid: tribology/evolving_contact.cpp) [bytes].
inline constexpr double MODEL2_BYTES_PER_RESERVED_STEP = 128;
//! Model 2 (RODAS4) steps per natural period at relative_tolerance 1e-8: 32 (v_b = 1 m/s)
//! to 94 (v_b = 10 m/s) measured on the Fig. 6 studies; steps grow as tol^(-1/4) (order 4).
inline constexpr double MODEL2_STEPS_PER_PERIOD = 100;
//! Model 2 steps an asperity takes however short the run (start-up, one stick phase).
inline constexpr double MODEL2_MIN_STEPS = 2000;
//! Model 1 `exact`: the slip-end scan evaluates x' 64 times per shorter period (drive or
//! natural), and each event adds a TOMS 748 refinement (~30 evaluations).
inline constexpr double MODEL1_SCAN_STEPS_PER_PERIOD = 64;
inline constexpr double STEPS_PER_EVENT = 30;
//! Stick/slip events per asperity: x' changes sign at most twice per period of the faster
//! of drive and natural oscillation.
inline constexpr double EVENTS_PER_PERIOD = 2;
//! Circuit: Radau IIA stages per substep, each evaluating every element.
inline constexpr double CIRCUIT_STAGES = 3;
//! Memory of a surface realisation per summit drawn [bytes]: ten per-summit arrays, and
//! their copy in the file being written.
inline constexpr double BYTES_PER_SUMMIT = 240;
//! The interacting mode's fixed-point iterations at most (surface/interaction).
inline constexpr double INTERACTION_ITERATIONS = 200;
//! ESPRIT memory per analysed sample and line [bytes]: the least-squares design matrix
//! (cos, sin per line) and the polish's Jacobian.
inline constexpr double ESPRIT_BYTES_PER_SAMPLE_LINE = 48;
//! Spectra: an FFT costs ~ N log2 N steps; its complex buffer 16 bytes per point.
inline constexpr double FFT_BYTES_PER_POINT = 16;
//! The program itself, its libraries and small tables [bytes].
inline constexpr double BASE_BYTES = 64e6;
//! ngspice (a `[circuit] netlist` load): solver steps per device and time step, in the
//! ~100 ns units of WorkLimits::steps (measured: 52 ns per device and step for 20 000
//! resistors); memory per device for its matrix and instance (measured: ~2.5 kB) [bytes];
//! and per value of the vectors it keeps (time, V, the port current, each element's
//! current when traces are kept) at every accepted step [bytes].
inline constexpr double NGSPICE_STEPS_PER_DEVICE_STEP = 1.0;
inline constexpr double NGSPICE_BYTES_PER_DEVICE = 4096;
inline constexpr double NGSPICE_BYTES_PER_VALUE = 8.0;
//! What the ngspice child may spend beyond its estimate, for the estimate's error: CPU time
//! as a factor on the estimate's steps at ~100 ns each, with a floor [s].
inline constexpr double NGSPICE_TIME_SAFETY = 20.0;
inline constexpr double NGSPICE_MIN_CPU_SECONDS = 60.0;

// ---------------------------------------------------------------- limits

struct WorkLimits {
  //! Peak memory one command (or one ensemble realisation) may need [bytes]: --max-memory-gb.
  double memory_bytes = 8e9;
  //! Elementary solver steps one run may take (scan steps, integrator steps, circuit stage
  //! evaluations, FFT points; ~100 ns each, so 1e11 is hours): --max-steps.
  double steps = 1e11;
};

//! One named part of an estimate, for the message at the limit.
struct WorkPart {
  std::string what;     //!< "4 asperities x 1e+06 samples"
  double amount = 0.0;  //!< bytes or steps
  std::string remedy;   //!< what lowers it, when the study says ("list fewer [output] traces"); may be empty
};

struct WorkEstimate {
  double samples = 0.0;            //!< output samples M
  double asperities = 0.0;         //!< n
  double events = 0.0;             //!< stick/slip events, all asperities
  double interaction_pairs = 0.0;  //!< spot pairs the interaction visits per realisation
  double memory_bytes = 0.0;       //!< peak memory [bytes]
  double steps = 0.0;              //!< elementary solver steps
  std::vector<WorkPart> memory;    //!< what the memory is made of
  std::vector<WorkPart> work;      //!< what the steps are made of

  void add_memory(std::string what, double bytes, std::string remedy = {});
  void add_steps(std::string what, double steps);
};

//! One run of `study` with `asperities` asperities (its own count when negative: a fixed
//! list or a drawn realisation); `writes_run_file` adds the traces `[output] traces` keeps
//! and the run file they go to (`run`), not an ensemble record. The asperities' dense
//! motions are summed and dropped one at a time (a long run's memory does not grow with
//! their number) unless `keeps_motions` (RunOptions::keep_motions, `export-netlist`) or a
//! netlist load (ngspice reads them all) keeps every one; `threads` Model 2 asperities are
//! solved at once (RunOptions::threads), each with its dense output. A random surface's sampling and
//! interaction are included. With a count given, the asperities' natural frequencies are
//! not known: the estimate is then a lower bound for any realisation with that many (what
//! depends on them is left out).
WorkEstimate estimate_run(const Study& study, double asperities = -1.0, bool writes_run_file = true,
                          bool keeps_motions = false, std::size_t threads = 1);

//! The most threads, from 1 to `wanted`, a `run` of `study` (RunOptions::threads) may solve
//! its asperities on within `limits` memory: more than it has asperities gain nothing, and
//! each holds one asperity's dense output. 1 when even that does not fit (check_work says why).
std::size_t run_threads_within(const Study& study, std::size_t wanted, const WorkLimits& limits);

//! `stengmc circuit`: `elements` displacement series of `samples` samples.
WorkEstimate estimate_circuit(double samples, double elements, std::size_t substeps);

//! `stengmc spectrum`: a signal of `samples` samples with `currents` element currents.
WorkEstimate estimate_spectrum(double samples, double currents, const SpectrumSettings& settings);

//! `stengmc surface`: `realisations` realisations of `surface`.
WorkEstimate estimate_surface(const RandomSurface& surface, double realisations);

//! Summits one realisation draws at most (almost surely): the mean, or for a Poisson count
//! the mean plus 6 standard deviations.
double summits_upper_bound(const RandomSurface& surface);

//! The budget of the ngspice child of `study`'s run (a `[circuit] netlist` load): the
//! memory limit, and CPU time from the estimate of its steps (circuit/ngspice_library.hpp).
ChildBudget ngspice_budget(const Study& study, const WorkLimits& limits);

//! What raises each limit where the limits were given: the command line's options, or a
//! Python function's keyword arguments (max_memory_gb=, max_steps=).
struct LimitNames {
  std::string memory = "--max-memory-gb";
  std::string steps = "--max-steps";
};

//! "" when `estimate` is within `limits`; else what exceeds: the quantity, its estimate,
//! the limit, the factor, the largest contribution and how to raise the limit.
std::string exceeded_limit(const WorkEstimate& estimate, const WorkLimits& limits, const LimitNames& names = {});

//! Throws InputError "<what>: <exceeded_limit>" when the estimate is over a limit.
void check_work(const WorkEstimate& estimate, const WorkLimits& limits, const std::string& what,
                const LimitNames& names = {});

}  // namespace stengmc
