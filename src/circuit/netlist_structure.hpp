#pragma once
//! The size and depth of what ngspice would build from a netlist's cards, found before it
//! builds it: subcircuits instanced inside each other multiply (ten levels of ten
//! instances are 1e10 devices), a subcircuit that instances itself expands for ever, and
//! ngspice evaluates `.func` calls and bracketed expressions recursively, so a deep or
//! self-calling chain overflows its stack (`.func f(x) {f(x)+1}` crashed stengmc with
//! SIGSEGV). Each is refused naming its card; the device count goes into the work estimate
//! (pipeline/work_estimate.hpp).
#include <cstddef>
#include <vector>

#include "circuit/spice_cards.hpp"

namespace stengmc {

//! Longest chain of `.func` calls accepted (ngspice recurses per call).
inline constexpr std::size_t MAX_FUNCTION_DEPTH = 32;
//! Deepest nesting of brackets ( { [ in one card accepted (ngspice's parsers recurse).
inline constexpr std::size_t MAX_BRACKET_DEPTH = 64;
//! Longest card accepted [characters]: a vendor model card is a few kilobytes.
inline constexpr std::size_t MAX_CARD_CHARACTERS = 1 << 20;
//! Devices after subcircuit expansion beyond which a netlist is refused outright; below
//! it the work estimate judges the run.
inline constexpr double MAX_EXPANDED_DEVICES = 1e7;

struct NetlistStructure {
  double devices = 0.0;  //!< devices ngspice builds, subcircuits expanded
};

//! Checks subcircuit nesting (`.subckt` closed by `.ends`), instancing cycles, the device
//! count after expansion, `.func` call depth and self-calls, bracket depth and card length.
//! @throws InputError naming the card's file and line and what is wrong
NetlistStructure examine_netlist_structure(const std::vector<SpiceCard>& cards);

}  // namespace stengmc
