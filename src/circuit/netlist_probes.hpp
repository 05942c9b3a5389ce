#pragma once
//! `[circuit] probes = ["v(store)", "i(d1)"]`: quantities of a load netlist recorded beside
//! the port (README, "Through ngspice"). A harvester designer wants the storage capacitor's
//! voltage, not only the port's.
#include <functional>
#include <string>
#include <vector>

#include "circuit/netlist_load.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! One probe of a netlist.
struct NetlistProbe {
  std::string name;     //!< as the study writes it, lower case: "v(store)", "i(d1)"
  std::string vector;   //!< what ngspice saves and returns: "v(store)", "@d1[id]", "vsense#branch"
  std::string dataset;  //!< its name in the run file's /circuit/probes: "v_store", "i_d1"
  std::string units;    //!< "V" or "A"
};

//! The probe `text`: `v(node)` (a node's voltage against ground) or `i(device)` (the
//! current through a V, E, H or L device, its branch, or through an R, C or D, positive
//! from its first node to its second), the node or device one of `load`'s cards names
//! (ground 0 and the port steng are nodes too). Names are letters, digits and `_`.
//! @throws InputError (via `fail`) saying what is wrong and what is expected
NetlistProbe parse_netlist_probe(const std::string& text, const NetlistLoad& load,
                                 const std::function<void(const std::string&)>& fail);

//! Reads `probes` of a `[circuit]` table: none when absent; it needs `load` (a netlist).
std::vector<NetlistProbe> read_probes_key(TomlTable& circuit, const NetlistLoad* load);

}  // namespace stengmc
