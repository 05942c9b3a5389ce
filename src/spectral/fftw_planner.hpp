#pragma once
//! FFTW's planner keeps global state: creating or destroying plans from two threads at once
//! is undefined (FFTW manual §5.4, "Thread safety"); fftw_execute on distinct plans is safe.
//! Every plan creation and destruction in the program goes through this one lock.
#include <mutex>

namespace stengmc {

std::mutex& fftw_planner_mutex();

}  // namespace stengmc
