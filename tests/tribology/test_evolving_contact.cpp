// A contact that changes in time (docs/model.md §1.4): the counterface's friction
// modulation against the closed form of a forced damped oscillator, the release against
// free ringing, stiffness steps and wear against closed forms and tighter solutions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "tribology/counterface.hpp"
#include "tribology/evolving_contact.hpp"
#include "tribology/friction_law.hpp"
#include "tribology/model2.hpp"

namespace stengmc {
namespace {

// A steadily sliding asperity: c_s = 0 makes F = N mu_s (2/pi) atan(s v_r), and with
// s = 1e6 s/m at v_r ~ v_b = 10 m/s its slope dF/dv_r = N mu_s (2/pi) / (s v_r^2) ~ 2e-12 N s/m
// is 1e-6 of c: friction is a constant force F while |x'| << v_b.
constexpr double K = 100.0;
constexpr double M = 1e-12;
constexpr double BELT = 10.0;

Model2Params sliding_params(double damping) {
  Model2Params p;
  p.belt_velocity_m_per_s = BELT;
  p.damping_n_s_per_m = damping;
  p.stribeck_decay_s_per_m = 0.0;
  p.atan_sharpness_s_per_m = 1e6;
  return p;
}

//! The asperity at its sliding equilibrium x0 = F(v_b) / k, at rest: with eps = 0 it stays there.
Asperity at_equilibrium(const Model2Params& p) {
  Asperity a;
  a.stiffness_n_per_m = K;
  a.mass_kg = M;
  a.initial_displacement_m = model2_friction(p, a.normal_load_n, BELT) / K;
  return a;
}

std::vector<double> grid_times(double t_end, double step) {
  std::vector<double> t;
  for (std::size_t j = 0; static_cast<double>(j) * step <= t_end * (1 + 1e-12); ++j) t.push_back(static_cast<double>(j) * step);
  return t;
}

// The OU nodes: the stationary variance eps^2 and the one-step correlation rho = exp(-dt/tau_c),
// within 4 standard errors of their estimators (AR(1): var(s^2) = 2 eps^4 (1 + rho^2) / ((1 - rho^2) n),
// var(rho_hat) = (1 - rho^2) / n): a wrong innovation or decay factor fails.
TEST(Counterface, ModulationNodesHaveTheOrnsteinUhlenbeckStatistics) {
  const double rms = 0.1, tau_c = 1e-7, dt = tau_c / 20.0;
  ModulationSequence eps({7, 3, 2}, rms, tau_c, dt);
  const std::size_t n = 400'000;
  double s2 = 0.0, s11 = 0.0;
  double previous = eps.value();
  s2 += previous * previous;
  for (std::size_t j = 1; j < n; ++j) {
    eps.advance();
    s2 += eps.value() * eps.value();
    s11 += previous * eps.value();
    previous = eps.value();
  }
  const double rho = std::exp(-dt / tau_c);
  const double variance = s2 / n;
  const double correlation = s11 / (s2 - previous * previous);
  const double se_variance = rms * rms * std::sqrt(2.0 * (1 + rho * rho) / ((1 - rho * rho) * n));
  const double se_rho = std::sqrt((1 - rho * rho) / n);
  EXPECT_NEAR(variance, rms * rms, 4 * se_variance);
  EXPECT_NEAR(correlation, rho, 4 * se_rho);
}

// The same stream gives the same nodes bit for bit; another asperity index, other nodes.
TEST(Counterface, ModulationIsAFunctionOfItsStream) {
  ModulationSequence a({11, 2, 5}, 0.01, 1e-7, 5e-9), b({11, 2, 5}, 0.01, 1e-7, 5e-9), c({11, 2, 6}, 0.01, 1e-7, 5e-9);
  bool differs = false;
  for (int j = 0; j < 1000; ++j) {
    ASSERT_EQ(a.value(), b.value());
    differs = differs || a.value() != c.value();
    a.advance();
    b.advance();
    c.advance();
  }
  EXPECT_TRUE(differs);
}

//! Stationary covariance of (x, v, f) for m x'' + c x' + k x = f, f an OU force of variance D
//! and rate alpha: A P + P A^T + Q = 0 (Lyapunov), solved by vectorisation.
Eigen::Matrix3d stationary_covariance(double k, double m, double c, double D, double alpha) {
  Eigen::Matrix3d A;
  A << 0, 1, 0, -k / m, -c / m, 1 / m, 0, 0, -alpha;
  Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
  Q(2, 2) = 2 * D * alpha;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 9, 9> L;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) L.block<3, 3>(3 * i, 3 * j) = I(i, j) * A + A(i, j) * I;  // kron(I, A) + kron(A, I)
  Eigen::Matrix<double, 9, 1> q = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(Q.data());
  Eigen::Matrix<double, 9, 1> p = L.partialPivLu().solve(-q);
  return Eigen::Map<Eigen::Matrix3d>(p.data());
}

// The excited oscillator (issue 26's first check): an asperity sliding steadily (friction a
// constant F) forced by F eps(t) is m x'' + c x' + k x = F eps(t); with the Lorentzian force
// spectrum S_F = F^2 eps^2 2 tau_c / (1 + w^2 tau_c^2) its stationary velocity variance is
//   <x'^2> = F^2 eps^2 / (m c (alpha + c/m + (k/m) / alpha)),  alpha = 1 / tau_c,
// and its displacement variance <(x - x0)^2> from the Lyapunov equation of (x, x', f) (the
// closed form is checked against the Lyapunov solution first).
// Simulated: 16 seeds x 1 ms after a 20 us transient (20 relaxation times 2m/c). The
// estimator's relative standard error for a narrow line of width c/m is sqrt(2 / (c/m T)) per
// seed (its autocorrelation e^{-c|tau|/2m} cos w tau, squared and integrated: m/c), 1.1 % over
// the 16; the tolerance is 4 of them. The linear interpolation of eps between its nodes biases
// the spectrum by < 4e-4 (counterface.hpp), far below.
TEST(Counterface, ExcitedOscillatorVarianceMatchesClosedForm) {
  const double damping = 1e-6;  // zeta = 0.05, line width c/(2 pi m) = 159 kHz
  Model2Params p = sliding_params(damping);
  p.counterface.friction_modulation_rms = 0.002;
  p.counterface.correlation_length_m = 1e-6;  // tau_c = 100 ns, alpha = 1e7 1/s = w0
  const Asperity a = at_equilibrium(p);
  const double x0 = a.initial_displacement_m;
  const double F = K * x0;
  const double D = std::pow(F * p.counterface.friction_modulation_rms, 2);
  const double alpha = BELT / p.counterface.correlation_length_m;
  const double v_closed = D / (M * damping * (alpha + damping / M + (K / M) / alpha));
  const Eigen::Matrix3d P = stationary_covariance(K, M, damping, D, alpha);
  ASSERT_NEAR(P(1, 1), v_closed, 1e-10 * v_closed);  // the closed form is the Lyapunov solution

  const double t_skip = 20e-6, t_end = 1e-3 + t_skip;
  const std::vector<double> times = grid_times(t_end, 10e-9);
  const auto first = static_cast<std::size_t>(t_skip / 10e-9);
  const int seeds = 16;
  double sum_v2 = 0.0, sum_x2 = 0.0;
  std::size_t count = 0;
  // Lags of 2, 4 and 5 damped periods (629 ns), to the nearest sample: where the velocity's
  // autocorrelation is its envelope, e^{-(c/2m) tau}, i.e. the line's width c/(2 pi m).
  const std::size_t lags[] = {126, 252, 315};
  double sum_lag[3] = {0.0, 0.0, 0.0};
  std::size_t count_lag[3] = {0, 0, 0};
  for (int seed = 1; seed <= seeds; ++seed) {
    const Model2Solution s = solve_model2_motion(a, p, t_end, {static_cast<std::uint64_t>(seed), 0, 0});
    MotionSamples samples;
    s.motion->sample(times, false, samples);
    for (std::size_t j = first; j < times.size(); ++j) {
      sum_v2 += samples.v_m_per_s[j] * samples.v_m_per_s[j];
      sum_x2 += (samples.x_m[j] - x0) * (samples.x_m[j] - x0);
      ++count;
    }
    for (int l = 0; l < 3; ++l)
      for (std::size_t j = first; j + lags[l] < times.size(); ++j) {
        sum_lag[l] += samples.v_m_per_s[j] * samples.v_m_per_s[j + lags[l]];
        ++count_lag[l];
      }
    EXPECT_TRUE(s.events.empty());  // never near the belt's velocity: no overtake
  }
  const double v2 = sum_v2 / static_cast<double>(count), x2 = sum_x2 / static_cast<double>(count);
  const double se = std::sqrt(2.0 / ((damping / M) * (t_end - t_skip) * seeds));
  std::printf("excited oscillator: <x'^2> = %.5g (closed form %.5g, ratio %.4f), <dx^2> = %.5g (Lyapunov %.5g, ratio "
              "%.4f), standard error %.3g\n",
              v2, P(1, 1), v2 / P(1, 1), x2, P(0, 0), x2 / P(0, 0), se);
  EXPECT_NEAR(v2 / P(1, 1), 1.0, 4 * se);
  EXPECT_NEAR(x2 / P(0, 0), 1.0, 4 * se);

  // The line's width: the normalised velocity autocorrelation at those lags against the
  // exact one, [e^{A tau} P]_vv / P_vv (the Lyapunov system's covariance at lag tau). Its
  // estimator's standard error is ~ that of the variance (Bartlett: sqrt(2 / (c/m T))
  // for a narrow line): tolerance 4 of them. Printed: the width this implies,
  // (c / 2 pi m) ln(rho_sim) / ln(rho_exact) (the OU part has decayed: e^{-alpha tau} < 1e-5).
  Eigen::Matrix3d A;
  A << 0, 1, 0, -K / M, -damping / M, 1 / M, 0, 0, -alpha;
  for (int l = 0; l < 3; ++l) {
    const double tau = 10e-9 * static_cast<double>(lags[l]);
    const Eigen::Matrix3d lagged = (A * tau).exp() * P;
    const double rho_exact = lagged(1, 1) / P(1, 1);
    const double rho_sim = sum_lag[l] / static_cast<double>(count_lag[l]) / v2;
    const double width_hz = damping / (2 * PI * M);
    std::printf("lag %.4g s: autocorrelation %.4f (exact %.4f, envelope e^{-c tau/2m} = %.4f); implied line width "
                "%.4g Hz (c/(2 pi m) = %.4g Hz)\n",
                tau, rho_sim, rho_exact, std::exp(-damping * tau / (2 * M)), width_hz * std::log(rho_sim) / std::log(rho_exact),
                width_hz);
    EXPECT_NEAR(rho_sim, rho_exact, 4 * se);
  }
}

//! x'' = (-c x' - k x + F(v_b - x') (1 + eps(t))) / m by classical RK4 at a step that
//! divides eps's grid (eps linear on every step): the tight reference.
struct Rk4Reference {
  std::vector<double> x, v;  // at t = j h
};
Rk4Reference rk4_reference(const Asperity& a, const Model2Params& p, const CounterfaceStream& stream, double t_end,
                           int substeps, double grid_step) {
  std::vector<double> node_times;
  const double h = grid_step / substeps;
  const auto n = static_cast<std::size_t>(std::llround(t_end / h));
  std::vector<double> t(2 * n + 1);
  for (std::size_t j = 0; j < t.size(); ++j) t[j] = 0.5 * h * static_cast<double>(j);
  std::vector<double> factor;
  modulation_factors(a, p, stream, t, factor);
  // `left`: the limit from before t (a step's last stage), else from after (its first):
  // the release switches friction off between the two.
  auto accel = [&](std::size_t half_index, double x, double v, bool left) {
    const double time = t[half_index];
    const bool contact = left ? time <= a.release_s * (1 + 1e-12) : time < a.release_s * (1 - 1e-12);
    const double k = stiffness_at(a, time);
    const double f = contact ? model2_friction(p, a.normal_load_n, p.belt_velocity_m_per_s - v) : 0.0;
    return (-p.damping_n_s_per_m * v - k * x + f * factor[half_index]) / a.mass_kg;
  };
  Rk4Reference r;
  double x = a.initial_displacement_m, v = 0.0;
  r.x.push_back(x);
  r.v.push_back(v);
  for (std::size_t j = 0; j < n; ++j) {
    const double k1x = v, k1v = accel(2 * j, x, v, false);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(2 * j + 1, x + 0.5 * h * k1x, v + 0.5 * h * k1v, false);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(2 * j + 1, x + 0.5 * h * k2x, v + 0.5 * h * k2v, false);
    const double k4x = v + h * k3v, k4v = accel(2 * j + 2, x + h * k3x, v + h * k3v, true);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    r.x.push_back(x);
    r.v.push_back(v);
  }
  return r;
}

// The integrator against a tighter solution of the same equation along the same eps path:
// RK4 at 1/16 of eps's grid step (~0.2 ns; its error ~(w0 h)^4 / 120 ~ 1e-15 relative per
// period) over 20 us. Agreement within 1e-4 of the excited motion's swing |x - x0| (the
// default tolerance, 1e-8 of the length scale F/k, is ~3e-6 of the swing here; the
// rms of x - x0 is ~1e-8 m against F/k = 2.8e-6 m).
TEST(Counterface, IntegratorFollowsTighterSolutionAlongTheSamePath) {
  Model2Params p = sliding_params(1e-7);
  p.counterface.friction_modulation_rms = 0.01;
  p.counterface.correlation_length_m = 0.5e-6;
  const Asperity a = at_equilibrium(p);
  const CounterfaceStream stream{3, 1, 4};
  const double t_end = 20e-6;
  const double grid = modulation_step_s(correlation_time_s(p.counterface, BELT), std::sqrt(K / M));
  const int substeps = 16;
  const Rk4Reference ref = rk4_reference(a, p, stream, t_end, substeps, grid);
  const Model2Solution s = solve_model2_motion(a, p, t_end, stream);
  double swing = 0.0, worst = 0.0;
  const double h = grid / substeps;
  for (std::size_t j = 0; j < ref.x.size(); j += 7) {
    const PhasePoint q = s.motion->at(std::min(h * static_cast<double>(j), t_end));
    swing = std::max(swing, std::abs(ref.x[j] - a.initial_displacement_m));
    worst = std::max(worst, std::abs(q.x_m - ref.x[j]));
  }
  std::printf("modulated path: max |x - x_ref| = %.3g m, swing %.3g m\n", worst, swing);
  EXPECT_GT(swing, 1e-9);
  EXPECT_LT(worst, 1e-4 * swing);
}

// Release: from its sliding equilibrium x0 the asperity loses its load at t_r and rings
// freely about x = 0: x = e^{-g s} x0 (cos w_d s + (g / w_d) sin w_d s), g = c / 2m,
// s = t - t_r; over 3 relaxation times 2m/c = 20 us. Tolerance 1e-6 of x0 (the default
// tolerance's documented accuracy on the output grid).
TEST(EvolvingContact, ReleasedAsperityRingsDownToRest) {
  Model2Params p = sliding_params(1e-7);
  Asperity a = at_equilibrium(p);
  a.release_s = 2e-6;
  const double x0 = a.initial_displacement_m;
  const double t_end = 62e-6;
  const Model2Solution s = solve_model2_motion(a, p, t_end);
  const double g = p.damping_n_s_per_m / (2 * M);
  const double wd = std::sqrt(K / M - g * g);
  double worst = 0.0;
  for (double t = 0.0; t <= t_end; t += 1e-8) {
    const double sr = t - a.release_s;
    const double expected = sr <= 0 ? x0 : std::exp(-g * sr) * x0 * (std::cos(wd * sr) + g / wd * std::sin(wd * sr));
    worst = std::max(worst, std::abs(s.motion->at(t).x_m - expected));
  }
  std::printf("release: max |x - closed form| = %.3g m (x0 = %.3g m)\n", worst, x0);
  EXPECT_LT(worst, 1e-6 * x0);
  // Relaxed: after 3 relaxation times the envelope is e^-3 of x0.
  EXPECT_LT(std::abs(s.motion->at(t_end).x_m), 1.01 * std::exp(-3.0) * x0 * std::sqrt(1 + g * g / (wd * wd)));
}

// A stiffness step k -> 1.1 k at t_s from the sliding equilibrium: the asperity rings about
// the new equilibrium x1 = F / k1, x = x1 + (x0 - x1) e^{-g s} (cos w_d s + (g / w_d) sin w_d s)
// with w_d = sqrt(k1/m - g^2): pointwise within 1e-6 of x0, and the line's frequency from
// the upward zero crossings of x - x1 (40 us, ~66 periods) within 1e-5 of
// sqrt(k1/m) sqrt(1 - zeta1^2) / 2 pi (crossings interpolated linearly at 1 ns: ~1e-9 s each).
TEST(EvolvingContact, StiffnessStepMovesTheLine) {
  Model2Params p = sliding_params(1e-7);
  Asperity a = at_equilibrium(p);
  a.stiffness_steps = {{2e-6, 1.1}};
  const double x0 = a.initial_displacement_m;
  const double k1 = 1.1 * K;
  const double x1 = K * x0 / k1;
  const double t_end = 42e-6;
  const Model2Solution s = solve_model2_motion(a, p, t_end);
  const double g = p.damping_n_s_per_m / (2 * M);
  const double wd = std::sqrt(k1 / M - g * g);
  double worst = 0.0;
  std::vector<double> crossings;
  double previous = 0.0;
  for (double t = 0.0; t <= t_end; t += 1e-9) {
    const double sr = t - 2e-6;
    const double x = s.motion->at(t).x_m;
    const double expected = sr <= 0 ? x0 : x1 + (x0 - x1) * std::exp(-g * sr) * (std::cos(wd * sr) + g / wd * std::sin(wd * sr));
    worst = std::max(worst, std::abs(x - expected));
    const double d = x - x1;
    if (sr > 0 && previous < 0 && d >= 0) crossings.push_back(t - 1e-9 * d / (d - previous));
    previous = d;
  }
  ASSERT_GT(crossings.size(), 50u);
  const double f = static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
  const double f_expected = damped_natural_frequency_hz(k1, M, p.damping_n_s_per_m);
  std::printf("stiffness step: max |x - closed form| = %.3g m, line %.7g Hz (closed form %.7g Hz)\n", worst, f, f_expected);
  EXPECT_LT(worst, 1e-6 * x0);
  EXPECT_NEAR(f / f_expected, 1.0, 1e-5);
}

// Wear k(t) = k0 (1 - w (t - t_on) / 1 ms), frozen after the release, against RK4 at 0.1 ns
// (a tighter solution; the equation is linear with a constant force here): within 1e-6 of x0
// over 50 us with a 30 %/ms wear, an onset at 1 us and a release at 40 us. The quasi-static
// closed form F / k(t) holds to the ramp's small ringing (~3e-5 of x0) before the release.
TEST(EvolvingContact, WearFollowsTighterSolutionAndFreezesAtRelease) {
  Model2Params p = sliding_params(1e-7);
  Asperity a = at_equilibrium(p);
  a.wear_rate_per_ms = 0.3;
  a.release_s = 40e-6;
  EXPECT_DOUBLE_EQ(stiffness_at(a, 20e-6), K * (1 - 0.3 * 0.02));
  EXPECT_DOUBLE_EQ(stiffness_at(a, 45e-6), K * (1 - 0.3 * 0.04));
  const double x0 = a.initial_displacement_m;
  const double t_end = 50e-6;
  const Model2Solution s = solve_model2_motion(a, p, t_end);
  // No modulation: eps = 0, modulation_factors gives 1; a grid step of 1.6 ns and 16 substeps.
  const Rk4Reference ref = rk4_reference(a, p, {}, t_end, 16, 1.6e-9);
  const double h = 1.6e-9 / 16;
  double worst = 0.0, worst_quasi_static = 0.0;
  for (std::size_t j = 0; j < ref.x.size(); j += 11) {
    const double t = std::min(h * static_cast<double>(j), t_end);
    const double x = s.motion->at(t).x_m;
    worst = std::max(worst, std::abs(x - ref.x[j]));
    if (t < a.release_s) worst_quasi_static = std::max(worst_quasi_static, std::abs(x - K * x0 / stiffness_at(a, t)));
  }
  std::printf("wear: max |x - x_ref| = %.3g m, max |x - F/k(t)| = %.3g m (x0 = %.3g m)\n", worst, worst_quasi_static, x0);
  EXPECT_LT(worst, 1e-6 * x0);
  EXPECT_LT(worst_quasi_static, 1e-4 * x0);
}

TEST(EvolvingContact, WearToZeroIsAModelError) {
  Model2Params p = sliding_params(1e-7);
  Asperity a = at_equilibrium(p);
  a.wear_rate_per_ms = 100.0;  // k reaches 0 after 10 us
  EXPECT_THROW(solve_model2_motion(a, p, 20e-6), ModelError);
}

// No modulation, no release, no wear, no steps: the autonomous integrator, as before.
TEST(EvolvingContact, OnlyEvolvingContactsTakeTheNewIntegrator) {
  Model2Params p;
  Asperity a;
  EXPECT_FALSE(contact_evolves(a, p));
  a.release_s = 1e-6;
  EXPECT_TRUE(contact_evolves(a, p));
  a = Asperity{};
  p.counterface.friction_modulation_rms = 0.01;
  EXPECT_TRUE(contact_evolves(a, p));
}

}  // namespace
}  // namespace stengmc
