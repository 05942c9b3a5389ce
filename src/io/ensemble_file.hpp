#pragma once
//! The output of an ensemble (docs/ensembles.md, ensemble output), file_type "stengmc-ensemble":
//!   /grid/          sweeps only: parameter (text, one per axis), values (G x axes)
//!   /realisations/  one entry per realisation, by grid point then id: grid_point,
//!                   realisation, valid (0/1), failure (text), every Scalar by name,
//!                   asperity_offset (entries + 1); over the dimension "member"
//!   /asperities/    every AsperityColumn by name, flat over the realisations:
//!                   realisation j's asperities are [asperity_offset[j], asperity_offset[j+1])
//!   /draws/         [[ensemble.draw]] only: parameter (text, one per draw), values
//!                   (realisations x draws, in /realisations order)
//!   /traces/realisation_<r>/{time, voltage, charge}  for [ensemble] trace_realisations
//!                   (or trace_all), and measured_voltage with [noise]
//!                   (in a sweep: /traces/point_<g>/realisation_<r>/...)
//!   /summary/<scalar>/  statistics over the valid realisations, one entry per grid point (over
//!                   a product grid shaped n_1 x ... x n_A, one axis per swept parameter,
//!                   io/ensemble_coordinates.hpp): count, mean, mean_low, mean_high, std, std_low,
//!                   std_high, median, median_low, median_high, p05, p05_low, p05_high,
//!                   p95, p95_low, p95_high, min, max, and <name>_method, <name>_known
//!   /summary/pooled/ fft_ratio, hr_ratio, valid_fraction, each with _low and _high (G each)
//!   /summary/target/ half_width (the final CI half-width of the target's mean; 0 without
//!                   a target or with fewer than 30 valid realisations), met (0/1)
//!   root attributes: provenance (input_text, surface_text, seed, version, git revision),
//!                   title, realisations_requested, realisations_run, valid_realisations,
//!                   stopped_at_target, target_statistic, target_half_width,
//!                   only_realisation (the id run by --only, else -1); merge --partial only:
//!                   partial (1), realisations_expected (grid points x realisations),
//!                   realisations_present
//!   coordinates for xarray (io/ensemble_coordinates.hpp): member, the swept values (a
//!                   product grid's axes, else auxiliary coordinates of grid_point),
//!                   /asperities/asperity_count (CF ragged-array count), index coordinates
//! Nothing in the datasets depends on the number of threads or on interruptions.
#include <string>

#include <vector>

#include "ensemble/sweep.hpp"
#include "pipeline/study.hpp"

namespace stengmc {

//! `base` is the study as written; `grid` its grid points (one without a sweep), run.
void write_ensemble_file(const std::string& path, const StudyFile& base, const std::vector<GridPoint>& grid);

}  // namespace stengmc
