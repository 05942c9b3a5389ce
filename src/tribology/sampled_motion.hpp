#pragma once
//! Motion through displacement samples: what the circuit sees when x(t) comes from a
//! file (FEM, measurements, another run), MODEL.md §2.
#include <string_view>
#include <vector>

#include "model/motion.hpp"

namespace stengmc {

//! How x(t) is continued between samples.
enum class Interpolation {
  spline,  //!< cubic spline, not-a-knot: x' continuous (default)
  linear,  //!< piecewise linear, what a SPICE PWL source sees: x' steps at every sample
};

//! Parses "spline" | "linear"; throws InputError naming `where` otherwise.
Interpolation parse_interpolation(std::string_view text, std::string_view where);

//! Name written to files.
std::string_view interpolation_name(Interpolation interpolation);

class SampledMotion final : public Motion {
 public:
  //! @param times_s        strictly increasing sample times [s] (at least 2; 4 for a spline)
  //! @param displacement_m x at those times [m]
  SampledMotion(std::vector<double> times_s, std::vector<double> displacement_m, Interpolation interpolation);

  [[nodiscard]] PhasePoint at(double t_s, Side side = Side::right) const override;
  [[nodiscard]] const std::vector<double>& breakpoints() const override { return breakpoints_; }

 private:
  std::vector<double> t_;
  std::vector<double> x_;
  std::vector<double> slope_;  // dx/dt at each sample (spline), unused for linear
  Interpolation interpolation_;
  std::vector<double> breakpoints_;
};

}  // namespace stengmc
