#pragma once
//! The coordinates of an ensemble file, so that xarray can select in it (issue 25):
//! - a sweep whose grid is a product (every combination of the swept values once, the first
//!   parameter varying slowest: what [[ensemble.sweep]] makes unless a value repeats) has one
//!   dimension per swept parameter, named after it (dots as underscores,
//!   "surface_summits_count"), with that parameter's values as its coordinate: /summary's
//!   datasets are shaped (first parameter, second, ...), so
//!   `.sel(surface_summits_count=8, noise_snr_db=20)` picks a point and each parameter is
//!   an axis to plot against. /grid holds each parameter's coordinate too, and /grid/values
//!   stays one row per grid point (over the lone parameter's dimension, else "grid_point");
//! - a grid that is not a product (a repeated value) keeps the dimension "grid_point"
//!   (coordinate: its index) and each parameter is an auxiliary coordinate over it (CF
//!   `coordinates`; `.set_index(grid_point=[...])` makes them selectable);
//! - /realisations, /draws and /asperities' counts are over "member", one row per
//!   realisation of every grid point, numbered 0.. without repeats; the realisation id
//!   (repeated at every grid point), the grid point and its swept values are auxiliary
//!   coordinates of it (a table of rows, not a grid: a partial or stopped run has unequal
//!   counts per point);
//! - /asperities is a CF contiguous ragged array (CF 1.10, 9.3.3): asperity_count over
//!   "member", with sample_dimension = "asperity", and an index coordinate for "asperity";
//! - every other dimension of these groups gets an index coordinate.
//! Only datasets are added, dimensions named and /summary reshaped: the values and their
//! order (grid point after grid point) are those of the flat layout.
#include <string>
#include <vector>

#include "core/hdf5_file.hpp"
#include "ensemble/sweep.hpp"

namespace stengmc {

//! The names of an ensemble file's axes.
struct EnsembleAxes {
  std::vector<std::string> parameters;  //!< the swept study keys ("surface.summits.count")
  std::vector<std::string> variables;   //!< their variable names ("surface_summits_count")
  //! With a sweep whose grid is a product: each parameter's values, in the grid's order
  //! (empty otherwise).
  std::vector<std::vector<double>> values;
  //! /grid's grid-point dimension: variables[0] for a product of one parameter, else "grid_point".
  std::string grid_dimension;
  //! /summary's dimensions: the variables of a product grid, else {grid_dimension}.
  std::vector<std::string> summary_dimensions;
  [[nodiscard]] bool product() const { return !values.empty(); }
};

//! The axes of `grid`, the grid points of `settings`' sweep (one point without one).
EnsembleAxes ensemble_axes(const EnsembleSettings& settings, const std::vector<GridPoint>& grid);

//! describe_output with the ensemble's dimension names, and the coordinates written below.
Hdf5Writer::Describer describe_ensemble_output(const EnsembleAxes& axes);

//! The grid's coordinates in `group` (/grid or a /summary group): a product grid's axes
//! (each parameter's values), else each parameter per grid point and the `coordinates`
//! attribute naming them on `variables` (those written in the group); the index grid_point
//! where the group is over it.
void write_grid_coordinates(Hdf5Writer& f, const std::string& group, const EnsembleAxes& axes,
                            const std::vector<GridPoint>& grid, const std::vector<std::string>& variables);

//! /realisations/member, /draws/member (with draws) and /asperities' ragged-array count and
//! index; the realisation id, grid point and swept values as auxiliary coordinates of
//! /realisations.
void write_member_coordinates(Hdf5Writer& f, const EnsembleAxes& axes, const std::vector<GridPoint>& grid,
                              const std::vector<std::string>& realisation_variables, bool draws);

}  // namespace stengmc
