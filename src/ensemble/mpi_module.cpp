#include "ensemble/mpi_module.hpp"

#include <dlfcn.h>

#include <string>

#include "core/error.hpp"
#include "core/executable_path.hpp"

namespace stengmc {

#ifndef STENGMC_MPI_MODULE  // a build without MPI, and the Python module: no MPI module

std::filesystem::path mpi_module_path() { return {}; }

ProcessTransport& load_mpi_module() { throw Error("this stengmc was built without MPI (STENGMC_WITH_MPI=OFF)"); }

#else

std::filesystem::path mpi_module_path() {
  // STENGMC_MPI_MODULE: the module's path from the executable's folder, set by CMake
  // (src/CMakeLists.txt) from GNUInstallDirs; the build tree mirrors it.
  return (executable_path().parent_path() / STENGMC_MPI_MODULE).lexically_normal();
}

ProcessTransport& load_mpi_module() {
  static ProcessTransport* transport = nullptr;
  if (transport != nullptr) return *transport;
  const std::string path = mpi_module_path().string();
  const std::string remedy = "it is built with stengmc (`cmake --build`) and installed beside it by `cmake --install` "
                             "(" STENGMC_MPI_MODULE " from the executable's folder); rebuild or reinstall, or run "
                             "stengmc without an MPI launcher (one process, threads with -j)";
  // RTLD_GLOBAL: MPI's own plugins (OpenMPI's mca_*.so, which libopen-pal opens in
  // MPI_Init) resolve symbols of libmpi and libopen-pal from the global scope in some builds.
  void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (library == nullptr)
    throw Error("an MPI launcher started stengmc, but its MPI module does not load: " + std::string(dlerror()) +
                "; " + remedy);
  const auto open = reinterpret_cast<OpenProcessTransport>(dlsym(library, PROCESS_TRANSPORT_ENTRY));
  if (open == nullptr)
    throw Error("the MPI module " + path + " has no function " + PROCESS_TRANSPORT_ENTRY + "; " + remedy);
  transport = open(PROCESS_TRANSPORT_INTERFACE_VERSION);
  if (transport == nullptr)
    throw Error("the MPI module " + path + " belongs to another build of stengmc (not interface version " +
                std::to_string(PROCESS_TRANSPORT_INTERFACE_VERSION) + "); " + remedy);
  return *transport;
}

#endif

}  // namespace stengmc
