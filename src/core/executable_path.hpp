#pragma once
//! The running executable's own file, so that what it ships beside itself (plotting
//! scripts, the MPI module) is found relative to it in the build tree and in a moved install.
#include <filesystem>

namespace stengmc {

//! The executable of this process, whatever argv[0] or the PATH said (/proc/self/exe:
//! Linux, the platform the project targets). Throws Error when the system cannot say.
[[nodiscard]] std::filesystem::path executable_path();

}  // namespace stengmc
