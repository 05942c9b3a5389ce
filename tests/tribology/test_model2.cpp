// Model 2 (mass on a moving belt, MODEL.md §1): accuracy of the default tolerance, closed
// forms, the two friction forms, dense output, natural frequencies and failure reporting.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "core/error.hpp"
#include "core/processor_features.hpp"
#include "tribology/friction_law.hpp"
#include "tribology/model2.hpp"

namespace stengmc {
namespace {

// The paper's Fig. 6 set-up: 50 us at 100 MHz, Table 1/2 values.
TimeGrid fig6_grid() { return TimeGrid::covering(50e-6, 100e6); }

Asperity table1_asperity(double k) {
  Asperity a;
  a.stiffness_n_per_m = k;
  return a;
}

Model2Params table1_params(double belt_velocity, std::string_view form = "consistent") {
  Model2Params p;
  p.belt_velocity_m_per_s = belt_velocity;
  p.friction_law = find_friction_law(form);
  return p;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) m = std::max(m, std::abs(a[j] - b[j]));
  return m;
}

bool has_event(const Trajectory& t, EventKind kind) {
  return std::any_of(t.events.begin(), t.events.end(), [kind](const Event& e) { return e.kind == kind; });
}

constexpr double K_VALUES[] = {25.0, 50.0, 100.0, 155.0};
constexpr double BELT_VELOCITIES[] = {1.0, 10.0};

// The guarantee documented on Model2Params::relative_tolerance: on the output grid the
// default tolerance's displacement differs from a 100x tighter solution by at most 1e-6 of
// max|x|, for all 8 Table-1 cases (k x v_b), in both friction forms. The tighter run stands
// in for the exact solution: its own error is ~100x smaller (the global error is close to
// proportional to the tolerance, measured: 3e-7 at 1e-8, 3e-9 at 1e-10). The bound is the
// documented one itself, not a loosened copy; measured worst case ~3.1e-7 with RODAS4 alone,
// 4.3e-8 with the sliding propagator (k = 155, v_b = 1, literal form).
TEST(Model2, DefaultToleranceMeetsDocumentedDisplacementAccuracy) {
  const TimeGrid grid = fig6_grid();
  for (const std::string_view form : {"consistent", "literal"}) {
    for (const double vb : BELT_VELOCITIES) {
      for (const double k : K_VALUES) {
        const Model2Params params = table1_params(vb, form);
        Model2Params tight = params;
        tight.relative_tolerance = params.relative_tolerance / 100.0;
        const Trajectory run = solve_model2(table1_asperity(k), params, grid);
        const Trajectory ref = solve_model2(table1_asperity(k), tight, grid);
        const double scale = max_abs(ref.x_m);
        ASSERT_GT(scale, 0.0);
        EXPECT_LE(max_abs_diff(run.x_m, ref.x_m), 1e-6 * scale)
            << "k = " << k << ", v_b = " << vb << ", form " << form;
        EXPECT_GT(run.solver_steps, 0u);
      }
    }
  }
}

// An independent method: Boost.Odeint's explicit Dormand-Prince 5(4) (the paper's ODE45
// family) with dense output at tolerance 1e-13, on the same equation written out here from
// MODEL.md §1 (only model2_friction is shared). It brute-forces the stiff sticking phase
// (2.3e6 right-hand sides for k = 25, v_b = 1; ~0.15 s), so its error is that of a
// different method at a 1e5x tighter tolerance (~1e-11 of max|x|). The default tolerance
// must meet its documented 1e-6 of max|x| against it (measured: 6e-8 .. 3.1e-7 with RODAS4
// alone, 9.2e-9 .. 3.3e-8 with the sliding propagator). Cases:
// the stiffest (k = 25, v_b = 1) and the fastest (k = 155, v_b = 10), both forms.
TEST(Model2, AgreesWithIndependentExplicitReference) {
  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 2>;
  const TimeGrid grid = fig6_grid();
  for (const std::string_view form : {"consistent", "literal"}) {
    for (const auto& [k, vb] : {std::pair{25.0, 1.0}, std::pair{155.0, 10.0}}) {
      const Asperity a = table1_asperity(k);
      const Model2Params params = table1_params(vb, form);
      // x in um and t in us keep both components O(1..10) for one absolute tolerance.
      auto rhs = [&](const State& y, State& dy, double /*t_us*/) {
        const double v = y[1];  // um/us = m/s
        const double f = model2_friction(params, a.normal_load_n, vb - v);
        dy[0] = v;
        dy[1] = (f - params.damping_n_s_per_m * v - k * y[0] * 1e-6) / a.mass_kg * 1e-6;  // um/us^2
      };
      std::vector<double> times_us(grid.count);
      for (std::size_t j = 0; j < grid.count; ++j) times_us[j] = grid.at(j) * 1e6;
      std::vector<double> ref_x;
      State y{0.0, 0.0};
      odeint::integrate_times(odeint::make_dense_output(1e-13, 1e-13, odeint::runge_kutta_dopri5<State>()), rhs,
                              y, times_us.begin(), times_us.end(), 1e-6,
                              [&](const State& s, double) { ref_x.push_back(s[0] * 1e-6); });
      ASSERT_EQ(ref_x.size(), grid.count);
      const Trajectory run = solve_model2(a, params, grid);
      EXPECT_LE(max_abs_diff(run.x_m, ref_x), 1e-6 * max_abs(ref_x))
          << "k = " << k << ", v_b = " << vb << ", form " << form;
    }
  }
}

// Closed form: with N = 0 there is no friction and the asperity is a free damped oscillator
//   x(t) = exp(-zeta w0 t) [x0 cos(wd t) + (v0 + zeta w0 x0) / wd sin(wd t)].
// At relative_tolerance = 1e-10 the global error is ~30x the tolerance (see above), so
// 1e-8 of the amplitude holds with a small margin and fails for any error in the
// damping, the stiffness or the dense output beyond that level.
TEST(Model2, NoFrictionIsFreeDampedOscillator) {
  Asperity a = table1_asperity(100.0);
  a.normal_load_n = 0.0;
  a.initial_displacement_m = 1e-6;
  a.initial_velocity_m_per_s = 3.0;
  Model2Params params = table1_params(1.0);
  params.relative_tolerance = 1e-10;
  const TimeGrid grid = fig6_grid();
  const Trajectory t = solve_model2(a, params, grid);

  const double w0 = std::sqrt(a.stiffness_n_per_m / a.mass_kg);
  const double zeta = params.damping_n_s_per_m / (2.0 * std::sqrt(a.stiffness_n_per_m * a.mass_kg));
  const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
  const double x0 = a.initial_displacement_m;
  const double b = (a.initial_velocity_m_per_s + zeta * w0 * x0) / wd;
  double max_x = 0.0, max_v = 0.0, err_x = 0.0, err_v = 0.0;
  for (std::size_t j = 0; j < grid.count; ++j) {
    const double tj = grid.at(j);
    const double e = std::exp(-zeta * w0 * tj);
    const double x = e * (x0 * std::cos(wd * tj) + b * std::sin(wd * tj));
    const double v = -zeta * w0 * x + e * wd * (-x0 * std::sin(wd * tj) + b * std::cos(wd * tj));
    max_x = std::max(max_x, std::abs(x));
    max_v = std::max(max_v, std::abs(v));
    err_x = std::max(err_x, std::abs(t.x_m[j] - x));
    err_v = std::max(err_v, std::abs(t.v_m_per_s[j] - v));
    // No friction at all: the force output must be exactly zero.
    ASSERT_EQ(t.friction_n[j], 0.0);
  }
  EXPECT_LE(err_x, 1e-8 * max_x);
  EXPECT_LE(err_v, 1e-8 * max_v);
}

// Closed form: started at the steady-sliding equilibrium x = F(v_b)/k, x' = 0, the
// right-hand side vanishes and the asperity must stay there. Only rounding in the
// nondimensionalisation and the Rosenbrock stages moves it: 1e-12 relative is ~1e4 ulp.
TEST(Model2, SteadySlidingEquilibriumStaysPut) {
  for (const double vb : BELT_VELOCITIES) {
    const Model2Params params = table1_params(vb);
    Asperity a = table1_asperity(50.0);
    const double force = model2_friction(params, a.normal_load_n, vb);
    a.initial_displacement_m = force / a.stiffness_n_per_m;
    const Trajectory t = solve_model2(a, params, fig6_grid());
    for (std::size_t j = 0; j < t.x_m.size(); ++j) {
      ASSERT_NEAR(t.x_m[j], a.initial_displacement_m, 1e-12 * a.initial_displacement_m) << "j = " << j;
      ASSERT_NEAR(t.v_m_per_s[j], 0.0, 1e-12 * vb);
      ASSERT_NEAR(t.friction_n[j], force, 1e-12 * force);
    }
    EXPECT_TRUE(t.events.empty());
  }
}

// Friction law spot values against MODEL.md §1 written out by hand.
TEST(Model2, FrictionFormsMatchModelDefinition) {
  const double n = 1e-3;
  for (const double vr : {-3.0, -1e-3, 0.0, 2e-4, 1.0, 10.0}) {
    const Model2Params p = table1_params(1.0);
    const double stribeck = 0.22 + 0.06 * std::exp(-1e-7 * std::abs(vr));
    const double sgn = (2.0 / 3.14159265358979323846) * std::atan(1e3 * vr);
    EXPECT_NEAR(model2_friction(p, n, vr), n * stribeck * sgn, 1e-15 * n);
    const Model2Params q = table1_params(1.0, "literal");
    EXPECT_NEAR(model2_friction(q, n, vr), n * (0.22 + (stribeck - 0.22) * sgn), 1e-15 * n);
  }
}

// Every law's batched forces() (the sliding propagator evaluates its collocation nodes
// through it) must give exactly force() one by one: the integrator's results may not depend
// on which of the two it calls. Bitwise, for a batch that mixes relative velocities on both
// sides of the fast atan series' threshold (|s v_r| = 64) and of the Stribeck polynomial's
// (c_s |v_r| = 1e-3), taken force by force, and for batches all inside both (sliding), taken
// by the branch-free series in SIMD (SSE2 pairs, and AVX2 quadruples where the processor
// has them: both versions run here): odd and even lengths, so that the vector loop's
// tail is exercised too. A law whose batch pointed at another formula, or dropped, shifted
// or reordered an element, fails here.
TEST(Model2, BatchedFrictionEqualsOneByOne) {
  FrictionParameters p;
  p.normal_load_n = 1e-3;
  p.kinetic_coefficient = 0.22;
  p.static_coefficient = 0.28;
  p.stribeck_decay_s_per_m = 1e-4;  // puts the polynomial's threshold at |v_r| = 10 m/s
  p.atan_sharpness_s_per_m = 1e3;   // and the series' at |v_r| = 0.064 m/s
  const std::vector<std::vector<double>> batches{
      {-2e4, -3.0, -0.0641, -0.0639, -1e-3, 0.0, 2e-4, 0.0639, 0.0641, 1.0, 10.0, 9.9, 11.0, 2e5},
      {-9.99, -3.0, -0.0641, 0.0641, 0.5, 1.0, 9.99},
      {0.07, -0.3, 2.5, -7.0, 0.9, 1.7}};
  for (const bool baseline : {false, true}) {
    use_baseline_instructions_only(baseline);
    for (const FrictionLaw& law : friction_laws()) {
      for (const std::vector<double>& v_r : batches) {
        std::vector<double> batch(v_r.size(), std::numeric_limits<double>::quiet_NaN());
        law.forces(p, v_r.data(), batch.data(), v_r.size());
        for (std::size_t i = 0; i < v_r.size(); ++i)
          EXPECT_EQ(batch[i], law.force(p, v_r[i])) << law.name << ", v_r = " << v_r[i] << ", baseline " << baseline;
        // In place (solve_model2 writes F over v_r).
        std::vector<double> in_place = v_r;
        law.forces(p, in_place.data(), in_place.data(), in_place.size());
        EXPECT_EQ(in_place, batch) << law.name;
      }
    }
  }
  use_baseline_instructions_only(false);
}

// The two friction forms coincide where v_r > 0 up to the term N mu_k (1 - (2/pi) atan(s v_r)),
// which at the Table-2 s = 1e3 s/m is still ~1e-3 of F at v_r ~ 0.5 m/s. To test "agree
// while v_r > 0" at the integrator's level we therefore take s = 1e9 s/m (that term < 1e-9
// of F) and a small load N = 1e-5 N (velocity swing F/sqrt(k m) ~ 0.6 m/s < v_b = 1 m/s,
// asserted below via min v_r > 0). Both runs then solve the same ODE to within 1e-9 of
// the force, so they must agree to the documented 1e-6 of max|x| (measured 3e-9, which is
// that residual term itself; at s = 1e3 s/m the same runs differ by 3e-3).
//
// With Table-1 values (k = 25, v_b = 1) the literal law never reverses (F >= 0.16 mN for any
// v_r), so the asperity overtakes the belt (asserted: an overtake event) and reaches
// ~12.6 um within 0.6 us, while the consistent asperity still sticks at x = v_b t: the
// difference must exceed 1 % of max|x| (measured: 106 %).
TEST(Model2, FrictionFormsAgreeWhileSlidingAndDifferWhenOvertaking) {
  const TimeGrid grid = fig6_grid();
  {
    Asperity a = table1_asperity(25.0);
    a.normal_load_n = 1e-5;
    Model2Params consistent = table1_params(1.0);
    consistent.atan_sharpness_s_per_m = 1e9;
    Model2Params literal = consistent;
    literal.friction_law = find_friction_law("literal");
    const Trajectory tc = solve_model2(a, consistent, grid);
    const Trajectory tl = solve_model2(a, literal, grid);
    double min_vr = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < grid.count; ++j) {
      min_vr = std::min({min_vr, 1.0 - tc.v_m_per_s[j], 1.0 - tl.v_m_per_s[j]});
    }
    ASSERT_GT(min_vr, 0.0);
    EXPECT_TRUE(tc.events.empty());
    EXPECT_TRUE(tl.events.empty());
    EXPECT_LE(max_abs_diff(tc.x_m, tl.x_m), 1e-6 * max_abs(tc.x_m));
  }
  {
    const Trajectory tc = solve_model2(table1_asperity(25.0), table1_params(1.0), grid);
    const Trajectory tl =
        solve_model2(table1_asperity(25.0), table1_params(1.0, "literal"), grid);
    EXPECT_TRUE(has_event(tl, EventKind::overtake));
    EXPECT_TRUE(has_event(tl, EventKind::regrip));
    EXPECT_GT(max_abs_diff(tc.x_m, tl.x_m), 0.01 * max_abs(tc.x_m));
  }
}

// Overtake/regrip times are sign changes of v_r = v_b - x' on the dense output: at each
// event the dense output's v_r must vanish to within rounding of the interpolant
// (1e-9 of the velocity swing), and the kinds must alternate starting with an overtake.
TEST(Model2, EventsSitOnRelativeVelocityZeros) {
  const Model2Params params = table1_params(1.0, "literal");
  const Trajectory t = solve_model2(table1_asperity(50.0), params, fig6_grid());
  ASSERT_FALSE(t.events.empty());
  const double swing = max_abs(t.v_m_per_s);
  for (std::size_t i = 0; i < t.events.size(); ++i) {
    const Event& e = t.events[i];
    EXPECT_EQ(e.kind, i % 2 == 0 ? EventKind::overtake : EventKind::regrip);
    EXPECT_EQ(e.asperity, 0u);
    EXPECT_NEAR(t.motion->at(e.time_s).v_m_per_s, params.belt_velocity_m_per_s, 1e-9 * swing);
  }
}

// Dense output: (1) motion->at(t_j) is what the samples were taken from, so the two agree
// to rounding (1e-12 relative; a knot falling on t_j may be evaluated from either side);
// (2) between the samples, at t_j + dt/2, it matches the dense output of a 100x tighter
// run to the documented 1e-6 of max|x| and 1e-5 of max|x'| (measured ~3e-7 and ~4e-6:
// velocity carries one order less than x in a 4th-order method with a quintic interpolant).
TEST(Model2, DenseOutputMatchesSamplesAndTightReference) {
  const TimeGrid grid = fig6_grid();
  for (const double vb : BELT_VELOCITIES) {
    const Model2Params params = table1_params(vb);
    Model2Params tight = params;
    tight.relative_tolerance /= 100.0;
    const Trajectory t = solve_model2(table1_asperity(155.0), params, grid);
    const Trajectory ref = solve_model2(table1_asperity(155.0), tight, grid);
    ASSERT_TRUE(t.motion);
    EXPECT_TRUE(t.motion->breakpoints().empty());
    const double sx = max_abs(t.x_m);
    const double sv = max_abs(t.v_m_per_s);
    for (std::size_t j = 0; j < grid.count; ++j) {
      const PhasePoint p = t.motion->at(grid.at(j));
      ASSERT_NEAR(p.x_m, t.x_m[j], 1e-12 * sx) << "j = " << j;
      ASSERT_NEAR(p.v_m_per_s, t.v_m_per_s[j], 1e-12 * sv) << "j = " << j;
      if (j + 1 < grid.count) {
        const double tm = grid.at(j) + 0.5 * grid.step_s;
        const PhasePoint q = t.motion->at(tm);
        const PhasePoint r = ref.motion->at(tm);
        ASSERT_NEAR(q.x_m, r.x_m, 1e-6 * sx) << "t = " << tm;
        ASSERT_NEAR(q.v_m_per_s, r.v_m_per_s, 1e-5 * sv) << "t = " << tm;
      }
    }
    EXPECT_THROW((void)t.motion->at(grid.at(grid.count - 1) * 1.01), ModelError);
  }
}

// MODEL.md §1 quotes f = 0.796, 1.125, 1.592, 1.981 MHz for k = 25, 50, 100, 155 N/m:
// agreement to 3 significant digits means within half a unit of the last quoted digit.
TEST(Model2, DampedNaturalFrequenciesMatchModelMd) {
  const double expected_mhz[] = {0.796, 1.125, 1.592, 1.981};
  for (int i = 0; i < 4; ++i) {
    const double f = damped_natural_frequency_hz(K_VALUES[i], 1e-12, 1e-7);
    EXPECT_NEAR(f / 1e6, expected_mhz[i], 0.0005) << "k = " << K_VALUES[i];
  }
  // Over-damped: no line.
  EXPECT_EQ(damped_natural_frequency_hz(1.0, 1e-12, 1e-5), 0.0);
}

// Degenerate grids: one sample is the initial state; none gives empty samples. Both keep
// a usable dense output at t = 0.
TEST(Model2, DegenerateGrids) {
  Asperity a = table1_asperity(50.0);
  a.initial_displacement_m = 2e-6;
  a.initial_velocity_m_per_s = 0.5;
  const Trajectory one = solve_model2(a, table1_params(1.0), TimeGrid{1e-8, 1});
  ASSERT_EQ(one.x_m.size(), 1u);
  EXPECT_EQ(one.x_m[0], 2e-6);
  EXPECT_EQ(one.v_m_per_s[0], 0.5);
  EXPECT_EQ(one.motion->at(0.0).x_m, 2e-6);
  const Trajectory none = solve_model2(a, table1_params(1.0), TimeGrid{1e-8, 0});
  EXPECT_TRUE(none.x_m.empty());
  EXPECT_EQ(none.solver_steps, 0u);
}

// A failing integration must say which asperity, belt velocity and time; bad mechanical
// input is an InputError.
TEST(Model2, FailuresAreReportedWithContext) {
  Model2Params params = table1_params(10.0);
  params.atan_sharpness_s_per_m = std::numeric_limits<double>::quiet_NaN();
  try {
    (void)solve_model2(table1_asperity(100.0), params, fig6_grid());
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("k = 100"), std::string::npos) << what;
    EXPECT_NE(what.find("v_b = 10"), std::string::npos) << what;
    EXPECT_NE(what.find("t = "), std::string::npos) << what;
  }
  Asperity massless = table1_asperity(100.0);
  massless.mass_kg = 0.0;
  EXPECT_THROW((void)solve_model2(massless, table1_params(1.0), fig6_grid()), InputError);
}

}  // namespace
}  // namespace stengmc
