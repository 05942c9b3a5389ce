#include "tribology/imposed_drive.hpp"

#include <cmath>

namespace stengmc {

PhasePoint ImposedDriveMotion::at(double t_s, Side) const {
  const double angle = omega_ * t_s + phase_rad_;
  return {amplitude_m_ * std::sin(angle), amplitude_m_ * omega_ * std::cos(angle)};
}

}  // namespace stengmc
