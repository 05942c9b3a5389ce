#include "tribology/model2_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Core>
#include <Eigen/LU>  // fixed-size 2x2 inverse

#include "core/error.hpp"
#include "tribology/model2_scaled_system.hpp"
#include "tribology/rodas4.hpp"
#include "tribology/sliding_propagator.hpp"

namespace stengmc {
namespace {


// RODAS4 (rodas4.hpp). The system is autonomous, so the D_i (df/dt) terms vanish and
// the stage times are not needed. L-stability matters here: in the sticking phase
// h |lambda| reaches 1e3..1e5 and an A-stable-only method (R(inf) != 0) would leave the
// stiff component ringing.
using namespace rodas4;

// Step-size control of rodas.f: h_new = h / clamp(err^(1/4) / SAFE, 1/MAX_GROWTH, MAX_SHRINK),
// with Gustafsson's predictive controller after accepted steps.
constexpr double SAFE = 0.9;
constexpr double MAX_SHRINK = 5.0;
constexpr double MAX_GROWTH = 6.0;
// Largest step in units of 1/w0 (~1/25 of the undamped period): keeps the quintic Hermite
// dense output (error ~ (w0 h)^6 / 46080 of the amplitude) below 1e-10 even where the
// local error test alone would allow longer steps.
constexpr double MAX_STEP = 0.25;
// Where the motion is not oscillating at all (the linearised system over-damped,
// zeta_e > 1: sticking, x' ~ v_b), x follows the slow manifold and the quintic is far more
// accurate than that bound; there the steps may reach MAX_STEP_STICKING, but stop at half
// the way to where breakaway could at the earliest begin: friction cannot hold more than
// N max(mu_s, mu_k), so sticking ends before k x + c x' reaches it.
constexpr double MAX_STEP_STICKING = 2.0;

//! Largest step from y for the quintic dense output (scaled units).
double max_step(const ScaledSystem& sys, const Vec2& y, const Mat2& jac) {
  if (!(-0.5 * jac(1, 1) > 1.0) || y[1] == 0.0) return MAX_STEP;
  const double direction = y[1] > 0.0 ? 1.0 : -1.0;
  const double gap = direction * sys.friction_term_bound() - sys.two_zeta() * y[1] - y[0];
  const double time_to_breakaway = gap / y[1];
  if (!(time_to_breakaway > 0.0)) return MAX_STEP;
  return std::clamp(0.5 * time_to_breakaway, MAX_STEP, MAX_STEP_STICKING);
}

// The catch of the belt: as x' reaches v_b, friction turns from ~N mu to whatever holds
// the spring within |v_r| ~ 1/s (picoseconds at the Table-2 values). A RODAS4 step grown on
// the smooth approach overshoots that knee and is rejected, and the steps after it halve
// towards it, an acceptance and a rejection each time (25 steps and 8 rejections in the
// first 4 ns of the k = 25 N/m asperity at v_b = 1). Instead a step that would pass it
// lands where s |v_r| = KNEE_LANDING (friction still within (2/pi)/64, 1 %, of saturation:
// the approach is smooth up to there), at the step start's acceleration; the knee itself
// is left to the error control. Measured: 16 steps and 4 rejections over those 4 ns, the
// same accuracy (bench/compare_scipy.py, docs/performance.md).
constexpr double KNEE_LANDING = 64.0;
// A landing nearer than this fraction of the last step is not aimed at: the
// constant-acceleration estimate falls a little short each time, and aiming again and
// again would creep up on the knee.
constexpr double KNEE_LANDING_MIN_FRACTION = 0.1;

//! Scaled time until x' reaches the landing velocity (v_r = +-KNEE_LANDING / s on the side
//! it comes from) at the acceleration f[1], or infinity where it is not heading there or
//! has passed it. `landing_offset`: KNEE_LANDING / s in units of the velocity scale.
double time_to_knee_landing(double belt_w, double landing_offset, const Vec2& y, const Vec2& f) {
  const double landing = belt_w - (belt_w > y[1] ? landing_offset : -landing_offset);
  const double gap = landing - y[1];
  const bool ahead = gap * f[1] > 0.0 && (belt_w - landing) * gap > 0.0;
  return ahead ? gap / f[1] : std::numeric_limits<double>::infinity();
}
constexpr std::size_t MAX_STEPS = 50'000'000;

// Where the sliding propagator (sliding_propagator.hpp) is tried: while the frozen
// oscillator is at most moderately damped. Sticking (zeta_e ~ 1e4: friction slope
// N mu_s (2/pi) s, far from linear near breakaway) stays with RODAS4, and so does a step
// the propagator cannot take at least PROPAGATOR_MIN_STEP long.
constexpr double PROPAGATOR_ZETA_MAX = 0.5;
// Longest step: one undamped period (the remainder is then fitted over at most one full
// swing; the error control decides below that). Half a period (before) took 144 steps
// where this takes 128 for the k = 25 N/m asperity at v_b = 1, rtol 1e-6, at the same
// accuracy; two periods took no fewer (the error test holds the steps below one).
constexpr double PROPAGATOR_MAX_STEP = 6.283185307179586;
constexpr double PROPAGATOR_MIN_STEP = 0.1;
constexpr double PROPAGATOR_MAX_GROWTH = 4.0;
// After the propagator gave way, RODAS4 steps before it is tried again; doubles with each
// consecutive failure (up to 2^6 times), back to this after a success.
constexpr std::size_t PROPAGATOR_COOLDOWN = 2;


// One RODAS4 step of size h from y (with f0 = f(y), jac = J(y)); returns y1 and the error
// estimate. The 2x2 iteration matrix is inverted in closed form: its determinant is
// (1/(gamma h))^2 + (1/(gamma h)) (2 zeta + g) + 1 > 0 with g >= 0 wherever friction
// increases with v_r, so it is well conditioned for every step size.
void rodas4_step(const ScaledSystem& sys, const Vec2& y, const Vec2& f0, const Mat2& jac, double h,
                 Vec2& y1, Vec2& err) {
  const double inv_gh = 1.0 / (GAMMA * h);
  Mat2 m = -jac;
  m(0, 0) += inv_gh;
  m(1, 1) += inv_gh;
  const Mat2 minv = m.inverse();  // Eigen's fixed-size 2x2 inverse is the cofactor formula
  const double inv_h = 1.0 / h;

  const Vec2 g1 = minv * f0;
  const Vec2 g2 = minv * (sys.rhs(y + A21 * g1) + (C21 * inv_h) * g1);
  const Vec2 g3 = minv * (sys.rhs(y + A31 * g1 + A32 * g2) + inv_h * (C31 * g1 + C32 * g2));
  const Vec2 g4 =
      minv * (sys.rhs(y + A41 * g1 + A42 * g2 + A43 * g3) + inv_h * (C41 * g1 + C42 * g2 + C43 * g3));
  const Vec2 y5 = y + A51 * g1 + A52 * g2 + A53 * g3 + A54 * g4;
  const Vec2 g5 = minv * (sys.rhs(y5) + inv_h * (C51 * g1 + C52 * g2 + C53 * g3 + C54 * g4));
  const Vec2 y6 = y5 + g5;
  err = minv * (sys.rhs(y6) + inv_h * (C61 * g1 + C62 * g2 + C63 * g3 + C64 * g4 + C65 * g5));
  y1 = y6 + err;
}

[[noreturn]] void fail(const Asperity& asperity, const Model2Params& params, double t_s, const std::string& why) {
  std::ostringstream msg;
  msg.precision(6);
  msg << "Model 2 integrator failed for the asperity with k = " << asperity.stiffness_n_per_m
      << " N/m at v_b = " << params.belt_velocity_m_per_s << " m/s, t = " << t_s << " s: " << why;
  throw ModelError(msg.str());
}

}  // namespace

double model2_length_scale(const Asperity& asperity, const Model2Params& params, double k, double w0) {
  const double mu_max = std::max(std::abs(params.friction.static_coefficient),
                                 std::abs(params.friction.kinetic_coefficient));
  const double length_m = std::max({mu_max * std::abs(asperity.normal_load_n) / k,
                                    std::abs(asperity.initial_displacement_m),
                                    std::abs(asperity.initial_velocity_m_per_s) / w0,
                                    std::abs(params.belt_velocity_m_per_s) / w0});
  return length_m > 0.0 && std::isfinite(length_m) ? length_m : 1e-6;
}

void integrate_model2(const Asperity& asperity, const Model2Params& params, double t_end_s, Model2Integration& out) {
  const double k = asperity.stiffness_n_per_m;
  const double m = asperity.mass_kg;
  if (!(k > 0.0) || !(m > 0.0) || !std::isfinite(k) || !std::isfinite(m)) {
    std::ostringstream msg;
    msg << "Model 2 needs a positive stiffness and mass, got k = " << k << " N/m, m = " << m << " kg";
    throw InputError(msg.str());
  }
  const double tol = params.relative_tolerance;
  if (!(tol > 0.0) || !(tol < 1.0)) {
    std::ostringstream msg;
    msg << "Model 2 relative_tolerance = " << tol << " must lie in (0, 1)";
    throw InputError(msg.str());
  }
  if (!(t_end_s >= 0.0) || !std::isfinite(t_end_s)) {
    std::ostringstream msg;
    msg << "Model 2 end time " << t_end_s << " s must be finite and >= 0";
    throw InputError(msg.str());
  }

  const double w0 = std::sqrt(k / m);
  const double length_m = model2_length_scale(asperity, params, k, w0);
  const double velocity_scale = w0 * length_m;
  const double accel_scale = w0 * velocity_scale;

  const ScaledSystem sys(asperity, params, length_m);
  out.knots.clear();
  out.pieces.clear();
  out.accepted_steps = 0;
  out.oscillator_steps = 0;
  out.rejected_steps = 0;
  out.natural_frequency_rad_per_s = w0;
  auto push_knot = [&](double tau, const Vec2& y, const Vec2& f) {
    out.knots.push_back({tau / w0, y[0] * length_m, y[1] * velocity_scale, f[1] * accel_scale});
  };

  Vec2 y{asperity.initial_displacement_m / length_m, asperity.initial_velocity_m_per_s / velocity_scale};
  Vec2 f;
  Mat2 jac;
  sys.rhs_and_jacobian(y, f, jac);
  if (!y.allFinite() || !f.allFinite()) fail(asperity, params, 0.0, "non-finite initial state");
  push_knot(0.0, y, f);
  // The initial state exactly as given, not through the scaling round trip (1 ulp).
  out.knots.back().x_m = asperity.initial_displacement_m;
  out.knots.back().v_m_per_s = asperity.initial_velocity_m_per_s;

  const double tau_end = w0 * t_end_s;
  const double belt_w = params.belt_velocity_m_per_s / velocity_scale;  // v_b, scaled
  const double landing_offset = KNEE_LANDING / (params.atan_sharpness_s_per_m * velocity_scale);
  double tau = 0.0;
  // A small first step: the start (x' = 0 against a moving belt) is a fast transient.
  double h = std::min({1e-4, MAX_STEP, tau_end});
  double h_prev_accepted = 0.0;
  double err_prev_accepted = 0.0;
  bool first_step = true;
  bool last_rejected = false;
  double h_propagator = PROPAGATOR_MAX_STEP;
  std::size_t cooldown = 0;
  unsigned failures = 0;
  Vec2 y1;
  Vec2 err;

  auto accept = [&](double tau_new, const Vec2& y_new, const MotionPiece& piece) {
    tau = tau_new;
    y = y_new;
    sys.rhs_and_jacobian(y, f, jac);
    push_knot(tau, y, f);
    out.pieces.push_back(piece);
    ++out.accepted_steps;
  };

  while (tau < tau_end) {
    if (out.accepted_steps + out.rejected_steps >= MAX_STEPS) {
      fail(asperity, params, tau / w0, "step budget of " + std::to_string(MAX_STEPS) + " exhausted");
    }
    const double zeta_e = -0.5 * jac(1, 1);
    // x' heading for v_b so fast that it gets there within the shortest propagator step
    // (constant acceleration): the step would cross the atan knee (the catch of the belt,
    // an overtake), where no propagator step holds; RODAS4 takes it, with no cooldown.
    const double gap_to_belt = belt_w - y[1];
    const bool knee_ahead = gap_to_belt * f[1] > 0.0 && gap_to_belt / f[1] < PROPAGATOR_MIN_STEP;
    if (params.sliding_propagator && cooldown == 0 && !knee_ahead && zeta_e <= PROPAGATOR_ZETA_MAX &&
        std::isfinite(zeta_e)) {
      double hp = h_propagator;
      const bool reaches_end = tau + 1.01 * hp >= tau_end;
      if (reaches_end) hp = tau_end - tau;
      const PropagatorStep step = propagator_step(sys, y, f, jac, hp, tol);
      const double e = step.error;
      // The bound scales as h^(NODES + 3) (interpolation of the remainder, times h); with
      // 5 nodes e^(-1/8) is three square roots (std::pow cost ~4 % of the run).
      double fac = PROPAGATOR_MAX_GROWTH;
      if (e > 0.0) {
        if constexpr (PROPAGATOR_NODES + 3 == 8) {
          fac = 0.9 / std::sqrt(std::sqrt(std::sqrt(e)));
        } else {
          fac = 0.9 * std::pow(e, -1.0 / (PROPAGATOR_NODES + 3));
        }
      }
      if (e <= 1.0 && step.suitable) {
        MotionPiece piece{PieceKind::oscillator, step.zeta, step.centre * length_m, {}};
        for (std::size_t j = 0; j < piece.particular_m.size(); ++j) piece.particular_m[j] = step.particular[j] * length_m;
        accept(reaches_end ? tau_end : tau + hp, step.y_end, piece);
        ++out.oscillator_steps;
        failures = 0;
        h_propagator = std::min(hp * std::clamp(fac, 1.0, PROPAGATOR_MAX_GROWTH), PROPAGATOR_MAX_STEP);
        continue;
      }
      ++out.rejected_steps;
      h_propagator = hp * std::clamp(fac, 0.2, 0.9);
      if (step.suitable && h_propagator >= PROPAGATOR_MIN_STEP) continue;
      // Friction too far from linear here: RODAS4 takes over for a while.
      cooldown = PROPAGATOR_COOLDOWN << std::min(failures, 6u);
      if (step.suitable) ++failures;
      h_propagator = PROPAGATOR_MIN_STEP;
    }

    // Take the last step exactly to tau_end; stretch a step by up to 1 % rather than
    // leave a sliver behind.
    bool reaches_end = false;
    if (tau + 1.01 * h >= tau_end) {
      h = tau_end - tau;
      reaches_end = true;
    }
    if (h <= 1e-14 * std::max(1.0, tau)) {
      std::ostringstream why;
      why << "step size underflow (h = " << h / w0 << " s)";
      fail(asperity, params, tau / w0, why.str());
    }

    rodas4_step(sys, y, f, jac, h, y1, err);
    double e = error_norm(err, y, y1, tol);
    if (!std::isfinite(e) || !y1.allFinite()) e = std::numeric_limits<double>::infinity();

    // err^(1/4) as two square roots: std::pow cost ~8 % of the run.
    double fac = std::clamp(std::sqrt(std::sqrt(e)) / SAFE, 1.0 / MAX_GROWTH, MAX_SHRINK);
    if (e <= 1.0) {
      if (!first_step) {
        // Gustafsson (1994) predictive controller, as in rodas.f.
        double fac_pred = (h_prev_accepted / h) * std::sqrt(std::sqrt(e * e / err_prev_accepted)) / SAFE;
        fac_pred = std::clamp(fac_pred, 1.0 / MAX_GROWTH, MAX_SHRINK);
        fac = std::max(fac, fac_pred);
      }
      first_step = false;
      h_prev_accepted = h;
      err_prev_accepted = std::max(1e-2, e);

      accept(reaches_end ? tau_end : tau + h, y1, {zeta_e > 1.0 ? PieceKind::cubic : PieceKind::quintic});
      if (cooldown > 0) --cooldown;

      double h_new = std::min(h / fac, max_step(sys, y, jac));
      const double to_landing = time_to_knee_landing(belt_w, landing_offset, y, f);
      if (h_new > to_landing && to_landing > KNEE_LANDING_MIN_FRACTION * h) h_new = to_landing;
      if (last_rejected) h_new = std::min(h_new, h);
      last_rejected = false;
      h = h_new;
      // The propagator resumes from what RODAS4 found affordable, not less than its minimum.
      if (cooldown == 0) h_propagator = std::max(PROPAGATOR_MIN_STEP, std::min(4.0 * h, PROPAGATOR_MAX_STEP));
    } else {
      ++out.rejected_steps;
      // A rejected first step usually means a far too optimistic guess: cut hard.
      h = first_step ? 0.1 * h : h / fac;
      last_rejected = true;
    }
  }
}

Model2Integration integrate_model2(const Asperity& asperity, const Model2Params& params, double t_end_s) {
  Model2Integration out;
  integrate_model2(asperity, params, t_end_s, out);
  return out;
}

}  // namespace stengmc
