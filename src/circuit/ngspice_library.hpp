#pragma once
//! The shared ngspice library (libngspice, Debian libngspice0-dev) behind one call: load a
//! netlist, run its transient, read vectors. Each call runs ngspice in a child process of
//! its own (core/child_process.hpp) under a time and memory budget: a netlist that crashes
//! ngspice (a recursive .func overflowed its stack), loops or grows without bound is an
//! error naming the netlist, not the end of stengmc; and the child starts ngspice afresh in
//! the root folder, so no `.spiceinit` of the current folder (which ngspice runs as
//! commands, `shell` included) is read. Children are independent: an ensemble's threads run
//! theirs at once. A build without ngspice (STENGMC_WITH_NGSPICE off) keeps the interface
//! and refuses with an InputError.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/child_process.hpp"

namespace stengmc {

//! Whether this build links libngspice.
bool ngspice_library_available();

//! One transient analysis: the netlist's cards (title first, `.end` last, with its own
//! `.tran`), the values of its EXTERNAL voltage sources, and the vectors wanted.
struct NgspiceTransient {
  std::vector<std::string> cards;
  //! The value of EXTERNAL voltage source `name` (lower case, as ngspice reports it) at
  //! time t [s]; ngspice asks at every Newton iteration of every trial step.
  std::function<double(std::string_view name, double t_s)> external_voltage;
  //! Names as ngspice knows them: "v(steng)", "vsense#branch", "@d1[id]". Only these are
  //! kept (a `.save` card is added), so memory grows with them, not with the circuit.
  std::vector<std::string> vectors;
  double stop_time_s = 0.0;          //!< the transient's end: a run that stops earlier is an error
  std::string origin;                //!< what messages blame (the user's netlist file)
  //! Where each card came from ("file:line", or "" for stengmc's own), so that ngspice's
  //! "Error on line N" can be traced to the user's file; empty or one per card.
  std::vector<std::string> card_origins;
  ChildBudget budget;          //!< what the ngspice child may spend
  bool show_progress = false;  //!< a progress bar with ETA on stderr while it runs
};

//! The accepted time points and the wanted vectors on them.
struct NgspiceVectors {
  std::vector<double> time_s;
  std::vector<std::vector<double>> values;  //!< one per NgspiceTransient::vectors, same order
};

//! Runs the transient in a child process.
//! @throws InputError naming `origin` with ngspice's own messages when the netlist does
//!         not load, the analysis fails or stops before stop_time_s (ngspice reports
//!         success even then), a wanted vector does not exist, or ngspice crashed or was
//!         stopped at its budget; or when this build has no ngspice
NgspiceVectors run_ngspice_transient(const NgspiceTransient& transient);

}  // namespace stengmc
