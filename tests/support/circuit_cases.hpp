#pragma once
//! Circuit cases with closed forms that both circuit solvers are tested on: test_circuit
//! (the motion-node solver, solve_circuit) and test_element_sums (the streamed one,
//! solve_circuit_streamed). Each test file picks its solver; the cases stay one.
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "core/constants.hpp"
#include "support/analytic_motion.hpp"

namespace stengmc::testing {

//! Either solver's signature.
using CircuitSolverFunction = CircuitResult (*)(std::span<const StengElement>, std::span<const Motion* const>,
                                                std::span<const double>, const CircuitParams&, Progress*);

inline std::vector<double> uniform_times(double end_s, std::size_t intervals) {
  std::vector<double> t(intervals + 1);
  for (std::size_t j = 0; j <= intervals; ++j) t[j] = end_s * static_cast<double>(j) / static_cast<double>(intervals);
  return t;
}

//! V1 (MODEL.md §2; Niu et al. Table 1; the paper's appendix validation): one element
//! dragged at constant speed into R, with Q(t) and V(t) in closed form.
struct V1Case {
  StengElement element{100e-6, 31.25e-6, 0.05, 0.08};
  double v = 1.0;
  double r = 1e9;
  CircuitSolverFunction solver = nullptr;  //!< set by the test file

  double a() const { return element.effective_thickness_m / (r * EPSILON_0 * element.width_m * v); }
  double charge(double t) const {
    const double l = element.length_m, u = l - v * t, s = a();
    return element.charge_density_c_per_m2 * element.width_m * (l + s * u / (1 - s) - l * std::pow(u / l, s) / (1 - s));
  }
  double voltage(double t) const {  // V = R dQ/dt, differentiated by hand
    const double l = element.length_m, u = l - v * t, s = a();
    return r * element.charge_density_c_per_m2 * element.width_m * s * v / (1 - s) * (std::pow(u / l, s - 1) - 1);
  }
  CircuitResult solve(std::size_t intervals, std::size_t substeps) const {
    UniformMotion motion(0.0, v);
    const Motion* motions[] = {&motion};
    const StengElement elements[] = {element};
    const auto times = uniform_times(0.05, intervals);
    return solver(std::span<const StengElement>(elements), std::span<const Motion* const>(motions), times,
                  CircuitParams{r, 0.0, substeps}, nullptr);
  }
};

//! Four Table-2 elements on sinusoidal motions at the paper's line frequencies.
struct FourElements {
  std::vector<StengElement> elements = std::vector<StengElement>(4);
  std::vector<SineMotion> motions{{2e-6, 3e-6, 2 * PI * 0.796e6}, {2e-6, 3e-6, 2 * PI * 1.125e6, 0.3},
                                  {2e-6, 3e-6, 2 * PI * 1.592e6, 1.1}, {2e-6, 3e-6, 2 * PI * 1.981e6, 2.0}};
  std::vector<const Motion*> pointers() const { return {&motions[0], &motions[1], &motions[2], &motions[3]}; }
  //! MODEL.md §2's quasi-static limit V = R sum sigma_i w_i x_i'.
  double quasi_static_voltage(double r, double t) const {
    double source = 0.0;
    for (std::size_t i = 0; i < 4; ++i)
      source += elements[i].charge_density_c_per_m2 * elements[i].width_m * motions[i].at(t, Side::right).v_m_per_s;
    return r * source;
  }
};

}  // namespace stengmc::testing
