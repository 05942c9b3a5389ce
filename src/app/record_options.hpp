#pragma once
//! --format and --column, how `spectrum` and `invert` read a record given as text
//! (io/instrument_csv.hpp; docs/records.md).
#include <CLI/CLI.hpp>

#include "io/instrument_csv.hpp"

namespace stengmc::app {

struct RecordOptions {
  std::string format = "auto";
  std::string column;

  //! The reader's options; CLI11 has checked the name.
  [[nodiscard]] RecordReadOptions read() const { return {record_format_named(format).value_or(RecordFormat::automatic), column}; }
};

inline void add_record_options(CLI::App* command, RecordOptions& options) {
  command
      ->add_option("--format", options.format,
                   "Layout of a text record: auto (by its first lines), plain (`t,V`), tektronix, keysight, rigol, lecroy, "
                   "picoscope")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "plain", "tektronix", "keysight", "rigol", "lecroy", "picoscope"}));
  command->add_option("--column", options.column,
                      "The voltage column of a text record, by its name in the header (default: the first channel)");
}

}  // namespace stengmc::app
