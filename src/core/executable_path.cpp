#include "core/executable_path.hpp"

#include <system_error>

#include "core/error.hpp"

namespace stengmc {

std::filesystem::path executable_path() {
  std::error_code error;
  std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw Error("cannot locate the stengmc executable (/proc/self/exe: " + error.message() + ")");
  return executable;
}

}  // namespace stengmc
