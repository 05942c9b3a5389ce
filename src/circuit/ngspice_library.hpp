#pragma once
//! The shared ngspice library (libngspice, Debian libngspice0-dev) behind one call: load a
//! netlist, run its transient, read vectors. libngspice keeps one global simulator state
//! and is not re-entrant: every call here holds one process-wide mutex, so concurrent
//! callers (an ensemble's threads) take turns. A build without it (STENGMC_WITH_NGSPICE
//! off) keeps the interface and refuses with an InputError.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

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
  std::vector<std::string> vectors;  //!< names as ngspice knows them: "v(steng)", "vsense#branch", "@d1[id]"
  double stop_time_s = 0.0;          //!< the transient's end: a run that stops earlier is an error
  std::string origin;                //!< what messages blame (the user's netlist file)
  //! Where each card came from ("file:line", or "" for stengmc's own), so that ngspice's
  //! "Error on line N" can be traced to the user's file; empty or one per card.
  std::vector<std::string> card_origins;
};

//! The accepted time points and the wanted vectors on them.
struct NgspiceVectors {
  std::vector<double> time_s;
  std::vector<std::vector<double>> values;  //!< one per NgspiceTransient::vectors, same order
};

//! Runs the transient (serialised with every other call in the process).
//! @throws InputError naming `origin` with ngspice's own messages when the netlist does
//!         not load, the analysis fails or stops before stop_time_s (ngspice reports
//!         success even then), or a wanted vector does not exist; or when this build has
//!         no ngspice
NgspiceVectors run_ngspice_transient(const NgspiceTransient& transient);

}  // namespace stengmc
