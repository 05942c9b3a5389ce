#pragma once
//! --format and --column, how `spectrum` and `invert` read a record given as text
//! (io/instrument_csv.hpp), and --dataset / --time-dataset, one in another program's HDF5
//! file (io/hdf5_record.hpp; docs/records.md).
#include <CLI/CLI.hpp>

#include "io/instrument_csv.hpp"

namespace stengmc::app {

struct RecordOptions {
  std::string format = "auto";
  std::string column;
  std::string dataset, time_dataset;

  //! The reader's options; CLI11 has checked the name.
  [[nodiscard]] RecordReadOptions read() const {
    return {record_format_named(format).value_or(RecordFormat::automatic), column, {dataset, time_dataset}};
  }
};

inline void add_record_options(CLI::App* command, RecordOptions& options) {
  CLI::Option* format =
      command->add_option("--format", options.format,
                   "Layout of a text record: auto (by its first lines), plain (`t,V`), tektronix, keysight, rigol, lecroy, "
                   "picoscope")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "plain", "tektronix", "keysight", "rigol", "lecroy", "picoscope"}));
  CLI::Option* column = command->add_option(
      "--column", options.column, "The voltage column of a text record, by its name in the header (default: the first channel)");
  CLI::Option* dataset =
      command->add_option("--dataset", options.dataset,
                          "The record is this dataset of another program's HDF5 file (\"/scope/ch1\"): 1-D, in its "
                          "`units` (V when absent), timed by --time-dataset, its dimension scale (a netCDF coordinate) "
                          "or its attributes sample_interval_s / sample_rate_hz (docs/records.md)");
  command
      ->add_option("--time-dataset", options.time_dataset,
                   "With --dataset: the dataset of its times, in its `units` (s when absent)")
      ->needs(dataset);
  dataset->excludes(column)->excludes(format);
}

}  // namespace stengmc::app
