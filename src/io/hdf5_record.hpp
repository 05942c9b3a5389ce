#pragma once
//! A measured record stored in another program's HDF5 file (an oscilloscope's, a lab
//! pipeline's, xarray's `to_netcdf`): one named dataset of voltages, its times from a time
//! dataset, the dimension scale attached to it, or sampling attributes (docs/records.md).
#include <string>

#include "io/signal_input.hpp"

namespace stengmc {

//! Where a record lies in an HDF5 file: `--dataset` and `--time-dataset`.
struct Hdf5RecordLocation {
  std::string dataset;       //!< the voltages: a 1-D numeric dataset ("/scope/ch1")
  std::string time_dataset;  //!< its times [s or the unit it states]; empty: found as below
};

//! The record at `where` in `path`. Voltages are converted from the dataset's `units`
//! attribute (V when absent). Times come from, in order: `where.time_dataset`; the dimension
//! scale attached to the dataset's axis (a netCDF coordinate; "<unit> since <epoch>" units read
//! as <unit>); the dataset's attributes `sample_interval_s` or `sample_rate_hz`, with
//! `start_time_s` (default 0). Times must be uniform (within 1e-6 of a step, and a float32's
//! rounding) and are then replaced by their grid.
//! @throws InputError naming the file, the dataset or attribute, and what was expected; a
//! damaged file is read by a child process first (io/guarded_read.hpp).
SignalInput read_hdf5_record(const std::string& path, const Hdf5RecordLocation& where);

}  // namespace stengmc
