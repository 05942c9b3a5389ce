#pragma once
//! The load's keys of a study's [circuit] table, read and listed beside CircuitParams
//! (docs/study-files.md): what run files record as /circuit attributes and generated
//! studies write back. `netlist` and `input` are the study's, read beside it.
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "core/setting.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! R, C_L and the substeps from `circuit`; InputError names the key.
CircuitParams read_circuit_params(TomlTable& circuit);

std::vector<Setting> circuit_settings(const CircuitParams& params);

}  // namespace stengmc
