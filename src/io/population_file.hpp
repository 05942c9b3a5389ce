#pragma once
//! Sampled populations and their validity reports in an HDF5 file (docs/output-files.md).
//! One layout for `stengmc surface` (group "/") and for a run's own realisation (group
//! "/surface"), so every tool reads both the same way. K realisations are stored as flat
//! arrays with offsets, realisation j's summits being [summit_offset[j], summit_offset[j+1]),
//! and as CF contiguous ragged arrays (the counts below).
//!
//!   G/realisations/  one entry per realisation:
//!     realisation, summit_count, asperity_count, cannot_slip_model1_count,
//!     near_length_model2_count, warnings (text, "; "-separated, "" when none);
//!     summit_offset, asperity_offset (K + 1 entries);
//!     with material data also: separation_m, total_load_n, real_area_m2, contact_density,
//!     screening_estimate, load_redistribution (fraction of the load the
//!     interaction moves between spots; SpotInteraction::load_redistribution),
//!     interaction_rms_relative, interaction_max_relative, overlapping_pairs,
//!     independence_holds (0/1), interacting_iterations, interacting_converged (0/1),
//!     load_carried (0/1: 0 when a Hertz load found no summit), localisation_radius_m,
//!     far_field_m (the uniform displacement of the nominal pressure outside R_loc);
//!     attribute `kernel` ("hertz_pressure" or "point_load")
//!     summit_count and asperity_count are CF ragged-array counts (sample_dimension
//!     "summit", "asperity": their index coordinates G/summit and G/asperity)
//!   G/summits/       every sampled summit: height_m, x_m, y_m, drive_phase_rad, normal_load_n,
//!     sampled_stiffness_n_per_m (stiffness rule "sampled"); with material data also
//!     interference_m, patch_radius_m, extra_displacement_m, interaction_relative
//!   G/asperities/    every summit in contact: summit_index (within its realisation; -1 for
//!     a fixed list, which has no summits),
//!     stiffness_n_per_m, mass_kg, normal_load_n, height_m, element_length_m,
//!     element_width_m, drive_phase_rad, cannot_slip_model1 (0/1),
//!     static_deflection_over_length, near_length_model2 (0/1) (0 for a model outside the
//!     report's ModelScope)
#include <span>
#include <string>

#include "core/hdf5_file.hpp"
#include "surface/population.hpp"
#include "pipeline/validity.hpp"

namespace stengmc {

//! Writes `populations` (and their `reports`, same length and order) under `group`.
//! `surface` decides which optional datasets exist (sampled stiffnesses, contact data),
//! so the layout depends on the surface, not on what a realisation happened to draw;
//! nullptr for a fixed list.
void write_populations(Hdf5Writer& file, const std::string& group, const RandomSurface* surface,
                       std::span<const Population> populations, std::span<const ValidityReport> reports);

//! The warnings of a report, joined with "; " (contact ones first, then Model 1, Model 2).
std::string joined_warnings(const ValidityReport& report);

}  // namespace stengmc
