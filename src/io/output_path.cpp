#include "io/output_path.hpp"

#include <filesystem>
#include <system_error>

#include "core/error.hpp"
#include "core/input_file.hpp"

namespace stengmc {


void check_output_path(const std::string& out, const std::vector<NamedInput>& inputs, const std::string& option) {
  if (out.empty()) throw InputError(option + " is empty: give the path of the HDF5 file to write");
  std::error_code error;
  const auto status = std::filesystem::status(out, error);  // follows links
  if (!error && status.type() != std::filesystem::file_type::not_found &&
      status.type() != std::filesystem::file_type::regular)
    throw InputError(option + " " + out + " exists and is " + describe_file_type(status.type()) +
                     ": stengmc writes its output to a regular file only; choose another output name");
  for (const NamedInput& input : inputs) {
    if (input.path.empty()) continue;
    std::error_code ignored;  // a missing output is fine: then they differ
    if (std::filesystem::equivalent(input.path, out, ignored))
      throw InputError(option + " " + out + " is the input file " + input.path + " (" + input.role +
                       "): writing there would destroy it; choose another output name");
  }
}

}  // namespace stengmc
