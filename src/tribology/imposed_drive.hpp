#pragma once
//! Model 1's imposed displacement x0(t) = A sin(omega t + phi) as a Motion, so the
//! circuit can be driven by it instead of x(t) (the paper's Fig. 3c).
#include <memory>

#include "tribology/model1.hpp"
#include "model/motion.hpp"

namespace stengmc {

class ImposedDriveMotion final : public Motion {
 public:
  ImposedDriveMotion(double amplitude_m, double angular_frequency_rad_per_s, double phase_rad)
      : amplitude_m_(amplitude_m), omega_(angular_frequency_rad_per_s), phase_rad_(phase_rad) {}
  ImposedDriveMotion(const Model1Params& params, const Asperity& asperity)
      : ImposedDriveMotion(params.drive_amplitude_m, params.drive_angular_frequency_rad_per_s, asperity.drive_phase_rad) {}

  [[nodiscard]] PhasePoint at(double t_s, Side) const override;
  [[nodiscard]] const std::vector<double>& breakpoints() const override { return none_; }

 private:
  double amplitude_m_;
  double omega_;
  double phase_rad_;
  std::vector<double> none_;
};

}  // namespace stengmc
