#pragma once
//! The S-TENG elements on a load given as a SPICE netlist, solved by ngspice
//! (circuit/ngspice_library.hpp): the co-simulation behind `[circuit] netlist`.
#include <span>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "circuit/netlist_load.hpp"
#include "circuit/ngspice_library.hpp"
#include "circuit/steng_netlist.hpp"
#include "model/asperity.hpp"
#include "model/motion.hpp"

namespace stengmc {

struct NetlistCircuitRun {
  CircuitResult circuit;            //!< V(port) and Q = integral of the port current, on `times`
  NgspiceVectors raw;               //!< ngspice's own time points: the port voltage and current, then `extra_vectors`
  SpiceTransientSettings settings;  //!< what the transient ran with
};

//! Runs the elements driven by their motions, in parallel between the port node
//! (STENG_PORT_NODE) and ground, on `load`, from times.front() to times.back(), and
//! resamples onto `times`. With `element_traces` also every element's current and its
//! delivered charge Q_i(t) - Q_i(t0) (Q_i = sigma w x - C_i V, exact given V), and each of
//! `extra_vectors` (ngspice vector names, e.g. NetlistProbe::vector) in circuit.probes. ngspice runs
//! in a child process under `budget` (circuit/ngspice_library.hpp).
//! @throws InputError naming the netlist file when ngspice rejects it, its run fails, it
//!         crashes or it exceeds the budget
//! @throws ModelError when a result is not finite
NetlistCircuitRun solve_netlist_circuit(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                                        std::span<const double> times, const NetlistLoad& load, bool element_traces,
                                        const std::vector<std::string>& extra_vectors = {},
                                        const ChildBudget& budget = {}, bool show_progress = false);

//! Devices ngspice builds for `elements` S-TENG elements on `load` (the work estimate's count).
double netlist_circuit_devices(std::size_t elements, const NetlistLoad& load);

//! ngspice's time steps for a run of `samples` output samples: at most a tenth of the sample
//! step each (steng_netlist.hpp), doubled for rejected steps and breakpoints.
double netlist_circuit_steps(double samples);

}  // namespace stengmc
