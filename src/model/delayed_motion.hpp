#pragma once
//! An asperity that comes into contact at its onset (`onset_s`, docs/model.md §1.3): at rest
//! at its initial displacement before, carried by nothing, then the motion a solver computed
//! from that state, shifted to start at the onset.
#include <memory>
#include <vector>

#include "model/motion.hpp"

namespace stengmc {

class DelayedMotion final : public Motion {
 public:
  //! `from_onset` starts at t = 0 from `at_rest` (x'= 0); this motion is `at_rest` until
  //! `onset_s` > 0 and from_onset(t - onset_s) after.
  DelayedMotion(std::unique_ptr<Motion> from_onset, double onset_s, double rest_displacement_m);

  [[nodiscard]] PhasePoint at(double t_s, Side side = Side::right) const override;
  //! The onset (where x'' jumps: friction takes hold) and the inner motion's, shifted.
  [[nodiscard]] const std::vector<double>& breakpoints() const override { return breakpoints_; }
  [[nodiscard]] std::vector<double> fine_structure(double resolution_s) const override;
  [[nodiscard]] double displacement_bound() const override;
  //! The rest state and the inner motion's excerpt over the same times from the onset;
  //! nullptr when the inner motion has none.
  [[nodiscard]] std::unique_ptr<Motion> excerpt(double t0_s, double t1_s) const override;
  //! Before the onset the rest state; from it on, the inner motion's own sampling on the
  //! shifted times (a uniform grid stays uniform).
  void sample(std::span<const double> times_s, bool midpoints, MotionSamples& out) const override;

  [[nodiscard]] double onset_s() const { return onset_s_; }

 private:
  std::unique_ptr<Motion> from_onset_;
  double onset_s_;
  double rest_displacement_m_;
  std::vector<double> breakpoints_;
};

}  // namespace stengmc
