// The streamed circuit (circuit/element_sums.hpp) against closed forms, its convergence
// order, the quasi-static limit, the exact charge balance, and the motion-node solver
// (circuit_solver.hpp), which evaluates every motion at every Radau node and is itself
// checked against closed forms and ngspice (test_circuit, test_ngspice).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "circuit/element_sums.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "support/analytic_motion.hpp"
#include "support/circuit_cases.hpp"
#include "tribology/model1.hpp"
#include "tribology/sampled_motion.hpp"

namespace stengmc {
namespace {

using testing::SineMotion;
using testing::UniformMotion;
using testing::FourElements;
using testing::uniform_times;

double relative_l2(const std::vector<double>& reference, const std::vector<double>& value, std::size_t first = 0) {
  double difference = 0.0, norm = 0.0;
  for (std::size_t j = first; j < reference.size(); ++j) {
    difference += (reference[j] - value[j]) * (reference[j] - value[j]);
    norm += reference[j] * reference[j];
  }
  return std::sqrt(difference / norm);
}

// ---- V1 (MODEL.md §2; support/circuit_cases.hpp) ----
struct V1 : testing::V1Case {
  V1() { solver = solve_circuit_streamed; }
};

TEST(ElementSumsV1, VoltageAndChargeMatchClosedFormAtFiftyMilliseconds) {
  // As the motion-node solver (test_circuit): 1e-9 relative at t = 0.05 s; x = v t is
  // interpolated exactly, so only Radau's truncation (far below 1e-12) and rounding remain.
  const V1 v1;
  const CircuitResult result = v1.solve(50, 4);
  EXPECT_LE(std::abs(result.voltage_v.back() - v1.voltage(0.05)) / std::abs(v1.voltage(0.05)), 1e-9);
  EXPECT_LE(std::abs(result.charge_c.back() - v1.charge(0.05)) / std::abs(v1.charge(0.05)), 1e-9);
}

TEST(ElementSumsV1, ConvergesAtFifthOrder) {
  // Radau IIA with 3 stages has classical order 5: over one 50 ms interval, 4 -> 8 -> 16
  // steps must divide the error of U (hence V) by ~32 (same range as test_circuit).
  const V1 v1;
  const std::vector<double> orders = testing::v1_observed_orders(v1);
  for (std::size_t k = 0; k < orders.size(); ++k) {
    EXPECT_GT(orders[k], 4.6) << "step halving " << k + 1;
    EXPECT_LT(orders[k], 5.4) << "step halving " << k + 1;
  }
}

// ---- Four Table-2 elements on sinusoidal motions (support/circuit_cases.hpp) ----
TEST(ElementSumsQuasiStatic, VoltageApproachesRTimesSourceCurrentLinearlyInR) {
  // MODEL.md §2: V ~ R sum sigma_i w_i x_i' for R sum C_i short against the motion; the
  // deviation falls tenfold per decade of R and is below 1e-5 at 1 kOhm (as test_circuit).
  // 10 ns samples of 2 MHz sines: the interpolation's own error (~1e-9) is far below.
  const std::vector<double> deviations = testing::quasi_static_deviations(solve_circuit_streamed, 300);
  for (std::size_t k = 1; k < deviations.size(); ++k) EXPECT_NEAR(deviations[k - 1] / deviations[k], 10.0, 1.5) << k;
  EXPECT_LT(deviations.back(), 1e-5);
}

TEST(ElementSumsSines, AgreesWithTheMotionNodeSolver) {
  // Both solve the same equation with Radau IIA at 4 substeps; the streamed one sees the
  // motions through the quintic Hermite of their samples (10 ns, 2 MHz: relative error
  // ~(w dt)^5 / 1e4 ~ 3e-9 in x'), the other evaluates them exactly. So V and Q agree
  // to ~1e-8 (measured below); 1e-7 leaves room for nothing else (a wrong sum or sign
  // is O(1), a wrong Hermite basis ~1e-3).
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(3e-6, 300);
  for (double load_capacitance : {0.0, 5e-17}) {
    const CircuitParams params{1e6, load_capacitance, 4};
    const CircuitResult reference = solve_circuit(four.elements, motions, times, params);
    const CircuitResult streamed = solve_circuit_streamed(four.elements, motions, times, params);
    const double ev = relative_l2(reference.voltage_v, streamed.voltage_v);
    const double eq = relative_l2(reference.charge_c, streamed.charge_c);
    std::printf("C_L = %g: streamed vs motion-node solver: V %.2e, Q %.2e\n", load_capacitance, ev, eq);
    EXPECT_LE(ev, 1e-7);
    EXPECT_LE(eq, 1e-7);
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_LE(relative_l2(reference.current_a[i], streamed.current_a[i]), 1e-7) << i;
      EXPECT_LE(relative_l2(reference.element_charge_c[i], streamed.element_charge_c[i]), 1e-7) << i;
    }
  }
}

TEST(ElementSumsCharge, ElementChargesSumToDeliveredChargeAndIntegrateTheCurrents) {
  // Sum over elements of Q_i(t) - Q_i(t0) = Q + C_L V exactly (charge balance, MODEL.md
  // §2): the solver forms Q from P and U, the element charges from each x and V, so this
  // holds to rounding (1e-12 of the scale). And the written currents, integrated by
  // Simpson's rule from sample 2 (after the R sum C start-up), must give each element's
  // charge change: ~(w dt)^4 / 180 ~ 4e-9 of the scale at 0.5 ns; 1e-7 as test_circuit.
  const FourElements four;
  const auto motions = four.pointers();
  const auto times = uniform_times(2e-6, 4000);
  for (double load_capacitance : {0.0, 5e-17}) {
    const CircuitResult result = solve_circuit_streamed(four.elements, motions, times, {1e6, load_capacitance, 2});
    double worst = 0.0, scale = 0.0;
    for (std::size_t j = 0; j < times.size(); ++j) {
      double sum = 0.0;
      for (std::size_t i = 0; i < 4; ++i) sum += result.element_charge_c[i][j];
      const double delivered = result.charge_c[j] + load_capacitance * result.voltage_v[j];
      worst = std::max(worst, std::abs(sum - delivered));
      scale = std::max(scale, std::abs(delivered));
    }
    EXPECT_LE(worst / scale, 1e-12) << "C_L = " << load_capacitance;
    const double dt = times[1] - times[0];
    for (std::size_t i = 0; i < 4; ++i) {
      double integral = 0.0, charge_scale = 0.0;
      for (std::size_t j = 2; j + 2 < times.size(); j += 2)
        integral += dt / 3 * (result.current_a[i][j] + 4 * result.current_a[i][j + 1] + result.current_a[i][j + 2]);
      for (double q : result.element_charge_c[i]) charge_scale = std::max(charge_scale, std::abs(q));
      const std::size_t end = 2 + 2 * ((times.size() - 3) / 2);
      const double change = result.element_charge_c[i][end] - result.element_charge_c[i][2];
      EXPECT_LE(std::abs(integral - change) / charge_scale, 1e-7) << "element " << i << ", C_L = " << load_capacitance;
    }
  }
}

TEST(ElementSumsKinks, PiecewiseLinearInputAgreesWithTheMotionNodeSolver) {
  // The sines sampled every 3.1 ns (shifted per element) and interpolated linearly: x'
  // steps at ~3900 knots, most inside the 5 ns output intervals, where the streamed solver
  // evaluates those elements exactly and splits its steps at the kinks, as the
  // motion-node solver does. Between kinks x is linear, so both are exact in the motion
  // and differ only by Radau's truncation, of V in one and of U = C V in the other; at 32
  // substeps that is gone (each moves by 1e-5 in V from 2 to 32 substeps, the two agree
  // to 3e-15), so they must agree to rounding (1e-12).
  const testing::PiecewiseLinearFour pwl;
  const FourElements& four = pwl.four;
  const std::vector<const Motion*>& motions = pwl.motions;
  const auto times = uniform_times(3e-6, 600);
  const CircuitParams params{1e6, 0.0, 32};
  const CircuitResult reference = solve_circuit(four.elements, motions, times, params);
  const CircuitResult streamed = solve_circuit_streamed(four.elements, motions, times, params);
  const double ev = relative_l2(reference.voltage_v, streamed.voltage_v);
  const double eq = relative_l2(reference.charge_c, streamed.charge_c);
  std::printf("PWL: streamed vs motion-node solver: V %.2e, Q %.2e\n", ev, eq);
  EXPECT_LE(eq, 1e-12);
}

TEST(ElementSumsKinks, KnotsOnTheSamplesUseBothOneSidedLimits) {
  // A PWL motion whose knots are the output times (what a SPICE source or `circuit
  // --interpolation linear` on its own grid gives): x' jumps at every sample, which the
  // sums carry as left and right limits, with no element evaluated inside an interval.
  // Exact in x, so with the truncation gone the two solvers agree to rounding: 2.4e-12
  // at 32 substeps of these 5 ns intervals, 1.2e-12 at 64 (no longer truncation). 1e-11
  // is far below what a wrong one-sided limit does (V follows x', which jumps by O(1)).
  const FourElements four;
  const auto times = uniform_times(3e-6, 600);
  std::vector<std::unique_ptr<SampledMotion>> sampled;
  std::vector<const Motion*> motions;
  for (std::size_t i = 0; i < 4; ++i) {
    std::vector<double> x;
    for (double t : times) x.push_back(four.motions[i].at(t, Side::right).x_m);
    sampled.push_back(std::make_unique<SampledMotion>(times, x, Interpolation::linear));
    motions.push_back(sampled.back().get());
  }
  const CircuitParams params{1e6, 0.0, 64};
  const CircuitResult reference = solve_circuit(four.elements, motions, times, params);
  const CircuitResult streamed = solve_circuit_streamed(four.elements, motions, times, params);
  EXPECT_LE(relative_l2(reference.voltage_v, streamed.voltage_v), 1e-11);
  EXPECT_LE(relative_l2(reference.charge_c, streamed.charge_c), 1e-11);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LE(relative_l2(reference.current_a[i], streamed.current_a[i]), 1e-11) << i;
}

TEST(ElementSumsKinks, ModelOneStickSlipAgreesWithTheMotionNodeSolver) {
  // Model 1 exact (MODEL.md §1): stick/slip transitions are breakpoints at arbitrary times
  // inside the 10 ns intervals; the slip phases are 2 MHz oscillator arcs. The streamed
  // solver evaluates the kinked intervals exactly and interpolates the rest (1e-8 of x'
  // at most, see above): agreement to 1e-7 in V and Q.
  Model1Params params;
  const TimeGrid grid = TimeGrid::covering(100e-6, 100e6);
  std::vector<Asperity> asperities(2);
  asperities[0].stiffness_n_per_m = 155;
  asperities[1].stiffness_n_per_m = 100;
  asperities[1].drive_phase_rad = 1.0;
  std::vector<Trajectory> trajectories;
  std::vector<const Motion*> motions;
  std::vector<StengElement> elements;
  for (const Asperity& a : asperities) {
    trajectories.push_back(solve_model1(a, params, grid));
    motions.push_back(trajectories.back().motion.get());
    elements.push_back(a.element);
  }
  for (const Motion* m : motions) ASSERT_GT(m->breakpoints().size(), 4u);
  const auto times = grid.times();
  const CircuitResult reference = solve_circuit(elements, motions, times, {});
  const CircuitResult streamed = solve_circuit_streamed(elements, motions, times, {});
  const double ev = relative_l2(reference.voltage_v, streamed.voltage_v);
  const double eq = relative_l2(reference.charge_c, streamed.charge_c);
  std::printf("Model 1: streamed vs motion-node solver: V %.2e, Q %.2e\n", ev, eq);
  EXPECT_LE(ev, 1e-7);
  EXPECT_LE(eq, 1e-7);
}

// ---- Errors ----

TEST(ElementSumsErrors, CapacitanceNotPositiveAndNonFiniteInputsAreModelErrors) {
  const auto times = uniform_times(1e-9, 4);
  {
    const StengElement elements[] = {StengElement{}};
    const UniformMotion motion(20e-6, 1.0);  // x > l = 10 um from the start
    const Motion* motions[] = {&motion};
    try {
      solve_circuit_streamed(elements, motions, times, {1e6, 0.0, 4});
      FAIL() << "expected ModelError";
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find("element capacitance not positive at t = 0 s"), std::string::npos) << e.what();
    }
  }
  {
    StengElement element;
    element.charge_density_c_per_m2 = std::numeric_limits<double>::quiet_NaN();
    const StengElement elements[] = {element};
    const UniformMotion motion(0.0, 1.0);
    const Motion* motions[] = {&motion};
    EXPECT_THROW(solve_circuit_streamed(elements, motions, times, {1e6, 0.0, 4}), ModelError);
  }
  const StengElement elements[] = {StengElement{}};
  const UniformMotion motion(0.0, 1.0);
  const Motion* motions[] = {&motion};
  EXPECT_THROW(solve_circuit_streamed(elements, motions, times, {0.0, 0.0, 4}), InputError);
  EXPECT_THROW(solve_circuit_streamed(elements, motions, times, {1e6, 0.0, 0}), InputError);
}

}  // namespace
}  // namespace stengmc
