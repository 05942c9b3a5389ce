#pragma once
//! `[circuit] netlist = "load.cir"` of a study file (README: study files).
#include <memory>
#include <string>

#include "circuit/netlist_load.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! Reads the key when present: the netlist, relative to the study file's folder, checked
//! (circuit/netlist_load.hpp); none when absent. It replaces the built-in load, so it
//! cannot be combined with load_resistance_ohm or load_capacitance_f.
//! @throws InputError naming the study file, the key and what was expected (or the
//!         netlist file and its line)
std::shared_ptr<const NetlistLoad> read_netlist_key(TomlTable& circuit, const std::string& study_file);

}  // namespace stengmc
