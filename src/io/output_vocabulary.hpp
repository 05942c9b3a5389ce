#pragma once
//! The vocabulary of stengmc's output files: for every dataset a writer makes, its CF
//! `units`, its `long_name` and the names of its axes (docs/output-files.md). Writers
//! pass describe_output to Hdf5Writer, which writes the attributes and, at commit, the
//! dimension scales that let netCDF readers (xarray) label the arrays.
#include <string>

#include "core/hdf5_dimensions.hpp"

namespace stengmc {

//! The description of the dataset at `path` in any stengmc output file; throws Error for
//! a path the vocabulary does not know (a writer's dataset missing from the table).
DatasetDescription describe_output(const std::string& path);

}  // namespace stengmc
