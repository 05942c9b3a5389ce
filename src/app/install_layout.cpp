#include "app/install_layout.hpp"

#include <system_error>

#include "core/error.hpp"

namespace stengmc::app {

std::filesystem::path scripts_dir() {
  // /proc/self/exe is the executable itself, whatever argv[0] or the PATH said (Linux,
  // the platform the project targets). STENGMC_SCRIPTS_RELATIVE_DIR is the path from the
  // install's bin folder to its scripts folder, set by CMake from GNUInstallDirs.
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw Error("cannot locate the stengmc executable (/proc/self/exe: " + error.message() + ")");
  const std::filesystem::path dir =
      (executable.parent_path() / STENGMC_SCRIPTS_RELATIVE_DIR).lexically_normal();
  if (!std::filesystem::is_regular_file(dir / "plot_run.py", error))
    throw Error("plotting scripts not found: expected " + (dir / "plot_run.py").string() + " beside " +
                executable.string() + " (" STENGMC_SCRIPTS_RELATIVE_DIR
                " from its folder; install with `cmake --install`, which puts them there)");
  return dir;
}

}  // namespace stengmc::app
