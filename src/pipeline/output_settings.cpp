#include "pipeline/output_settings.hpp"

#include <algorithm>
#include <filesystem>

namespace stengmc {

std::string default_output_file(const std::string& study_file) {
  return (std::filesystem::path("results") / std::filesystem::path(study_file).stem()).string() + ".h5";
}

OutputSettings read_output_settings(TomlTable* output, const std::string& study_file) {
  OutputSettings settings{default_output_file(study_file), {}};
  if (!output) return settings;
  settings.file = output->string("file", settings.file);
  if (settings.file.empty()) output->fail("file", "is empty: give the path of the HDF5 file to write, or leave the key out");
  if (output->has("traces")) {
    const auto names = output->string_list("traces", {"x", "v", "friction", "current", "charge", "x0"});
    auto wanted = [&](std::string_view name) { return std::find(names.begin(), names.end(), name) != names.end(); };
    settings.traces = {wanted("x"), wanted("v"), wanted("friction"), wanted("current"), wanted("charge"), wanted("x0")};
  }
  return settings;
}

}  // namespace stengmc
