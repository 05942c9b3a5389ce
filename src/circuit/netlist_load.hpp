#pragma once
//! A load circuit given as a SPICE netlist (`[circuit] netlist = "load.cir"`, README:
//! "ngspice netlist"): the user describes what the S-TENG port drives; stengmc adds the
//! S-TENG elements and runs the transient through the ngspice library
//! (circuit/netlist_circuit.hpp).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

//! The node the S-TENG elements drive, against ground `0`: every netlist names it.
inline constexpr std::string_view STENG_PORT_NODE = "steng";

struct NetlistLoad {
  std::string file;                //!< where it was read from (messages, provenance)
  std::string text;                //!< the file, verbatim (recorded in every output)
  std::vector<std::string> lines;  //!< the circuit cards handed to ngspice: no title, no .end
  std::vector<std::size_t> line_numbers;  //!< each card's line in the file (1-based), for messages
};

//! Checks a load netlist's text and splits it into the cards ngspice receives. As in any
//! SPICE file the first line is the title (ignored); `.end` is optional. Analyses and
//! control blocks (.tran, .op, .ac, .dc, .control, ...) are stengmc's to set and are
//! rejected, as is a netlist that never names the port node.
//! @throws InputError naming `file`, the line and what was expected
NetlistLoad parse_netlist_load(const std::string& text, const std::string& file);

}  // namespace stengmc
