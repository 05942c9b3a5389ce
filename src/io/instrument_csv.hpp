#pragma once
//! Records exported by oscilloscopes as delimited text (CSV, TSV, semicolons): a preamble,
//! a header, a units row, then one sample a line (docs/records.md lists the layouts).
#include <string>

#include "io/hdf5_record.hpp"
#include "io/record_format.hpp"
#include "io/signal_input.hpp"

namespace stengmc {

//! How to read a measured record: `--format` and `--column` of `spectrum` and `invert` for a
//! text record; `--dataset` and `--time-dataset` for one in another program's HDF5 file
//! (io/hdf5_record.hpp).
struct RecordReadOptions {
  RecordFormat format = RecordFormat::automatic;  //!< automatic: by the signature of the first lines
  std::string column;                             //!< the voltage column by name; empty: the first channel
  Hdf5RecordLocation hdf5;                        //!< dataset empty: the file is a text record or stengmc's own
};

//! Whether `path` is read as text: no HDF5 dataset was named, and its extension is .csv,
//! .tsv or .txt (any case), or a text format was named.
bool is_record_text(const std::string& path, const RecordReadOptions& options);

//! The times [s] and voltages [V] of a text record, converted from the units the file states.
//! Printed times are put back on the uniform grid they were rounded from.
//! @throws InputError naming the file, the line and the column of what cannot be read, a
//! layout that does not match, and times off a uniform grid.
SignalInput read_record_text(const std::string& path, const RecordReadOptions& options);

}  // namespace stengmc
