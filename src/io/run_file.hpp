#pragma once
//! The output file of a run (layout: docs/output-files.md). Format version 1.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "core/hdf5_file.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/run_summary.hpp"

namespace stengmc {

inline constexpr std::int64_t RUN_FILE_FORMAT_VERSION = 1;

//! Root attributes every stengmc file carries: what it is and where it came from.
struct Provenance {
  std::string file_type;    //!< "stengmc-run", "stengmc-circuit", "stengmc-spectrum", "stengmc-surface"
  std::string input_file;   //!< the study (or displacement file) it was made from
  std::string input_text;   //!< that study's text, verbatim ("" for binary inputs)
  std::uint64_t seed = 0;   //!< master seed
  std::string surface_file; //!< the surface file a study drew from ("" if inline or none)
  std::string surface_text; //!< that file's text, verbatim
  std::string auxiliary_inputs;  //!< files the surface read (histograms), "<path>\n<text>" each
};

void write_provenance(Hdf5Writer& file, const Provenance& provenance);

//! The root attributes netlist_file, netlist_text and netlist_cards: a study's `[circuit]
//! netlist`, verbatim and as ngspice ran it (nothing when it has none).
void write_netlist_provenance(Hdf5Writer& file, const std::shared_ptr<const NetlistLoad>& netlist);

//! /asperity/{sigma,d0,w,l}: the element parameters.
void write_elements(Hdf5Writer& file, std::span<const StengElement> elements);

//! /circuit/{voltage,charge}, /asperity/current and /asperity/charge (as `traces` asks),
//! plus the load as attributes.
void write_circuit(Hdf5Writer& file, const CircuitResult& circuit, const CircuitParams& params,
                   const OutputTraces& traces = {});

//! Writes a complete run file at `path` (temporary name, renamed when complete).
void write_run_file(const std::string& path, const Study& study, const RunResult& result, const RunSummary& summary);

}  // namespace stengmc
