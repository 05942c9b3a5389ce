// Model 1, `exact` solver (MODEL.md §1). The motion is a chain of phases:
// - stick: x = x_s, x' = 0, until |k (x0(t) - x_s)| exceeds mu_s N; with x0 = A sin(omega t + phi)
//   the exit instant solves A sin(theta) = x_s +- mu_s N / k in closed form (asin);
// - slip in direction s = +-1: m x'' + k x = k x0(t) - mu_k N s, a forced linear oscillator with
//   constant friction, solved in closed form; it ends at the first root of x', located by a scan
//   that cannot step over a root (sign changes of x' and local minima of s x') and refined
//   with TOMS 748 (Alefeld, Potra & Shi 1995, ACM TOMS 21:327) to machine precision.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "tribology/model1.hpp"

namespace stengmc {

namespace {

constexpr double INF = std::numeric_limits<double>::infinity();

//! Constants of the forced oscillator shared by every slip phase of one asperity.
struct Oscillator {
  double omega = 0.0;      //!< drive pulsation [rad/s]
  double w0 = 0.0;         //!< natural pulsation sqrt(k/m) [rad/s]
  double forced = 0.0;     //!< amplitude of the particular solution A / (1 - (omega/w0)^2) [m]
  double half_sum = 0.0;   //!< (omega + w0) / 2 [rad/s]
  double half_diff = 0.0;  //!< (omega - w0) / 2 [rad/s]
};

//! One stick or slip phase, valid from t0 until the next phase starts.
struct Phase {
  double t0 = 0.0;       //!< start [s]
  int direction = 0;     //!< 0 stuck, +-1 sign of x' while slipping
  double x_start = 0.0;  //!< x(t0) [m]
  double v_start = 0.0;  //!< x'(t0) [m/s]
  // Slip only: x(t) = forced sin(theta0 + omega tau) + offset + c1 cos(w0 tau) + c2 sin(w0 tau).
  double sin_theta0 = 0.0;  //!< sin of the drive phase omega t0 + phi
  double cos_theta0 = 0.0;  //!< cos of the drive phase omega t0 + phi
  double offset = 0.0;      //!< -mu_k N s / k [m]
  double c1 = 0.0;          //!< [m]
  double c2 = 0.0;          //!< [m]
};

//! x, x', x'' of a phase at tau = t - t0 >= 0.
struct State {
  double x = 0.0;
  double v = 0.0;
  double a = 0.0;
};

State evaluate(const Phase& p, const Oscillator& o, double tau) {
  if (p.direction == 0) return {p.x_start, 0.0, 0.0};
  const double sd = std::sin(o.omega * tau);
  const double cd = std::cos(o.omega * tau);
  const double sn = std::sin(o.w0 * tau);
  const double cn = std::cos(o.w0 * tau);
  const double sin_theta = p.sin_theta0 * cd + p.cos_theta0 * sd;
  const double homogeneous = p.c1 * cn + p.c2 * sn;
  State s;
  s.x = o.forced * sin_theta + p.offset + homogeneous;
  // x' regrouped so that every term is O(tau) with full relative accuracy near tau = 0:
  // cos(omega tau) - cos(w0 tau) = -2 sin((omega + w0) tau / 2) sin((omega - w0) tau / 2).
  // A slip from rest then has s x' > 0 just after t0 instead of rounding noise, so the search
  // for the phase end never mistakes the start for a root.
  const double cos_difference = -2.0 * std::sin(o.half_sum * tau) * std::sin(o.half_diff * tau);
  s.v = p.v_start * cn + o.forced * o.omega * (p.cos_theta0 * cos_difference - p.sin_theta0 * sd) -
        p.c1 * o.w0 * sn;
  s.a = -o.forced * o.omega * o.omega * sin_theta - o.w0 * o.w0 * homogeneous;
  return s;
}

//! Everything the phase chain needs about one asperity.
struct Model1Problem {
  Oscillator osc;
  double amplitude = 0.0;      //!< A [m]
  double phase = 0.0;          //!< phi [rad]
  double stiffness = 0.0;      //!< k [N/m]
  double static_force = 0.0;   //!< mu_s N [N]
  double kinetic_force = 0.0;  //!< mu_k N [N]
  double scan_step = 0.0;      //!< root scan step: 1/64 of the shorter period [s]
  bool resonant = false;       //!< |1 - (omega/w0)^2| < 1e-9: closed form unusable
};

Phase make_stick(double t0, double x) { return Phase{t0, 0, x, 0.0}; }

Phase make_slip(const Model1Problem& pr, double t0, double x, double v, int direction) {
  if (pr.resonant) {
    std::ostringstream message;
    message << "Model 1 exact solver: drive at resonance, |1 - (omega/w0)^2| < 1e-9 (omega = "
            << pr.osc.omega << " rad/s, w0 = " << pr.osc.w0
            << " rad/s): the closed-form slip phase does not exist; use solver = euler_cromer";
    throw ModelError(message.str());
  }
  Phase p{t0, direction, x, v};
  const double theta0 = pr.osc.omega * t0 + pr.phase;
  p.sin_theta0 = std::sin(theta0);
  p.cos_theta0 = std::cos(theta0);
  p.offset = -pr.kinetic_force * direction / pr.stiffness;
  p.c1 = x - (pr.osc.forced * p.sin_theta0 + p.offset);
  p.c2 = (v - pr.osc.forced * pr.osc.omega * p.cos_theta0) / pr.osc.w0;
  return p;
}

//! Root of f on [lo, hi] with f(lo) f(hi) <= 0, to machine precision (TOMS 748).
template <class F>
double refine_root(F f, double lo, double hi, double f_lo, double f_hi) {
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  std::uintmax_t max_iter = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      f, lo, hi, f_lo, f_hi, boost::math::tools::eps_tolerance<double>(), max_iter);
  return 0.5 * (bracket.first + bracket.second);
}

//! Duration tau > 0 of a slip phase: first root of x' after t0, or INF if none by tau_limit.
double slip_duration(const Phase& p, const Model1Problem& pr, double tau_limit) {
  const Oscillator& o = pr.osc;
  const double s = p.direction;
  auto f = [&](double tau) { return s * evaluate(p, o, tau).v; };
  auto g = [&](double tau) { return s * evaluate(p, o, tau).a; };
  // Root of s x' in (lo, hi] given s x'(hi) <= 0. Should f(lo) not be > 0 (a phase from rest
  // whose first point is still at rounding level), halve towards lo until it is.
  auto root_in = [&](double lo, double f_lo, double hi, double f_hi) {
    if (f_lo <= 0.0) {
      double trial = 0.5 * (lo + hi);
      double f_trial = f(trial);
      for (int halvings = 0; f_trial <= 0.0 && halvings < 1100; ++halvings) {
        hi = trial;
        f_hi = f_trial;
        trial = 0.5 * (lo + hi);
        f_trial = f(trial);
      }
      if (f_trial <= 0.0) return hi;  // the phase has (numerically) zero length
      lo = trial;
      f_lo = f_trial;
    }
    return refine_root(f, lo, hi, f_lo, f_hi);
  };
  // From rest, s x' = s x''(t0) tau + O(tau^2) with s x''(t0) >= 0 by the choice of s, but
  // rounding adds ~eps |A omega^2| tau. When mu_s = mu_k, s x''(t0) = 0 and that noise can fake
  // a root at tau ~ 1e-25 s; no physical slip is as short as 1e-9 of a scan step, so start there.
  double tau_a = p.v_start == 0.0 ? 1e-9 * pr.scan_step : 0.0;
  State sa = evaluate(p, o, tau_a);
  double f_a = s * sa.v;
  double g_a = s * sa.a;
  while (tau_a < tau_limit) {
    const double tau_b = tau_a + pr.scan_step;
    const State sb = evaluate(p, o, tau_b);
    const double f_b = s * sb.v;
    const double g_b = s * sb.a;
    // s x'' rising through 0 is a local minimum of s x': a root pair inside one scan step
    // would go unseen by the end-point signs, so look at the minimum itself.
    if (g_a < 0.0 && g_b > 0.0) {
      const double tau_min = refine_root(g, tau_a, tau_b, g_a, g_b);
      const double f_min = f(tau_min);
      if (f_min <= 0.0) return root_in(tau_a, f_a, tau_min, f_min);
    }
    if (f_b <= 0.0) return root_in(tau_a, f_a, tau_b, f_b);
    tau_a = tau_b;
    f_a = f_b;
    g_a = g_b;
  }
  return INF;
}

//! First instant >= t0 at which the asperity stuck at x leaves the static-friction band, with
//! the slip direction; {INF, 0} if A sin never leaves [x - mu_s N/k, x + mu_s N/k].
std::pair<double, int> stick_exit(const Model1Problem& pr, double t0, double x) {
  if (pr.amplitude == 0.0) return {INF, 0};
  const double theta_s = pr.osc.omega * t0 + pr.phase;
  // A crossing computed from asin may land a few ulps before theta_s when the stick began
  // on the band edge: that crossing is the present instant, not one period later.
  const double slack = 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(theta_s));
  auto first_after = [&](double base) {
    const double n = std::ceil((theta_s - slack - base) / (2.0 * PI));
    return std::max(theta_s, base + 2.0 * PI * n);
  };
  double theta_up = INF;    // sin rising through c_up: k (x0 - x) exceeds +mu_s N
  double theta_down = INF;  // sin falling through c_down: k (x0 - x) exceeds -mu_s N
  const double c_up = (x + pr.static_force / pr.stiffness) / pr.amplitude;
  const double c_down = (x - pr.static_force / pr.stiffness) / pr.amplitude;
  if (c_up <= -1.0) theta_up = theta_s;
  else if (c_up < 1.0) theta_up = first_after(std::asin(c_up));
  if (c_down >= 1.0) theta_down = theta_s;
  else if (c_down > -1.0) theta_down = first_after(PI - std::asin(c_down));
  if (theta_up == INF && theta_down == INF) return {INF, 0};
  const int direction = theta_up <= theta_down ? 1 : -1;
  const double theta = std::min(theta_up, theta_down);
  return {std::max(t0, (theta - pr.phase) / pr.osc.omega), direction};
}

//! Dense output: the phase chain, located by binary search on the start times.
class PhaseMotion final : public Motion {
 public:
  PhaseMotion(std::vector<Phase> phases, Oscillator osc) : phases_(std::move(phases)), osc_(osc) {
    starts_.reserve(phases_.size());
    for (const Phase& p : phases_) starts_.push_back(p.t0);
    breakpoints_.assign(starts_.begin() + 1, starts_.end());
  }

  [[nodiscard]] PhasePoint at(double t_s, Side side) const override {
    const auto it = side == Side::right ? std::upper_bound(starts_.begin(), starts_.end(), t_s)
                                        : std::lower_bound(starts_.begin(), starts_.end(), t_s);
    const std::size_t i = it == starts_.begin() ? 0 : static_cast<std::size_t>(it - starts_.begin()) - 1;
    const State s = evaluate(phases_[i], osc_, std::max(0.0, t_s - phases_[i].t0));
    return {s.x, s.v};
  }

  [[nodiscard]] const std::vector<double>& breakpoints() const override { return breakpoints_; }

 private:
  std::vector<Phase> phases_;
  Oscillator osc_;
  std::vector<double> starts_;
  std::vector<double> breakpoints_;
};

Model1Problem make_problem(const Asperity& asperity, const Model1Params& params) {
  Model1Problem pr;
  const double m = asperity.mass_kg;
  pr.stiffness = asperity.stiffness_n_per_m;
  pr.amplitude = params.drive_amplitude_m;
  pr.phase = asperity.drive_phase_rad;
  pr.static_force = params.friction.static_coefficient * asperity.normal_load_n;
  pr.kinetic_force = params.friction.kinetic_coefficient * asperity.normal_load_n;
  Oscillator& o = pr.osc;
  o.omega = params.drive_angular_frequency_rad_per_s;
  o.w0 = std::sqrt(pr.stiffness / m);
  const double detuning = 1.0 - (o.omega / o.w0) * (o.omega / o.w0);
  pr.resonant = std::abs(detuning) < 1e-9;
  o.forced = pr.resonant ? 0.0 : pr.amplitude / detuning;
  o.half_sum = 0.5 * (o.omega + o.w0);
  o.half_diff = 0.5 * (o.omega - o.w0);
  // 64 points per shortest period: x'' (a sum of two sinusoids) then changes sign at most
  // once per scan step except at near-tangencies, so no minimum of s x' is stepped over.
  pr.scan_step = 2.0 * PI / std::max(o.omega, o.w0) / 64.0;
  return pr;
}

}  // namespace

Trajectory solve_model1_exact(const Asperity& asperity, const Model1Params& params, const TimeGrid& grid) {
  validate_model1(asperity, params, grid);
  const Model1Problem pr = make_problem(asperity, params);
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;
  auto spring_force = [&](double t, double x) {
    return pr.stiffness * (imposed_displacement(params, asperity, t) - x);
  };
  auto sign = [](double value) { return value > 0.0 ? 1 : -1; };

  Trajectory out;
  std::vector<Phase> phases;
  // Initial phase: a moving asperity slides; one at rest slides only if static friction is
  // already exceeded at t = 0 (a `slip` event at 0), otherwise it starts stuck.
  const double x_init = asperity.initial_displacement_m;
  const double v_init = asperity.initial_velocity_m_per_s;
  if (v_init != 0.0) {
    phases.push_back(make_slip(pr, 0.0, x_init, v_init, sign(v_init)));
  } else if (const double f0 = spring_force(0.0, x_init); std::abs(f0) > pr.static_force) {
    phases.push_back(make_slip(pr, 0.0, x_init, 0.0, sign(f0)));
    out.events.push_back({0.0, 0, EventKind::slip});
  } else {
    phases.push_back(make_stick(0.0, x_init));
  }

  // A slip from rest always lasts a positive time; this only guards against a chain of
  // zero-length phases that rounding might still produce at a near-tangent crossing.
  std::size_t stalled = 0;
  // x' changes sign at most twice per period of the faster of drive and natural
  // oscillation: a chain far longer than that has lost its arithmetic (phases that advance
  // by an ulp) and would never end.
  const double max_phases = 8.0 * t_end * std::max(pr.osc.omega, pr.osc.w0) / (2.0 * PI) + 1000.0;
  for (;;) {
    if (static_cast<double>(phases.size()) > max_phases)
      throw ModelError("Model 1 exact solver: more than " + std::to_string(static_cast<long long>(max_phases)) +
                       " stick/slip transitions by t = " + std::to_string(phases.back().t0) +
                       " s, where at most two per period are possible; the phases no longer advance (check the drive "
                       "and the asperity's parameters)");
    const Phase current = phases.back();
    double t_next = INF;
    Phase next;
    if (current.direction == 0) {
      const auto [t_exit, direction] = stick_exit(pr, current.t0, current.x_start);
      if (!(t_exit <= t_end)) break;
      t_next = t_exit;
      out.events.push_back({t_next, 0, EventKind::slip});
      next = make_slip(pr, t_next, current.x_start, 0.0, direction);
    } else {
      const double tau = slip_duration(current, pr, t_end - current.t0);
      if (!(current.t0 + tau <= t_end)) break;
      t_next = current.t0 + tau;
      // x' = 0 here by construction; the position comes from the closed form.
      const double x = evaluate(current, pr.osc, tau).x;
      const double force = spring_force(t_next, x);
      if (std::abs(force) <= pr.static_force) {
        out.events.push_back({t_next, 0, EventKind::stick});
        next = make_stick(t_next, x);
      } else {
        out.events.push_back({t_next, 0, EventKind::reversal});
        next = make_slip(pr, t_next, x, 0.0, sign(force));
      }
    }
    stalled = t_next > current.t0 ? 0 : stalled + 1;
    if (stalled > 1000) {
      throw ModelError("Model 1 exact solver: stick/slip transitions stopped advancing at t = " +
                       std::to_string(t_next) + " s; use euler_cromer");
    }
    // A zero-length phase (slip starting the instant a stick began) is replaced, not kept,
    // so that phase start times, and hence breakpoints, stay strictly increasing.
    if (t_next == current.t0) phases.back() = next;
    else phases.push_back(next);
  }

  // Samples: walk the phases in step with the grid; closed-form evaluation, no root finding.
  out.x_m.resize(grid.count);
  out.v_m_per_s.resize(grid.count);
  out.friction_n.resize(grid.count);
  std::size_t i = 0;
  for (std::size_t j = 0; j < grid.count; ++j) {
    const double t = grid.at(j);
    while (i + 1 < phases.size() && phases[i + 1].t0 <= t) ++i;
    const Phase& p = phases[i];
    const State s = evaluate(p, pr.osc, std::max(0.0, t - p.t0));
    out.x_m[j] = s.x;
    out.v_m_per_s[j] = s.v;
    // MODEL.md §1: mu_k N sign(x') while slipping, the spring force k (x0 - x) while stuck.
    out.friction_n[j] = p.direction != 0 ? pr.kinetic_force * p.direction : spring_force(t, s.x);
  }
  out.solver_steps = phases.size();
  out.motion = std::make_unique<PhaseMotion>(std::move(phases), pr.osc);
  return out;
}

}  // namespace stengmc
