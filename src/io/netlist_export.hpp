#pragma once
//! `stengmc export-netlist`: a study's realisation as a stand-alone ngspice / LTspice
//! netlist (README: "ngspice netlist"), for users who stay in their circuit simulator.
#include <string>

#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"

namespace stengmc {

//! The netlist text: header comments (study, realisation, seed, program version, git
//! revision, the port node), the S-TENG subcircuit, each element driven by its x(t) as a
//! PWL source through the run's samples (valid part), in parallel between the port node
//! and ground, the load (R || C_L, or the study's `[circuit] netlist`), and `.options` /
//! `.tran` chosen as the co-simulation chooses them (circuit/steng_netlist.hpp).
std::string export_netlist_text(const Study& study, const RunResult& result);

//! Writes it to `path` (temporary name, renamed when complete).
void write_netlist_file(const std::string& path, const Study& study, const RunResult& result);

}  // namespace stengmc
