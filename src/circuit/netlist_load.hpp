#pragma once
//! A load circuit given as a SPICE netlist (`[circuit] netlist = "load.cir"`, README:
//! "ngspice netlist"): the user describes what the S-TENG port drives; stengmc adds the
//! S-TENG elements and runs the transient through the ngspice library
//! (circuit/netlist_circuit.hpp).
//!
//! A netlist is data, not a program (circuit/netlist_policy.hpp): it is split into cards
//! the way ngspice splits it (circuit/spice_cards.hpp), every card is checked against the
//! list of what a load needs, `.include` and `.lib` are read here from regular files
//! inside the study's folder and inlined, and ngspice receives exactly the checked cards.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

//! The node the S-TENG elements drive, against ground `0`: every netlist names it.
inline constexpr std::string_view STENG_PORT_NODE = "steng";

//! A netlist or a file it includes is at most this large [bytes]; all of them together
//! at most four times as much.
inline constexpr std::uint64_t MAX_NETLIST_FILE_BYTES = 16ull << 20;
//! `.include` / `.lib` nest at most this deep.
inline constexpr std::size_t MAX_INCLUDE_DEPTH = 16;

struct NetlistFile {
  std::string path;  //!< as read (messages, provenance)
  std::string text;  //!< verbatim
};

struct NetlistLoad {
  std::string file;                  //!< where it was read from (messages, provenance)
  std::string text;                  //!< the file, verbatim (recorded in every output)
  std::vector<NetlistFile> included;  //!< files `.include` / `.lib` read, verbatim, in the order read
  //! The cards handed to ngspice: no title, no comments, continuations joined, includes
  //! inlined, no .end; each one accepted by the policy.
  std::vector<std::string> lines;
  std::vector<std::string> origins;  //!< each card's "file:line", for messages
  double devices = 0.0;              //!< devices ngspice builds from `lines`, subcircuits expanded
};

//! Checks a load netlist's text and makes the cards ngspice receives. As in any SPICE file
//! the first line is the title (ignored); `.end` is optional. Files named by `.include` /
//! `.lib` are read relative to the file that names them and must lie inside
//! `allowed_folder` (links resolved); "" means the folder of `file`.
//! @throws InputError naming the file, the line and what was expected
NetlistLoad parse_netlist_load(const std::string& text, const std::string& file, const std::string& allowed_folder = "");

//! Reads the netlist at `path` (a regular file inside `allowed_folder`, links resolved)
//! and parses it. `origin` names what gave the path in messages about reading it (the
//! study file, line and key); messages about its contents name the netlist's own lines.
NetlistLoad read_netlist_load(const std::string& path, const std::string& allowed_folder, const std::string& origin);

//! The canonical cards as one text (what ngspice is given and `export-netlist` writes).
std::string netlist_cards_text(const NetlistLoad& load);

}  // namespace stengmc
