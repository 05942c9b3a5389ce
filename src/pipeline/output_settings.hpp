#pragma once
//! What a run writes and where: the study's [output] table (docs/study-files.md). Kept
//! apart from the physics of a Study: changing it changes no number of a run, only which
//! arrays are kept in memory and written.
#include <string>

#include "core/toml_reader.hpp"

namespace stengmc {

//! Which n x M traces a run file holds (docs/output-files.md); all by default. The
//! voltage, charge, time and per-asperity parameters are always written.
struct OutputTraces {
  bool x = true;         //!< /asperity/x
  bool v = true;         //!< /asperity/v
  bool friction = true;  //!< /asperity/friction
  bool current = true;   //!< /asperity/current
  bool charge = true;    //!< /asperity/charge
  bool x0 = true;        //!< /asperity/x0 (Model 1)
};

struct OutputSettings {
  std::string file;      //!< where `run` writes, unless the command line says otherwise
  OutputTraces traces;   //!< which traces it keeps and writes
};

//! `results/<study file's stem>.h5`: where a study without [output] file writes.
std::string default_output_file(const std::string& study_file);

//! Reads [output] (`file`, `traces`); without the table, the defaults for `study_file`.
OutputSettings read_output_settings(TomlTable* output, const std::string& study_file);

}  // namespace stengmc
