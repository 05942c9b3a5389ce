#include "spectral/fftw_planner.hpp"

namespace stengmc {

std::mutex& fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace stengmc
