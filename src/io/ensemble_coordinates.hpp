#pragma once
//! The coordinates of an ensemble file, so that xarray can select in it (issue 25):
//! - a sweep's parameters label the grid points: with one swept parameter its name (dots
//!   as underscores, "surface_summits_count") is the dimension of /grid and /summary and
//!   its values that dimension's coordinate (`.sel(surface_summits_count=8)`); with
//!   several, the dimension stays "grid_point" (coordinate: its index) and each parameter
//!   is an auxiliary coordinate over it (CF `coordinates`; `.set_index(grid_point=[...])`
//!   then `.unstack()` gives one dimension per parameter, the grid being their product);
//! - /realisations, /draws and /asperities' counts are over "member", one row per
//!   realisation of every grid point, numbered 0.. without repeats; the realisation id
//!   (repeated at every grid point), the grid point and its swept values are auxiliary
//!   coordinates of it;
//! - /asperities is a CF contiguous ragged array (CF 1.10, 9.3.3): asperity_count over
//!   "member", with sample_dimension = "asperity", and an index coordinate for "asperity";
//! - every other dimension of these groups gets an index coordinate.
//! Only datasets are added and dimensions named: no dataset a reader knows changes.
#include <string>
#include <vector>

#include "core/hdf5_file.hpp"
#include "ensemble/sweep.hpp"

namespace stengmc {

//! The names of an ensemble file's axes.
struct EnsembleAxes {
  std::vector<std::string> parameters;  //!< the swept study keys ("surface.summits.count")
  std::vector<std::string> variables;   //!< their variable names ("surface_summits_count")
  std::string grid_dimension;           //!< the grid points' dimension: variables[0] alone, else "grid_point"
};

EnsembleAxes ensemble_axes(const EnsembleSettings& settings);

//! describe_output with the ensemble's dimension names, and the coordinates written below.
Hdf5Writer::Describer describe_ensemble_output(const EnsembleAxes& axes);

//! The grid's coordinates in `group` (/grid or a /summary group), and the `coordinates`
//! attribute its variables need with several swept parameters (`variables`: those written).
void write_grid_coordinates(Hdf5Writer& f, const std::string& group, const EnsembleAxes& axes,
                            const std::vector<GridPoint>& grid, const std::vector<std::string>& variables);

//! /realisations/member, /draws/member (with draws) and /asperities' ragged-array count and
//! index; the realisation id, grid point and swept values as auxiliary coordinates of
//! /realisations.
void write_member_coordinates(Hdf5Writer& f, const EnsembleAxes& axes, const std::vector<GridPoint>& grid,
                              const std::vector<std::string>& realisation_variables, bool draws);

}  // namespace stengmc
