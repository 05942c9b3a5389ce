#pragma once
//! The records `stengmc invert` reads (docs/inverse.md): a CSV `t,V` or an oscilloscope's
//! text export (io/instrument_csv.hpp); a dataset of another program's HDF5 file
//! (io/hdf5_record.hpp); a stengmc
//! run (or circuit) file, its /circuit/measured_voltage when it has one, else
//! /circuit/voltage; or a stengmc ensemble file, every kept trace (measured_voltage when
//! the study had [noise]) as one record, skipping invalid realisations (their traces stop
//! where the model left the device's range).
#include <string>
#include <vector>

#include "io/instrument_csv.hpp"

namespace stengmc {

struct NamedRecord {
  std::string name;               //!< "path" or "path#realisation_<r>" (ensembles; "#point_<g>/..." in sweeps)
  std::vector<double> times_s;
  std::vector<double> voltage_v;
};

//! @param text how to read a text record (`--format`, `--column`), or the dataset of a record
//! in another program's HDF5 file (`--dataset`: one record, named "path#dataset").
//! @param notes when given, receives what the user should know of the reading (invalid
//! realisations skipped).
//! @throws InputError for an unreadable file, one without a voltage, or an ensemble without traces.
std::vector<NamedRecord> read_inverse_records(const std::string& path, const RecordReadOptions& text = {},
                                              std::vector<std::string>* notes = nullptr);

}  // namespace stengmc
