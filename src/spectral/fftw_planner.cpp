#include "spectral/fftw_planner.hpp"

namespace stengmc {

// Never destroyed: the per-thread analyzers (thread_spectrum_analyzer) release their plans
// when their thread ends, which for OpenMP's workers can be after static destructors ran.
std::mutex& fftw_planner_mutex() {
  static std::mutex* const mutex = new std::mutex;
  return *mutex;
}

}  // namespace stengmc
