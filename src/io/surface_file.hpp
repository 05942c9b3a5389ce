#pragma once
//! The output of `stengmc surface` (docs/output-files.md), file_type "stengmc-surface":
//!   /realisations, /summits, /asperities   the populations (layout: io/population_file.hpp)
//!   /target/heights/{value, density}       the height law (attribute discrete = 0/1; for a
//!   /target/stiffness/{value, density}     discrete law `density` holds probabilities);
//!                                          stiffness only under rule "sampled"
//!   /load_separation/{separation_m, total_load_n}  the first realisation's Hertz curve
//!       (interacting mode: of the summits lowered by the solved interaction)
//!       (attributes realisation, solved_separation_m, nominal_load_n); load rule "hertz"
//!   root attributes: provenance (io/run_file.hpp), first_realisation, realisation_count,
//!       the validity thresholds.
#include <string>

#include "io/run_file.hpp"
#include "pipeline/surface_examination.hpp"

namespace stengmc {

void write_surface_file(const std::string& path, const Provenance& provenance, const SurfaceExamination& examination);

}  // namespace stengmc
