#pragma once

namespace stengmc {

//! Program version (from CMake's project version).
const char* program_version();

//! Git revision of the source tree at build time ("-dirty" when it had changes).
const char* git_revision();

}  // namespace stengmc
