#pragma once
//! Finds and opens the MPI module (libstengmc_mpi.so, ensemble/mpi_transport.cpp) when an
//! MPI launcher started stengmc. It sits at the same path relative to the executable in the
//! build tree as in an install (<prefix>/lib/stengmc beside <prefix>/bin, by GNUInstallDirs),
//! so a moved install keeps finding it.
#include <filesystem>

#include "ensemble/process_transport.hpp"

namespace stengmc {

//! Where the module is looked for: beside this executable, at the path CMake compiled in.
[[nodiscard]] std::filesystem::path mpi_module_path();

//! Opens the module (once; it stays loaded) and returns its transport, not started yet.
//! @throws Error naming the path tried, the loader's reason and what to do, when the module
//!         is missing, does not load, or comes from another build; or when this build has
//!         no MPI (STENGMC_WITH_MPI off)
ProcessTransport& load_mpi_module();

}  // namespace stengmc
