#pragma once
#include <cstddef>
#include <memory>
#include <vector>

#include "tribology/events.hpp"
#include "model/motion.hpp"

namespace stengmc {

//! One asperity's solved motion: dense output for the circuit, and samples on the
//! output grid for files and spectra.
struct Trajectory {
  std::unique_ptr<Motion> motion;      //!< continuous x(t), x'(t)
  std::vector<double> x_m;             //!< displacement on the output grid [m]
  std::vector<double> v_m_per_s;       //!< velocity on the output grid [m/s]
  std::vector<double> friction_n;      //!< friction force on the asperity on the output grid [N]
  std::vector<Event> events;           //!< stick/slip (Model 1) or overtake (Model 2) events
  std::size_t solver_steps = 0;        //!< integrator steps or closed-form phases taken
  std::size_t rejected_steps = 0;      //!< steps the error control rejected (Model 2)
};

}  // namespace stengmc
