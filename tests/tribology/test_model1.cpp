// Model 1 (Coulomb stick-slip under an imposed sinusoid, MODEL.md §1): the exact solver against
// an independent adaptive Runge-Kutta integration with event location, its slip phases against
// the ODE, the paper's no-slip case, Euler-Cromer convergence and dense-output consistency.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "core/error.hpp"
#include "tribology/model1.hpp"

namespace stengmc {
namespace {

constexpr double TWO_PI = 2.0 * 3.14159265358979323846;
constexpr double DRIVE_PERIOD_S = 1e-4;  // default omega = 2 pi 10 kHz

// Paper Table 1 asperity with stiffness k [N/m].
Asperity table1_asperity(double k) {
  Asperity a;
  a.stiffness_n_per_m = k;
  a.mass_kg = 1e-12;
  a.normal_load_n = 1e-3;
  return a;
}

struct RefEvent {
  double t_s;
  EventKind kind;
};

// Independent reference: the slip ODE m x'' = k (x0 - x) - mu_k N s integrated by an adaptive
// Runge-Kutta-Fehlberg 7(8) (Boost.Odeint) at 1e-14 tolerances in scaled variables; a v = 0
// event is located by bisection, re-integrating one RKF78 step from the accepted step's start
// to each trial time; a stick ends where |k (x0 - x_s)| - mu_s N changes sign, scanned then
// bisected. Nothing here uses the solver's closed form.
// Boost.Odeint's steppers copy their scratch arrays (std::array, left uninitialised until
// the first step) when make_controlled takes one by value: GCC 12 reports the copy
// (-Wmaybe-uninitialized) though nothing reads those values before a step writes them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
std::vector<RefEvent> reference_events(const Asperity& asp, const Model1Params& p, double t_end) {
  namespace ode = boost::numeric::odeint;
  using Y = std::array<double, 2>;  // (x / L, v / (L w0))
  const double k = asp.stiffness_n_per_m, m = asp.mass_kg;
  const double fs = p.friction.static_coefficient * asp.normal_load_n;
  const double fk = p.friction.kinetic_coefficient * asp.normal_load_n;
  const double w0 = std::sqrt(k / m), omega = p.drive_angular_frequency_rad_per_s;
  const double length = fs / k, speed = length * w0;
  auto drive = [&](double t) { return p.drive_amplitude_m * std::sin(omega * t + asp.drive_phase_rad); };
  auto sgn = [](double v) { return v > 0.0 ? 1.0 : -1.0; };
  const double max_step = TWO_PI / std::max(omega, w0) / 50.0;
  std::vector<RefEvent> events;

  double t = 0.0, x = asp.initial_displacement_m, v = asp.initial_velocity_m_per_s, s = 0.0;
  if (v != 0.0) {
    s = sgn(v);
  } else if (std::abs(k * (drive(0.0) - x)) > fs) {
    s = sgn(drive(0.0) - x);
    events.push_back({0.0, EventKind::slip});
  }
  while (t < t_end) {
    if (s == 0.0) {  // stuck at x: scan, then bisect the threshold crossing
      auto excess = [&](double tt) { return std::abs(k * (drive(tt) - x)) - fs; };
      const double scan = TWO_PI / omega / 4000.0;
      double lo = t, hi = t;
      while (hi < t_end && excess(hi) <= 0.0) { lo = hi; hi += scan; }
      if (excess(hi) <= 0.0) break;
      while (true) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (excess(mid) > 0.0 ? hi : lo) = mid;
      }
      if (hi > t_end) break;
      t = hi;
      s = sgn(drive(t) - x);
      v = 0.0;
      events.push_back({t, EventKind::slip});
      continue;
    }
    const double dir = s;
    auto rhs = [&](const Y& y, Y& dydt, double tt) {
      dydt[0] = w0 * y[1];
      dydt[1] = (k * (drive(tt) - length * y[0]) - fk * dir) / (m * speed);
    };
    auto controlled = ode::make_controlled(1e-14, 1e-14, ode::runge_kutta_fehlberg78<Y>());
    ode::runge_kutta_fehlberg78<Y> single;
    Y y{x / length, v / speed};
    double dt = max_step / 8.0;
    bool ended = false;
    while (t < t_end) {
      Y y_new = y;
      double t_new = t;
      dt = std::min(dt, max_step);
      if (controlled.try_step(rhs, y_new, t_new, dt) != ode::success) continue;
      if (dir * y_new[1] > 0.0) {
        y = y_new;
        t = t_new;
        continue;
      }
      // s v > 0 just after t (or at t), <= 0 at t_new: bisect, one RKF78 step per trial.
      auto state_at = [&](double tau) {
        Y out;
        single.do_step(rhs, y, t, out, tau);
        return out;
      };
      double lo = 0.0, hi = t_new - t;
      while (true) {
        const double mid = 0.5 * (lo + hi);
        if (t + mid <= t + lo || t + mid >= t + hi) break;
        (dir * state_at(mid)[1] > 0.0 ? lo : hi) = mid;
      }
      const Y end = state_at(hi);
      t += hi;
      x = length * end[0];
      v = 0.0;
      const double force = k * (drive(t) - x);
      if (std::abs(force) <= fs) {
        s = 0.0;
        events.push_back({t, EventKind::stick});
      } else {
        s = sgn(force);
        events.push_back({t, EventKind::reversal});
      }
      ended = true;
      break;
    }
    if (!ended) break;
  }
  return events;
}
#pragma GCC diagnostic pop

std::string kinds(const std::vector<RefEvent>& events) {
  std::string out;
  for (const auto& e : events) out += std::string(event_name(e.kind)).substr(0, 2) + " ";
  return out;
}

// Event times of the exact solver against the independent integration. The reference's own
// event-time error is ~ (1e-14 local tolerance) / w0 plus bisection to 1 ulp, and position
// errors of ~1e-13 L carried by a stick shift the next slip by ~1e-13 L / (A omega), all
// far below 1e-9 of t; 1e-9 relative is the brief's acceptance bound with margin for events
// where the drive is near its turning point (a slower threshold crossing amplifies errors).
TEST(Model1Exact, EventTimesMatchIndependentRungeKuttaIntegration) {
  struct Case {
    double k;            // [N/m]
    double phase;        // [rad]
    double v_init;       // [m/s]
    double omega;        // [rad/s]; 0: the default 2 pi 10 kHz
    double mu_s;         // 0: Table 1's 0.28
    std::size_t min_events;
  };
  // Table 1 at three stiffnesses; a drive phase with a sliding start; mu_s = mu_k (slips from
  // rest start with zero acceleration); a drive faster than the asperity (omega = 2 w0 > w0).
  const std::vector<Case> cases = {{155.0, 0.0, 0.0, 0.0, 0.0, 100}, {75.0, 0.0, 0.0, 0.0, 0.0, 40},
                                   {40.0, 0.0, 0.0, 0.0, 0.0, 10},   {75.0, 1.0, 0.3, 0.0, 0.0, 40},
                                   {155.0, 0.0, 0.0, 0.0, 0.22, 100},
                                   {40.0, 0.0, 0.0, 2.0 * std::sqrt(40.0 / 1e-12), 0.0, 4}};
  double worst = 0.0;
  for (const Case& c : cases) {
    Asperity asp = table1_asperity(c.k);
    asp.drive_phase_rad = c.phase;
    asp.initial_velocity_m_per_s = c.v_init;
    Model1Params params;
    if (c.omega > 0.0) params.drive_angular_frequency_rad_per_s = c.omega;
    if (c.mu_s > 0.0) params.friction.static_coefficient = c.mu_s;
    const double duration = 2.0 * TWO_PI / params.drive_angular_frequency_rad_per_s;
    const Trajectory traj = solve_model1_exact(asp, params, TimeGrid::covering(duration, 1e3 / duration));
    std::vector<RefEvent> ref = reference_events(asp, params, duration);
    std::vector<RefEvent> got;
    for (const Event& e : traj.events) got.push_back({e.time_s, e.kind});
    // Drop events in the last 1e-6 of the run, where one side may just miss t_end.
    for (auto* list : {&ref, &got}) {
      std::erase_if(*list, [&](const RefEvent& e) { return e.t_s > duration * (1.0 - 1e-6); });
    }
    ASSERT_EQ(got.size(), ref.size()) << "k = " << c.k << "\nexact: " << kinds(got)
                                      << "\nreference: " << kinds(ref);
    ASSERT_GE(got.size(), c.min_events) << "k = " << c.k << " should stick-slip many times";
    double case_worst = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].kind, ref[i].kind) << "k = " << c.k << ", event " << i;
      const double rel = std::abs(got[i].t_s - ref[i].t_s) / std::max(ref[i].t_s, 1e-9 * duration);
      case_worst = std::max(case_worst, rel);
      EXPECT_LE(rel, 1e-9) << "k = " << c.k << ", event " << i << " at " << ref[i].t_s << " s";
    }
    worst = std::max(worst, case_worst);
    std::printf("k = %g N/m, phi = %g, v0 = %g m/s, omega = %.4g rad/s, mu_s = %g: %zu events, "
                "max relative event-time error %.2e\n", c.k, c.phase, c.v_init,
                params.drive_angular_frequency_rad_per_s, params.friction.static_coefficient,
                got.size(), case_worst);
  }
  std::printf("max relative event-time error vs RKF78 reference: %.3e\n", worst);
}

// Slip phases against the ODE itself: x' and x'' by central differences of the dense output,
// residual m x'' + k x - k x0 + mu_k N s. With delta = 1e-3 / w0 the truncation error is
// (w0 delta)^2 / 6 ~ 2e-7 of the largest term (m |x''| <= ~2 mu_s N) and rounding
// eps |v| / delta is ~1e-13 of it, so 1e-6 mu_s N fails on any wrong sign or amplitude
// (a wrong friction sign alone leaves 2 mu_k N). Stick/reversal decisions are checked too.
TEST(Model1Exact, SlipPhasesSatisfyTheOde) {
  const Asperity asp = table1_asperity(155.0);
  const Model1Params params;
  const double k = asp.stiffness_n_per_m, m = asp.mass_kg, n = asp.normal_load_n;
  const double fs = params.friction.static_coefficient * n, fk = params.friction.kinetic_coefficient * n;
  const Trajectory traj = solve_model1_exact(asp, params, TimeGrid::covering(2 * DRIVE_PERIOD_S, 1e6));
  const Motion& motion = *traj.motion;
  const double delta = 1e-3 / std::sqrt(k / m);
  std::size_t checked = 0;
  for (std::size_t i = 0; i + 1 < traj.events.size(); ++i) {
    const Event& e = traj.events[i];
    const double t_next = traj.events[i + 1].time_s;
    const double x_next = motion.at(t_next).x_m;
    const double force_next = k * (imposed_displacement(params, asp, t_next) - x_next);
    if (traj.events[i + 1].kind == EventKind::stick) {
      EXPECT_LE(std::abs(force_next), fs);
    }
    if (traj.events[i + 1].kind == EventKind::reversal) {
      EXPECT_GT(std::abs(force_next), fs);
    }
    if (e.kind == EventKind::stick) continue;
    EXPECT_NEAR(motion.at(t_next, Side::left).v_m_per_s, 0.0, 1e-12);  // slip ends at x' = 0
    for (double f : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const double t = e.time_s + f * (t_next - e.time_s);
      const PhasePoint here = motion.at(t), before = motion.at(t - delta), after = motion.at(t + delta);
      const double v_fd = (after.x_m - before.x_m) / (2 * delta);
      const double a_fd = (after.v_m_per_s - before.v_m_per_s) / (2 * delta);
      const double s = here.v_m_per_s > 0 ? 1.0 : -1.0;
      const double residual = m * a_fd + k * here.x_m - k * imposed_displacement(params, asp, t) + fk * s;
      EXPECT_LE(std::abs(residual), 1e-6 * fs) << "slip phase starting " << e.time_s << " s";
      EXPECT_NEAR(v_fd, here.v_m_per_s, 1e-6 * 10.0) << "x' is the derivative of x (|x'| < 10 m/s)";
      ++checked;
    }
  }
  EXPECT_GT(checked, 100u);
}

// Paper Table 1 with k = 10 N/m: mu_s N / k = 28 um > A = 9 um, so the drive never breaks
// static friction (MODEL.md §1). Exact equalities: a stuck asperity is computed as x = 0.
TEST(Model1, StiffnessTenNeverSlips) {
  const Asperity asp = table1_asperity(10.0);
  Model1Params params;
  EXPECT_FALSE(model1_can_slip(params, asp));
  EXPECT_TRUE(model1_can_slip(params, table1_asperity(155.0)));
  for (Model1Solver solver : {Model1Solver::exact, Model1Solver::euler_cromer}) {
    params.solver = solver;
    const TimeGrid grid = TimeGrid::covering(2 * DRIVE_PERIOD_S, 1e6);
    const Trajectory traj = solve_model1(asp, params, grid);
    EXPECT_TRUE(traj.events.empty());
    ASSERT_EQ(traj.x_m.size(), grid.count);
    for (std::size_t j = 0; j < grid.count; ++j) {
      ASSERT_EQ(traj.x_m[j], 0.0);
      ASSERT_EQ(traj.v_m_per_s[j], 0.0);
      // Stuck: the friction output is the spring force k x0 it balances.
      ASSERT_DOUBLE_EQ(traj.friction_n[j], 10.0 * imposed_displacement(params, asp, grid.at(j)));
    }
    EXPECT_TRUE(traj.motion->breakpoints().empty());
  }
}

// Max |x_ec - x_exact| on the output grid for h = step / q, q = 1, 2, 4, ...
std::vector<double> euler_cromer_errors(const Asperity& asp, const TimeGrid& grid, std::size_t q_max) {
  Model1Params params;
  const Trajectory exact = solve_model1_exact(asp, params, grid);
  params.solver = Model1Solver::euler_cromer;
  std::vector<double> errors;
  for (std::size_t q = 1; q <= q_max; q *= 2) {
    params.euler_cromer_substeps = q;
    const Trajectory ec = solve_model1(asp, params, grid);
    double err = 0.0;
    for (std::size_t j = 0; j < grid.count; ++j) err = std::max(err, std::abs(ec.x_m[j] - exact.x_m[j]));
    errors.push_back(err);
  }
  return errors;
}

void print_orders(const char* what, const std::vector<double>& errors, double step) {
  for (std::size_t i = 0; i < errors.size(); ++i) {
    std::printf("%s h = %.4g s: error %.4e m", what, step / std::pow(2.0, double(i)), errors[i]);
    if (i > 0) std::printf(", order %.3f", std::log2(errors[i - 1] / errors[i]));
    std::printf("\n");
  }
}

// Euler-Cromer against the exact solver on a slip that starts at t = 0 from rest (x(0) =
// -1.5 mu_s N / k), then sticks, up to just before the next slip (3.23 us). The transition
// at t = 0 lies on every step grid, so the error is the scheme's own, deterministic first-
// order error (v_{n+1} is x' at t_n + h/2, not at t_n); halving h should halve it. Measured
// orders are 1.000 +- 0.001; the band [0.8, 1.3] fails for a first-order term gone wrong
// (order 2 or 0) and errors must fall at every halving.
TEST(Model1EulerCromer, ConvergesAtFirstOrderOnASlipPhase) {
  Asperity asp = table1_asperity(155.0);
  asp.initial_displacement_m = -1.5 * 0.28 * 1e-3 / 155.0;
  const TimeGrid grid = TimeGrid::covering(3e-6, 1e9);  // 1 ns output step
  const std::vector<double> errors = euler_cromer_errors(asp, grid, 16);
  print_orders("slip phase: euler_cromer", errors, grid.step_s);
  for (std::size_t i = 1; i < errors.size(); ++i) {
    EXPECT_LT(errors[i], errors[i - 1]);
    const double order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_GE(order, 0.8);
    EXPECT_LE(order, 1.3);
  }
}

// Stick-slip over a whole drive period. Each stick-to-slip transition lands on the step grid
// with a delay in [0, h) whose fraction changes erratically with h, so one run's max error is
// O(h) only as a bound (single runs give "orders" from -1 to 3). Averaged over 16 drive phases
// the bound's constant settles: we require the mean error to fall at every halving and the
// order fitted over q = 1 .. 16 (measured 1.01) to lie in [0.8, 1.3].
TEST(Model1EulerCromer, StickSlipErrorIsFirstOrderOnAverage) {
  const TimeGrid grid = TimeGrid::covering(DRIVE_PERIOD_S, 1e9);
  const int phases = 16;
  std::vector<double> mean(5, 0.0);
  for (int i = 0; i < phases; ++i) {
    Asperity asp = table1_asperity(155.0);
    asp.drive_phase_rad = TWO_PI * (i + 0.5) / phases;
    const std::vector<double> errors = euler_cromer_errors(asp, grid, 16);
    for (std::size_t n = 0; n < mean.size(); ++n) mean[n] += errors[n] / phases;
  }
  print_orders("stick-slip, mean over 16 drive phases: euler_cromer", mean, grid.step_s);
  for (std::size_t i = 1; i < mean.size(); ++i) EXPECT_LT(mean[i], mean[i - 1]);
  const double order = std::log2(mean.front() / mean.back()) / 4.0;
  EXPECT_GE(order, 0.8);
  EXPECT_LE(order, 1.3);
}

// The dense output is what the circuit sees, the samples what files and spectra see: they must
// be the same function. Exact solver: the samples are evaluated by the same closed form, so
// equality is exact on the right and continuity-level (1e-12 relative) on the left.
// Euler-Cromer: the sample velocity is the scheme's state v_n, the slope of the step into t_n,
// i.e. the left limit; x at a step time is the stored step value.
TEST(Model1, DenseOutputMatchesSamples) {
  const Asperity asp = table1_asperity(155.0);
  Model1Params params;
  const TimeGrid grid = TimeGrid::covering(DRIVE_PERIOD_S, 2e8);
  const Trajectory exact = solve_model1_exact(asp, params, grid);
  const auto& bp = exact.motion->breakpoints();
  ASSERT_EQ(bp.size() + 1, exact.solver_steps);
  EXPECT_TRUE(std::is_sorted(bp.begin(), bp.end()));
  for (std::size_t i = 0; i < bp.size(); ++i) EXPECT_EQ(bp[i], exact.events[i].time_s);
  for (std::size_t j = 0; j < grid.count; ++j) {
    const PhasePoint r = exact.motion->at(grid.at(j), Side::right);
    const PhasePoint l = exact.motion->at(grid.at(j), Side::left);
    ASSERT_EQ(r.x_m, exact.x_m[j]);
    ASSERT_EQ(r.v_m_per_s, exact.v_m_per_s[j]);
    ASSERT_NEAR(l.x_m, exact.x_m[j], 1e-12 * 1e-5);
    ASSERT_NEAR(l.v_m_per_s, exact.v_m_per_s[j], 1e-12 * 10.0);
  }
  params.solver = Model1Solver::euler_cromer;
  params.euler_cromer_substeps = 3;
  const Trajectory ec = solve_model1(asp, params, grid);
  EXPECT_EQ(ec.solver_steps, (grid.count - 1) * 3);
  const auto& ebp = ec.motion->breakpoints();
  EXPECT_TRUE(std::adjacent_find(ebp.begin(), ebp.end(), std::greater_equal<>()) == ebp.end());
  for (std::size_t j = 0; j < grid.count; ++j) {
    ASSERT_EQ(ec.motion->at(grid.at(j), Side::right).x_m, ec.x_m[j]);
    ASSERT_EQ(ec.motion->at(grid.at(j), Side::left).v_m_per_s, ec.v_m_per_s[j]);
  }
  // Between step times x is linear with the step's slope.
  const double t = grid.at(100) + 0.4 * grid.step_s / 3;
  const PhasePoint mid = ec.motion->at(t);
  EXPECT_NEAR(mid.x_m, ec.x_m[100] + (t - grid.at(100)) * mid.v_m_per_s, 1e-20);
}

// Drive at the natural pulsation: the closed-form particular solution divides by zero, so the
// exact solver must refuse and name the alternative; Euler-Cromer still runs.
TEST(Model1Exact, RejectsResonantDrive) {
  const Asperity asp = table1_asperity(155.0);
  Model1Params params;
  params.drive_angular_frequency_rad_per_s = std::sqrt(155.0 / 1e-12);
  const TimeGrid grid = TimeGrid::covering(1e-5, 1e9);
  try {
    (void)solve_model1_exact(asp, params, grid);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("euler_cromer"), std::string::npos) << e.what();
  }
  params.solver = Model1Solver::euler_cromer;
  EXPECT_NO_THROW((void)solve_model1(asp, params, grid));
}

// Rejected inputs name the parameter.
TEST(Model1, RejectsInvalidParameters) {
  Model1Params params;
  params.friction.static_coefficient = 0.1;  // < mu_k = 0.22
  const TimeGrid grid = TimeGrid::covering(1e-5, 1e8);
  try {
    (void)solve_model1(table1_asperity(155.0), params, grid);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mu_s"), std::string::npos) << e.what();
  }
  params = Model1Params{};
  params.solver = Model1Solver::euler_cromer;
  params.euler_cromer_substeps = 0;
  EXPECT_THROW((void)solve_model1(table1_asperity(155.0), params, grid), InputError);
  EXPECT_THROW((void)solve_model1(table1_asperity(-1.0), Model1Params{}, grid), InputError);
}

}  // namespace
}  // namespace stengmc
