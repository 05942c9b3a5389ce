#pragma once
// Motions with closed forms, for tests that need x(t) and x'(t) exactly.
#include <cmath>
#include <vector>

#include "model/motion.hpp"

namespace stengmc::testing {

//! x = x_0 + v t.
class UniformMotion final : public Motion {
 public:
  UniformMotion(double x0_m, double v_m_per_s) : x0_(x0_m), v_(v_m_per_s) {}
  PhasePoint at(double t, Side) const override { return {x0_ + v_ * t, v_}; }
  const std::vector<double>& breakpoints() const override { return none_; }

 private:
  double x0_, v_;
  std::vector<double> none_;
};

//! x = offset + amplitude sin(omega t + phase).
class SineMotion final : public Motion {
 public:
  SineMotion(double offset_m, double amplitude_m, double omega_rad_per_s, double phase_rad = 0.0)
      : offset_(offset_m), amplitude_(amplitude_m), omega_(omega_rad_per_s), phase_(phase_rad) {}
  PhasePoint at(double t, Side) const override {
    return {offset_ + amplitude_ * std::sin(omega_ * t + phase_), amplitude_ * omega_ * std::cos(omega_ * t + phase_)};
  }
  const std::vector<double>& breakpoints() const override { return none_; }

 private:
  double offset_, amplitude_, omega_, phase_;
  std::vector<double> none_;
};

}  // namespace stengmc::testing
