// The circuit solver against closed forms, its convergence order, the quasi-static
// limit and charge conservation (MODEL.md §2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "support/analytic_motion.hpp"
#include "support/circuit_cases.hpp"
#include "tribology/sampled_motion.hpp"

namespace stengmc {
namespace {

using testing::SineMotion;
using testing::UniformMotion;
using testing::FourElements;
using testing::uniform_times;

// ---- V1 (MODEL.md §2; support/circuit_cases.hpp) ----
struct V1 : testing::V1Case {
  V1() { solver = solve_circuit; }
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
  const std::vector<double> orders = testing::v1_observed_orders(v1);
  for (std::size_t k = 0; k < orders.size(); ++k) {
    EXPECT_GT(orders[k], 4.6) << "step halving " << k + 1;
    EXPECT_LT(orders[k], 5.4) << "step halving " << k + 1;
  }
}

// ---- Four Table-2 elements on sinusoidal motions (support/circuit_cases.hpp) ----
TEST(CircuitQuasiStatic, VoltageApproachesRTimesSourceCurrentLinearlyInR) {
  // MODEL.md §2: for R sum C_i much shorter than the motion, V ~ R sum sigma_i w_i x_i'
  // (the paper's finding). The leading correction is of order R sum C_i times the motion's
  // frequency, so the relative deviation must fall tenfold per decade of R, and at
  // R = 1 kOhm (R sum C ~ 7e-14 s, omega R C ~ 1e-6) be below 1e-5.
  const std::vector<double> deviations = testing::quasi_static_deviations(solve_circuit, 600);
  for (std::size_t k = 1; k < deviations.size(); ++k) {
    EXPECT_NEAR(deviations[k - 1] / deviations[k], 10.0, 1.5) << "decade " << k;
  }
  EXPECT_LT(deviations.back(), 1e-5);
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

// ---- Per-element delivered charge ----

//! Q_i = sigma_i w_i x_i - C_i V, the element's charge state (MODEL.md §2).
double element_charge_state(const StengElement& e, const Motion& motion, double t, double voltage) {
  const double x = motion.at(t, Side::right).x_m;  // x is continuous: either side
  const double capacitance = EPSILON_0 * e.width_m * (e.length_m - x) / e.effective_thickness_m;
  return e.charge_density_c_per_m2 * e.width_m * x - capacitance * voltage;
}

struct ElementChargeErrors {
  double per_element = 0.0;  // max_i max_j |integral i_i - delta Q_i| / max_j |integral i_i|
  double sum = 0.0;          // max_j |sum_i integral i_i - (Q + C_L V)| / max_j |Q + C_L V|
};

ElementChargeErrors element_charge_errors(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                                          std::span<const double> times, const CircuitResult& result,
                                          double load_capacitance) {
  ElementChargeErrors errors;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const double initial = element_charge_state(elements[i], *motions[i], times[0], result.voltage_v[0]);
    double worst = 0.0, scale = 0.0;
    for (std::size_t j = 0; j < times.size(); ++j) {
      const double state = element_charge_state(elements[i], *motions[i], times[j], result.voltage_v[j]) - initial;
      worst = std::max(worst, std::abs(result.element_charge_c[i][j] - state));
      scale = std::max(scale, std::abs(result.element_charge_c[i][j]));
    }
    errors.per_element = std::max(errors.per_element, worst / scale);
  }
  double worst = 0.0, scale = 0.0;
  for (std::size_t j = 0; j < times.size(); ++j) {
    double sum = 0.0;
    for (std::size_t i = 0; i < elements.size(); ++i) sum += result.element_charge_c[i][j];
    const double delivered = result.charge_c[j] + load_capacitance * result.voltage_v[j];
    worst = std::max(worst, std::abs(sum - delivered));
    scale = std::max(scale, std::abs(delivered));
  }
  errors.sum = worst / scale;
  return errors;
}

TEST(CircuitElementCharge, MatchesElementStateAndSumsToDeliveredChargeOnSines) {
  // The solver integrates i_i = sigma w x' + (eps0 w x'/d0) V - C_i dV/dt with the Radau
  // stage quadrature; it never forms Q_i = sigma w x - C_i V, so comparing with the change
  // of Q_i tests the currents, the quadrature and the bookkeeping together.
  // Per element: Radau IIA is collocation, so the V-terms integrate -(C_i u)' with u the
  // cubic collocation polynomial, and the stage quadrature is exact to degree 4. On smooth
  // steps the error is O(h^6) (~1e-16 of the scale per step at omega h = 2 pi 2 MHz x
  // 1.25 ns = 0.016). The first step dominates: V jumps from 0 to ~R sum sigma w x' within
  // R sum C ~ 7e-11 s << h, u carries that jump, and the curvature of C_i across the step
  // leaves a one-time error of reduced order (observed, constant after the first sample and
  // falling ~10x per halving of h: 6e-11 at h = 5 ns, 6e-12 at 2.5 ns, 6e-13 at 1.25 ns,
  // 6e-14 at 0.625 ns). 1e-9 therefore holds with room, even at one substep.
  // Sum over elements: V' at the stages is alpha_j V_j + beta_j, so the sum of the element
  // increments is h b.V/R + C_L (V_end - V_n) exactly; only rounding remains (~1e-15).
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(3e-6, 600);
  for (double load_capacitance : {0.0, 5e-17}) {
    const CircuitResult result = solve_circuit(four.elements, motions, times, {1e6, load_capacitance, 4});
    ASSERT_EQ(result.element_charge_c.size(), 4u);
    const ElementChargeErrors errors = element_charge_errors(four.elements, motions, times, result, load_capacitance);
    EXPECT_LE(errors.per_element, 1e-9) << "C_L = " << load_capacitance;
    EXPECT_LE(errors.sum, 1e-9) << "C_L = " << load_capacitance;
  }
}

TEST(CircuitElementCharge, MatchesElementStateAndSumsToDeliveredChargeOnPiecewiseLinearInput) {
  // The sines sampled every 3.1 ns (shifted per element) and interpolated linearly, as a
  // SPICE PWL source sees them: x' steps at every sample, ~3900 breakpoints, most inside
  // the 5 ns output intervals, each restarting a stiff transient in V. Between breakpoints
  // x and C_i are linear in t, so (C_i u)' with u the cubic collocation polynomial is of
  // degree 3, which the quadrature (exact to degree 4) integrates exactly, transients or
  // not, and sigma w x' is constant: per element too only rounding remains (observed ~1e-14).
  const testing::PiecewiseLinearFour pwl;
  const FourElements& four = pwl.four;
  const std::vector<const Motion*>& motions = pwl.motions;
  const auto times = uniform_times(3e-6, 600);
  for (double load_capacitance : {0.0, 5e-17}) {
    const CircuitResult result = solve_circuit(four.elements, motions, times, {1e6, load_capacitance, 2});
    const ElementChargeErrors errors = element_charge_errors(four.elements, motions, times, result, load_capacitance);
    EXPECT_LE(errors.per_element, 1e-9) << "C_L = " << load_capacitance;
    EXPECT_LE(errors.sum, 1e-9) << "C_L = " << load_capacitance;
  }
}

// ---- Step nodes ----

//! Passes through to a motion and records the times of every left-limit evaluation.
class RecordingMotion final : public Motion {
 public:
  explicit RecordingMotion(const Motion& inner) : inner_(inner) {}
  PhasePoint at(double t, Side side) const override {
    if (side == Side::left) left_times_.push_back(t);
    return inner_.at(t, side);
  }
  const std::vector<double>& breakpoints() const override { return inner_.breakpoints(); }
  const std::vector<double>& left_times() const { return left_times_; }

 private:
  const Motion& inner_;
  mutable std::vector<double> left_times_;
};

TEST(CircuitSteps, LastNodeIsExactlyEachBreakpointAndOutputTime) {
  // The last Radau node is the step's end passed as is, not t + 1.0 h: on this grid, which
  // crosses zero, -0.45 ns + (0.0171 ns - -0.45 ns) rounds off the breakpoint 0.0171 ns (the
  // guard below checks that the grid really has such a pair), and a left limit taken one
  // ulp past a PWL knot returns the next segment's slope. So every piece end (breakpoint or
  // output time) must be evaluated from the left bit for bit, and there must be exactly one
  // left evaluation per step.
  const std::vector<double> times{-2.1e-9, -0.45e-9, 0.37e-9, 1.9e-9, 4.3e-9, 9.7e-9};
  const SampledMotion inner({-3e-9, -1.234e-9, 0.0171e-9, 0.9e-9, 3.3e-9, 7.77e-9, 11e-9},
                            {0.0, 1e-7, -2e-7, 3e-7, 0.0, 1e-7, 2e-7}, Interpolation::linear);
  std::vector<double> piece_ends(times.begin() + 1, times.end());
  for (double b : inner.breakpoints())
    if (b > times.front() && b < times.back()) piece_ends.push_back(b);
  std::sort(piece_ends.begin(), piece_ends.end());
  std::size_t rounding_pairs = 0;
  for (std::size_t k = 1; k < piece_ends.size(); ++k)
    if (piece_ends[k - 1] + 1.0 * (piece_ends[k] - piece_ends[k - 1]) != piece_ends[k]) ++rounding_pairs;
  ASSERT_GT(rounding_pairs, 0u) << "the grid no longer exercises the rounding";
  const StengElement elements[] = {StengElement{}};
  for (std::size_t substeps : {1, 3}) {
    const RecordingMotion recording(inner);
    const Motion* motions[] = {&recording};
    solve_circuit(elements, motions, times, {1e6, 0.0, substeps});
    std::vector<double> left = recording.left_times();
    EXPECT_EQ(left.size(), piece_ends.size() * substeps) << "substeps = " << substeps;
    std::sort(left.begin(), left.end());
    for (double t : piece_ends)
      EXPECT_TRUE(std::binary_search(left.begin(), left.end(), t))
          << "no left limit at piece end t = " << t << " s, substeps = " << substeps;
  }
}

// ---- Errors and progress ----

std::string model_error_message(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                                std::span<const double> times, const CircuitParams& params) {
  try {
    solve_circuit(elements, motions, times, params);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "no ModelError";
}

//! x = 0 up to `valid_until`, NaN after it (a displacement file with a hole).
class HoleMotion final : public Motion {
 public:
  explicit HoleMotion(double valid_until_s) : valid_until_(valid_until_s) {}
  PhasePoint at(double t, Side) const override {
    return t <= valid_until_ ? PhasePoint{} : PhasePoint{std::numeric_limits<double>::quiet_NaN(), 0.0};
  }
  const std::vector<double>& breakpoints() const override { return none_; }

 private:
  double valid_until_;
  std::vector<double> none_;
};

TEST(CircuitErrors, NonFiniteResultsAreModelErrorsNamingTimeAndInputs) {
  const auto times = uniform_times(1e-9, 4);
  {
    // V(t0) = 0, so a NaN sigma shows first in the element current at the initial time.
    StengElement element;
    element.charge_density_c_per_m2 = std::numeric_limits<double>::quiet_NaN();
    const StengElement elements[] = {element};
    const UniformMotion motion(0.0, 1.0);
    const Motion* motions[] = {&motion};
    const std::string message = model_error_message(elements, motions, times, {1e6, 0.0, 4});
    EXPECT_NE(message.find("non-finite current or charge of element 1 at t = 0 s"), std::string::npos) << message;
    EXPECT_NE(message.find("check the load resistance, load capacitance, sigma, d0"), std::string::npos) << message;
  }
  {
    // NaN x after 0.5 ns: the capacitance check lets NaN through (it is not "x >= l"), and
    // the first output time that sees it is 0.75 ns.
    const StengElement elements[] = {StengElement{}};
    const HoleMotion motion(0.5e-9);
    const Motion* motions[] = {&motion};
    const std::string message = model_error_message(elements, motions, times, {1e6, 0.0, 4});
    EXPECT_NE(message.find("non-finite voltage at t = 7.5e-10 s"), std::string::npos) << message;
  }
}

TEST(CircuitErrors, CapacitanceNotPositiveIsAModelErrorNotADivisionByZero) {
  // x = 20 um + ... passes l = 10 um at once: sum C_i < 0 at the first node.
  const StengElement elements[] = {StengElement{}};
  const UniformMotion motion(20e-6, 1.0);
  const Motion* motions[] = {&motion};
  const std::string message = model_error_message(elements, motions, uniform_times(1e-9, 4), {1e6, 0.0, 4});
  EXPECT_NE(message.find("element capacitance not positive at t = 0 s"), std::string::npos) << message;
  EXPECT_NE(message.find("x reached l"), std::string::npos) << message;
}

TEST(CircuitProgress, ReportingProgressChangesNothing) {
  // 1001 samples: three full batches and a remainder. The bar is silent for its first
  // second, so this prints nothing.
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(1e-6, 1000);
  const CircuitResult plain = solve_circuit(four.elements, motions, times, {1e6, 0.0, 2});
  Progress progress("circuit", times.size());
  const CircuitResult reported = solve_circuit(four.elements, motions, times, {1e6, 0.0, 2}, &progress);
  EXPECT_EQ(plain.voltage_v, reported.voltage_v);
  EXPECT_EQ(plain.element_charge_c, reported.element_charge_c);
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
