#pragma once
//! The unit of work of an ensemble: realisation r of a study, run end to end (surface ->
//! tribology -> circuit -> noise -> spectra) and reduced to its record. It depends on the
//! study and r alone, so any thread, process or machine can compute it.
#include <cstdint>
#include <string_view>

#include "ensemble/realisation_record.hpp"
#include "ensemble/study_file.hpp"
#include "pipeline/work_estimate.hpp"

namespace stengmc {

//! @param base the study read without drawing a realisation (read_study(file, nullopt))
//! @param keep_traces also keep the time, voltage and charge traces (and the noisy voltage
//!        with [noise])
//! With [[ensemble.draw]], the realisation's drawn values are set first (docs/ensembles.md)
//! and kept as the record's extras "draw:<parameter>".
//! A realisation whose model breaks (ModelError: x reaching l under `error`, an integrator
//! failure, nothing in contact, a line above Nyquist) or whose run is flagged invalid
//! (x reaching l under `flag`) gives an invalid record saying why. InputErrors propagate:
//! they are the study's, and would fail every realisation alike. A realisation whose work
//! estimate, with the asperities it drew, exceeds `limits` is an invalid record whose
//! failure starts with WORK_LIMIT_FAILURE (a resumed run with other limits runs it again).
RealisationRecord run_realisation(const StudyFile& base, std::uint64_t realisation, bool keep_traces,
                                  const WorkLimits& limits = {});

//! How the failure of a realisation refused by the work limits begins.
inline constexpr std::string_view WORK_LIMIT_FAILURE = "work limit: ";

}  // namespace stengmc
