#include "app/install_layout.hpp"

#include <system_error>

#include "core/error.hpp"
#include "core/executable_path.hpp"

namespace stengmc::app {

std::filesystem::path scripts_dir() {
  // STENGMC_SCRIPTS_RELATIVE_DIR is the path from the install's bin folder to its scripts
  // folder, set by CMake from GNUInstallDirs.
  const std::filesystem::path executable = executable_path();
  const std::filesystem::path dir =
      (executable.parent_path() / STENGMC_SCRIPTS_RELATIVE_DIR).lexically_normal();
  std::error_code error;
  if (!std::filesystem::is_regular_file(dir / "plot_run.py", error))
    throw Error("plotting scripts not found: expected " + (dir / "plot_run.py").string() + " beside " +
                executable.string() + " (" STENGMC_SCRIPTS_RELATIVE_DIR
                " from its folder; install with `cmake --install`, which puts them there)");
  return dir;
}

}  // namespace stengmc::app
