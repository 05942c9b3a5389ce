#pragma once
// Text files of tests/support/ shared by several tests (and by the Python checks in io/).
#include <string>

#include "core/input_file.hpp"

namespace stengmc::testing {

//! A file of tests/support/ (found through the source folder the build compiles in).
inline std::string support_file_text(const std::string& name) {
  return read_text_file(std::string(STENGMC_SOURCE_DIR) + "/tests/support/" + name, "the test support file");
}

}  // namespace stengmc::testing
