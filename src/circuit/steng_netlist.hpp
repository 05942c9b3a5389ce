#pragma once
//! The S-TENG elements as SPICE cards, shared by the co-simulation (netlist_circuit.hpp)
//! and `stengmc export-netlist` (io/netlist_export.hpp), so both run the same circuit.
//!
//! Each element is the paper's appendix subcircuit (second model, Fig. 10; MODEL.md §2):
//! an open-circuit voltage source sigma d0 x / (eps0 (l - x)) in series with the
//! capacitor C(x) = eps0 w (l - x) / d0, driven by its displacement x(t) as a node
//! voltage (1 V per metre). Two corrections to the printed listing: its `V(1)` means the
//! node `l`, and the terminals are `vp`/`vn` since ngspice takes no `+`/`-` inside V().
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "model/asperity.hpp"

namespace stengmc {

//! The `.subckt` card block of one element (named stengmc_element), epsilon0 in F/m.
std::vector<std::string> steng_subcircuit_cards(double epsilon0_f_per_m);

//! Element `index`'s cards: its parameter sources, its displacement source
//! `Vstengmc_x<index>` with the given value (e.g. "external" or a PWL(...) list) and the
//! instance between STENG_ELEMENT_NODE and ground.
std::vector<std::string> steng_element_cards(std::size_t index, const StengElement& element,
                                             const std::string& displacement_source);

//! The name ngspice gives element `index`'s displacement source (lower case).
std::string steng_displacement_source_name(std::size_t index);

//! The 0 V source between the elements and `port_node` that measures the port current.
std::vector<std::string> steng_port_cards(const std::string& port_node);

//! Its branch current: the current the elements deliver into the load [A].
inline constexpr const char* STENG_PORT_CURRENT_VECTOR = "vstengmc_port#branch";

//! The node the elements share, on the near side of the sense source.
inline constexpr const char* STENG_ELEMENT_NODE = "stengmc_port";

//! The branch current of element `index`'s sense source: minus the element's current into the load.
std::string steng_element_current_vector(std::size_t index);

//! The transient's numerical settings, scaled to the problem (NGSPICE-NOTES, measured).
struct SpiceTransientSettings {
  double stop_time_s = 0.0;
  double print_step_s = 0.0;  //!< tstep: ngspice's first step is a tenth of it
  double max_step_s = 0.0;    //!< tmax
  double reltol = 1e-6;
  double abstol_a = 1e-12;
  double chgtol_c = 1e-14;
  double vntol_v = 1e-6;
};

//! Settings for elements moving at speeds up to `max_speed_m_per_s` on an output grid of
//! step `sample_step_s` up to `stop_time_s`. `time_constant_s` bounds the first step: the
//! load's R times the elements' capacitance where known (ngspice's first step is backward
//! Euler and must be well below it).
SpiceTransientSettings choose_transient(std::span<const StengElement> elements, double max_speed_m_per_s,
                                        double sample_step_s, double stop_time_s, double time_constant_s);

//! The `.options` and `.tran` cards of `settings`.
std::vector<std::string> transient_cards(const SpiceTransientSettings& settings);

//! Every digit a double needs (shortest round trip), so ngspice reads exactly the number we hold.
std::string spice_number(double value);

}  // namespace stengmc
