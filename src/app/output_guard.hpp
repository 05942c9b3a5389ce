#pragma once
//! Commands that read one file and write another refuse to overwrite what they read.
#include <filesystem>
#include <string>

#include "core/error.hpp"

namespace stengmc::app {

inline void refuse_overwriting_input(const std::string& input, const std::string& out) {
  std::error_code ignored;  // a missing output is fine: then they differ
  if (std::filesystem::equivalent(input, out, ignored))
    throw InputError("--out " + out + " is the input file; choose another output name");
}

}  // namespace stengmc::app
