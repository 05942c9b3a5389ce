#pragma once
//! The files a command reads, so its output can be refused when it would replace one.
#include <string>
#include <vector>

#include "io/output_path.hpp"
#include "pipeline/study.hpp"

namespace stengmc::app {

//! The study, the surface file it names and the histogram files that surface reads.
inline std::vector<NamedInput> study_inputs(const Study& study) {
  std::vector<NamedInput> inputs{{study.file, "the study"}, {study.surface_file, "the surface file the study names"}};
  for (const std::string& file : study.surface->auxiliary_input_files())
    inputs.push_back({file, "a histogram file the surface reads"});
  if (study.netlist) inputs.push_back({study.netlist->file, "the load netlist the study names"});
  return inputs;
}

//! Where the output path came from, for messages: the option, or the study's [output] file.
inline std::string output_option(const std::string& command_line_out, const Study& study) {
  return command_line_out.empty() ? study.file + ": [output] file =" : "--out";
}

}  // namespace stengmc::app
