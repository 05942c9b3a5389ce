#pragma once
//! What a load netlist may hold (docs/faults.md, "Netlists are data"). A netlist someone
//! shared must not make stengmc run commands or read files: ngspice runs a control section
//! (any card its front end reads as `.control`, which it matches by prefix: `.controlx`
//! too), `*#` lines, `pre_` commands and `shell`; its XSPICE code models read files
//! (filesource, d_source, d_state, table2D/3D); OSDI devices load compiled code; `.include`
//! and `.lib` read any path. So the policy is a list of what a load needs, and every card
//! outside it is refused with its file and line:
//!  - elements, by their first letter: every SPICE device but XSPICE (A) and OSDI (N);
//!  - `.model` of a built-in device type (diodes, transistors, switches, R, C, L, lines);
//!  - `.subckt` / `.ends`, `.param`, `.func`;
//!  - `.include` / `.inc` and `.lib FILE ENTRY` of regular files inside the study's folder,
//!    which stengmc reads and inlines itself (circuit/netlist_load.hpp), and inside a
//!    library file its `.lib ENTRY` ... `.endl` sections;
//!  - `.end`, after which nothing is read.
//! Dot cards are matched whole, not by prefix, so nothing ngspice would read as another
//! card passes as an accepted one.
#include <string>

#include "circuit/spice_cards.hpp"

namespace stengmc {

enum class CardKind {
  element,       //!< a device or subcircuit instance
  model,         //!< .model of a built-in type
  subcircuit,    //!< .subckt
  ends,          //!< .ends
  parameter,     //!< .param
  function,      //!< .func
  include,       //!< .include / .inc FILE
  library,       //!< .lib FILE ENTRY (a call) or, in a library file, .lib ENTRY (a section)
  library_end,   //!< .endl
  end,           //!< .end
};

//! The kind of an accepted card.
//! @throws InputError naming the card's file and line, what it is and why it is refused
CardKind classify_card(const SpiceCard& card);

}  // namespace stengmc
