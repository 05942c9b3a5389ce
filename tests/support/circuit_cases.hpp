#pragma once
//! Circuit cases with closed forms that both circuit solvers are tested on: test_circuit
//! (the motion-node solver, solve_circuit) and test_element_sums (the streamed one,
//! solve_circuit_streamed). Each test file picks its solver; the cases stay one.
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "core/constants.hpp"
#include "support/analytic_motion.hpp"
#include "tribology/sampled_motion.hpp"

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

//! The four sines sampled every 3.1 ns (element i shifted by 0.7 i ns) and interpolated
//! linearly, as a SPICE PWL source sees them: x' steps at ~3900 knots, most of them inside
//! the output intervals of a 5 ns grid.
struct PiecewiseLinearFour {
  FourElements four;
  std::vector<std::unique_ptr<SampledMotion>> sampled;
  std::vector<const Motion*> motions;

  PiecewiseLinearFour() {
    for (std::size_t i = 0; i < 4; ++i) {
      std::vector<double> t, x;
      for (double time = -0.7e-9 * static_cast<double>(i); time < 3.01e-6 + 3.1e-9; time += 3.1e-9) {
        t.push_back(time);
        x.push_back(four.motions[i].at(time, Side::right).x_m);
      }
      sampled.push_back(std::make_unique<SampledMotion>(t, x, Interpolation::linear));
      motions.push_back(sampled.back().get());
    }
  }
};

//! V1's observed convergence orders at t = 0.05 s, one interval of 4 -> 8 -> 16 steps.
inline std::vector<double> v1_observed_orders(const V1Case& v1) {
  std::vector<double> errors, orders;
  for (std::size_t steps : {4, 8, 16}) errors.push_back(std::abs(v1.solve(1, steps).voltage_v.back() - v1.voltage(0.05)));
  for (std::size_t k = 1; k < errors.size(); ++k) orders.push_back(std::log2(errors[k - 1] / errors[k]));
  return orders;
}

//! The four elements' relative L2 deviation from the quasi-static limit for R = 1e6, 1e5,
//! 1e4, 1e3 Ohm over 3 us (`intervals` samples; the start-up transient, the first tenth, skipped).
inline std::vector<double> quasi_static_deviations(CircuitSolverFunction solver, std::size_t intervals) {
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(3e-6, intervals);
  std::vector<double> deviations;
  for (double r : {1e6, 1e5, 1e4, 1e3}) {
    const CircuitResult result = solver(four.elements, motions, times, CircuitParams{r, 0.0, 4}, nullptr);
    double num = 0.0, den = 0.0;
    for (std::size_t j = times.size() / 10; j < times.size(); ++j) {
      const double expected = four.quasi_static_voltage(r, times[j]);
      num += std::pow(result.voltage_v[j] - expected, 2);
      den += expected * expected;
    }
    deviations.push_back(std::sqrt(num / den));
  }
  return deviations;
}

}  // namespace stengmc::testing
