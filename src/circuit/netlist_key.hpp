#pragma once
//! `[circuit] netlist = "load.cir"` of a study file (README: study files).
#include <string>

#include "circuit/circuit_solver.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! Reads the key when present: the netlist, relative to the study file's folder, checked
//! (circuit/netlist_load.hpp) into params.netlist. It replaces the built-in load, so it
//! cannot be combined with load_resistance_ohm or load_capacitance_f.
//! @throws InputError naming the study file, the key and what was expected (or the
//!         netlist file and its line)
void read_netlist_key(TomlTable& circuit, const std::string& study_file, CircuitParams& params);

}  // namespace stengmc
