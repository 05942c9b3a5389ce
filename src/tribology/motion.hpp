#pragma once
#include <vector>

namespace stengmc {

//! Displacement and velocity of an asperity at one instant.
struct PhasePoint {
  double x_m = 0.0;          //!< displacement [m]
  double v_m_per_s = 0.0;    //!< velocity [m/s]
};

//! Which one-sided limit to take where the velocity jumps (piecewise-linear input).
enum class Side { left, right };

//! Continuous-time motion x(t), x'(t) of one asperity: the dense output of a tribology
//! solver or an interpolant through samples. The circuit solver evaluates it between
//! output samples, so its own accuracy is what the circuit sees (MODEL.md §2).
class Motion {
 public:
  virtual ~Motion() = default;

  //! State at time t [s]; `side` selects the one-sided limit where x' jumps.
  [[nodiscard]] virtual PhasePoint at(double t_s, Side side = Side::right) const = 0;

  //! Sorted times [s] where x' or x'' is not smooth (stick/slip transitions, sample
  //! knots of a linear interpolant). The circuit solver never steps across one.
  [[nodiscard]] virtual const std::vector<double>& breakpoints() const = 0;
};

}  // namespace stengmc
