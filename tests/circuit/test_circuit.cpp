// The circuit solver against closed forms, its convergence order, the quasi-static
// limit and charge conservation (MODEL.md §2).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "core/constants.hpp"
#include "support/analytic_motion.hpp"

namespace stengmc {
namespace {

using testing::SineMotion;
using testing::UniformMotion;

std::vector<double> uniform_times(double end_s, std::size_t intervals) {
  std::vector<double> t(intervals + 1);
  for (std::size_t j = 0; j <= intervals; ++j) t[j] = end_s * static_cast<double>(j) / static_cast<double>(intervals);
  return t;
}

// ---- V1 (MODEL.md §2; Niu et al. Table 1; the paper's appendix validation) ----
struct V1 {
  StengElement element{100e-6, 31.25e-6, 0.05, 0.08};
  double v = 1.0;
  double r = 1e9;
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
    CircuitParams params{r, 0.0, substeps};
    const auto times = uniform_times(0.05, intervals);
    return solve_circuit(elements, motions, times, params);
  }
};

TEST(CircuitV1, VoltageAndChargeMatchClosedFormAtFiftyMilliseconds) {
  // The issue asks for 1e-9 relative at t = 0.05 s (LTspice reached 1e-6). Radau IIA is
  // order 5; with 200 steps of 0.25 ms on a 1.1 s time constant its truncation error is
  // far below 1e-12, so what remains is rounding.
  const V1 v1;
  const CircuitResult result = v1.solve(50, 4);
  const double v_exact = v1.voltage(0.05);
  const double q_exact = v1.charge(0.05);
  EXPECT_LE(std::abs(result.voltage_v.back() - v_exact) / std::abs(v_exact), 1e-9);
  EXPECT_LE(std::abs(result.charge_c.back() - q_exact) / std::abs(q_exact), 1e-9);
}

TEST(CircuitV1, ConvergesAtFifthOrder) {
  // Radau IIA with 3 stages has classical order 2s-1 = 5 (Hairer & Wanner II, Thm IV.5.3).
  // V1's coefficients are smooth, so halving the step divides the error by ~32. 4, 8 and
  // 16 steps over 50 ms (time constant 1.1 s) are in the asymptotic range (relative errors
  // ~9e-7 .. 9e-10, far above rounding); 1 -> 2 steps is not yet (observed 4.2).
  const V1 v1;
  std::vector<double> errors;
  for (std::size_t steps : {4, 8, 16}) {
    const CircuitResult result = v1.solve(1, steps);
    errors.push_back(std::abs(result.voltage_v.back() - v1.voltage(0.05)));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    EXPECT_GT(order, 4.6) << "step halving " << k;
    EXPECT_LT(order, 5.4) << "step halving " << k;
  }
}

// ---- Four Table-2 elements on sinusoidal motions ----
struct FourElements {
  std::vector<StengElement> elements = std::vector<StengElement>(4);
  std::vector<SineMotion> motions{{2e-6, 3e-6, 2 * PI * 0.796e6}, {2e-6, 3e-6, 2 * PI * 1.125e6, 0.3},
                                  {2e-6, 3e-6, 2 * PI * 1.592e6, 1.1}, {2e-6, 3e-6, 2 * PI * 1.981e6, 2.0}};
  std::vector<const Motion*> pointers() const { return {&motions[0], &motions[1], &motions[2], &motions[3]}; }
  double quasi_static_voltage(double r, double t) const {
    double source = 0.0;
    for (std::size_t i = 0; i < 4; ++i)
      source += elements[i].charge_density_c_per_m2 * elements[i].width_m * motions[i].at(t, Side::right).v_m_per_s;
    return r * source;
  }
};

TEST(CircuitQuasiStatic, VoltageApproachesRTimesSourceCurrentLinearlyInR) {
  // MODEL.md §2: for R sum C_i much shorter than the motion, V ~ R sum sigma_i w_i x_i'
  // (the paper's finding). The leading correction is of order R sum C_i times the motion's
  // frequency, so the relative deviation must fall tenfold per decade of R, and at
  // R = 1 kOhm (R sum C ~ 7e-14 s, omega R C ~ 1e-6) be below 1e-5.
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(3e-6, 600);
  std::vector<double> deviations;
  for (double r : {1e6, 1e5, 1e4, 1e3}) {
    const CircuitResult result = solve_circuit(four.elements, motions, times, {r, 0.0, 4});
    // Skip the start-up transient (a few R sum C).
    double num = 0.0, den = 0.0;
    for (std::size_t j = times.size() / 10; j < times.size(); ++j) {
      const double expected = four.quasi_static_voltage(r, times[j]);
      num += std::pow(result.voltage_v[j] - expected, 2);
      den += expected * expected;
    }
    deviations.push_back(std::sqrt(num / den));
  }
  for (std::size_t k = 1; k < deviations.size(); ++k) {
    EXPECT_NEAR(deviations[k - 1] / deviations[k], 10.0, 1.5) << "decade " << k;
  }
  EXPECT_LT(deviations.back(), 1e-5);
}

double element_charge_sum(const FourElements& four, double t, double voltage) {
  double sum = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const StengElement& e = four.elements[i];
    const double x = four.motions[i].at(t, Side::right).x_m;
    const double capacitance = EPSILON_0 * e.width_m * (e.length_m - x) / e.effective_thickness_m;
    sum += e.charge_density_c_per_m2 * e.width_m * x - capacitance * voltage;
  }
  return sum;
}

TEST(CircuitConservation, ElementChargesEqualDeliveredChargeWithAndWithoutLoadCapacitor) {
  // Sum_i integral(i_i dt) = sum_i [Q_i(t) - Q_i(0)], Q_i = sigma w x - C_i V (MODEL.md §2),
  // must equal the charge through R plus the charge on C_L. The solver computes Q from
  // V/R by quadrature and never forms Q_i, so agreement to 1e-9 tests both.
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(3e-6, 600);
  for (double load_capacitance : {0.0, 5e-17}) {
    const CircuitResult result = solve_circuit(four.elements, motions, times, {1e6, load_capacitance, 4});
    const double initial = element_charge_sum(four, 0.0, 0.0);
    double worst = 0.0;
    for (std::size_t j = 1; j < times.size(); ++j) {
      const double elements = element_charge_sum(four, times[j], result.voltage_v[j]) - initial;
      const double delivered = result.charge_c[j] + load_capacitance * result.voltage_v[j];
      worst = std::max(worst, std::abs(elements - delivered));
    }
    double scale = 0.0;
    for (double q : result.charge_c) scale = std::max(scale, std::abs(q));
    EXPECT_LE(worst / scale, 1e-9) << "C_L = " << load_capacitance;
  }
}

TEST(CircuitConservation, IntegratedElementCurrentsEqualDeliveredCharge) {
  // The written currents i_i, integrated by Simpson's rule on the output grid, must give
  // the delivered charge. The start-up transient (R sum C ~ 7e-11 s) is shorter than a
  // sample step, so the integral starts at sample 2, after it. Simpson's error is
  // ~ (omega dt)^4 / 180 ~ 4e-9 of the charge scale here (omega dt = 2 pi 2 MHz x 0.5 ns);
  // 1e-7 of max |Q| leaves room for that and nothing else.
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(2e-6, 4000);
  const CircuitResult result = solve_circuit(four.elements, motions, times, {1e6, 0.0, 2});
  double integral = 0.0;
  const double dt = times[1] - times[0];
  const std::size_t start = 2;
  for (std::size_t j = start; j + 2 < times.size(); j += 2)
    for (std::size_t i = 0; i < 4; ++i)
      integral += dt / 3 * (result.current_a[i][j] + 4 * result.current_a[i][j + 1] + result.current_a[i][j + 2]);
  double scale = 0.0;
  for (double q : result.charge_c) scale = std::max(scale, std::abs(q));
  const double delivered = result.charge_c.back() - result.charge_c[start];
  EXPECT_LE(std::abs(integral - delivered) / scale, 1e-7);
}

TEST(CircuitInput, RejectsNonPositiveLoadAndUnorderedTimes) {
  const FourElements four;
  const auto motions = four.pointers();
  EXPECT_THROW(solve_circuit(four.elements, motions, uniform_times(1e-6, 10), {0.0, 0.0, 4}), std::exception);
  const std::vector<double> backwards{0.0, 2e-9, 1e-9};
  EXPECT_THROW(solve_circuit(four.elements, motions, backwards, {1e6, 0.0, 4}), std::exception);
}

}  // namespace
}  // namespace stengmc
