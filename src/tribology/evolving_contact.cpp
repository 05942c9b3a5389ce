#include "tribology/evolving_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>
#include <sstream>
#include <string>

#include <Eigen/Core>
#include <Eigen/LU>  // fixed-size 2x2 inverse

#include "core/error.hpp"
#include "tribology/rodas4.hpp"
#include "tribology/sliding_propagator.hpp"  // error_norm, shared with the autonomous integrator

namespace stengmc {
namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

constexpr double MS = 1e-3;  // the wear rate's time unit [s]
constexpr double INF = std::numeric_limits<double>::infinity();

// Step-size control of rodas.f, as in model2_integrator.cpp.
constexpr double SAFE = 0.9;
constexpr double MAX_SHRINK = 5.0;
constexpr double MAX_GROWTH = 6.0;
// Largest step in units of 1 / (w0 sqrt(kappa_max)) (~1/25 of the shortest undamped
// period): the quintic Hermite dense output then errs by < 1e-10 of the amplitude
// (model2_integrator.cpp, MAX_STEP).
constexpr double MAX_STEP = 0.25;
constexpr std::size_t MAX_STEPS = 50'000'000;
// Most nodes of eps's grid in one integration: a step per node at least.
constexpr double MAX_MODULATION_NODES = 5e7;

//! The product of the stiffness steps at or before t [s] (1 with none).
double step_factor_at(const Asperity& a, double t_s) {
  double factor = 1.0;
  for (const StiffnessStep& s : a.stiffness_steps)
    if (s.time_s <= t_s) factor *= s.factor;
  return factor;
}

//! The largest stiffness factor any step sequence reaches from the onset on (>= 1: wear only lowers k).
double largest_step_factor(const Asperity& a) {
  double factor = step_factor_at(a, a.onset_s);
  double largest = std::max(1.0, factor);
  for (const StiffnessStep& s : a.stiffness_steps)
    if (s.time_s > a.onset_s) largest = std::max(largest, factor *= s.factor);
  return largest;
}

//! Model 2 with time-dependent coefficients in the scaled variables of model2_scaled_system.hpp
//! (tau = w0 t from the onset, u = x / L, w = x' / (w0 L), w0 = sqrt(k0 / m)):
//!   u' = w,  w' = -kappa(tau) u - 2 zeta w + l(tau) F(v_b - w0 L w) (1 + eps(tau)) / (k0 L),
//! kappa = k / k0. On one segment (between two consecutive boundaries: eps's nodes, the
//! stiffness steps, the release) kappa and eps are linear in tau and l is constant.
class EvolvingSystem {
 public:
  EvolvingSystem(const Asperity& a, const Model2Params& params, double length_m, double w0)
      : friction_(params, a.normal_load_n),
        belt_velocity_(params.belt_velocity_m_per_s),
        velocity_scale_(w0 * length_m),
        force_scale_(1.0 / (a.stiffness_n_per_m * length_m)),
        two_zeta_(params.damping_n_s_per_m / std::sqrt(a.stiffness_n_per_m * a.mass_kg)),
        wear_per_tau_(a.wear_rate_per_ms / (MS * w0)),
        tau_release_(std::isfinite(a.release_s) ? w0 * (a.release_s - a.onset_s) : INF) {}

  [[nodiscard]] double kappa(double tau) const {
    return step_factor_ * (1.0 - wear_per_tau_ * (in_contact_ ? tau : tau_release_));
  }

  [[nodiscard]] double modulation(double tau) const { return 1.0 + eps_start_ + eps_slope_ * (tau - tau_eps_start_); }

  [[nodiscard]] Vec2 rhs(double tau, const Vec2& y) const {
    double accel = -kappa(tau) * y[0] - two_zeta_ * y[1];
    if (in_contact_) accel += force_scale_ * friction_.force(belt_velocity_ - velocity_scale_ * y[1]) * modulation(tau);
    return {y[1], accel};
  }

  //! f, its Jacobian in y and its derivative in tau at (tau, y), on the current segment.
  void derivatives(double tau, const Vec2& y, Vec2& f, Mat2& jac, Vec2& f_tau) const {
    double accel = -kappa(tau) * y[0] - two_zeta_ * y[1];
    double dw = -two_zeta_;
    double dtau = in_contact_ ? step_factor_ * wear_per_tau_ * y[0] : 0.0;
    if (in_contact_) {
      double force = 0.0;
      double slope = 0.0;
      friction_.force_and_slope(belt_velocity_ - velocity_scale_ * y[1], force, slope);
      const double mod = modulation(tau);
      accel += force_scale_ * force * mod;
      dw -= force_scale_ * slope * velocity_scale_ * mod;
      dtau += force_scale_ * force * eps_slope_;
    }
    f = {y[1], accel};
    jac << 0.0, 1.0, -kappa(tau), dw;
    f_tau = {0.0, dtau};
  }

  //! The linear eps on [tau0, tau1] from eps0 to eps1.
  void set_modulation(double tau0, double eps0, double tau1, double eps1) {
    tau_eps_start_ = tau0;
    eps_start_ = eps0;
    eps_slope_ = (eps1 - eps0) / (tau1 - tau0);
  }
  void multiply_stiffness(double factor) { step_factor_ *= factor; }
  void release() {
    in_contact_ = false;
    eps_start_ = eps_slope_ = 0.0;
  }
  [[nodiscard]] bool in_contact() const { return in_contact_; }
  [[nodiscard]] double tau_release() const { return tau_release_; }

 private:
  StribeckFriction friction_;
  double belt_velocity_;
  double velocity_scale_;
  double force_scale_;
  double two_zeta_;
  double wear_per_tau_;
  double tau_release_;
  double step_factor_ = 1.0;
  bool in_contact_ = true;
  double tau_eps_start_ = 0.0;
  double eps_start_ = 0.0;
  double eps_slope_ = 0.0;
};

//! One non-autonomous RODAS4 step of size h from (tau, y) with f0, jac, f_tau there.
void rodas4_step(const EvolvingSystem& sys, double tau, const Vec2& y, const Vec2& f0, const Mat2& jac,
                 const Vec2& f_tau, double h, Vec2& y1, Vec2& err) {
  using namespace rodas4;
  const double inv_gh = 1.0 / (GAMMA * h);
  Mat2 m = -jac;
  m(0, 0) += inv_gh;
  m(1, 1) += inv_gh;
  const Mat2 minv = m.inverse();
  const double inv_h = 1.0 / h;
  const Vec2 g1 = minv * (f0 + (h * D1) * f_tau);
  const Vec2 g2 = minv * (sys.rhs(tau + STAGE2 * h, y + A21 * g1) + (C21 * inv_h) * g1 + (h * D2) * f_tau);
  const Vec2 g3 = minv * (sys.rhs(tau + STAGE3 * h, y + A31 * g1 + A32 * g2) + inv_h * (C31 * g1 + C32 * g2) +
                          (h * D3) * f_tau);
  const Vec2 g4 = minv * (sys.rhs(tau + STAGE4 * h, y + A41 * g1 + A42 * g2 + A43 * g3) +
                          inv_h * (C41 * g1 + C42 * g2 + C43 * g3) + (h * D4) * f_tau);
  const Vec2 y5 = y + A51 * g1 + A52 * g2 + A53 * g3 + A54 * g4;
  const Vec2 g5 = minv * (sys.rhs(tau + h, y5) + inv_h * (C51 * g1 + C52 * g2 + C53 * g3 + C54 * g4));
  const Vec2 y6 = y5 + g5;
  err = minv * (sys.rhs(tau + h, y6) + inv_h * (C61 * g1 + C62 * g2 + C63 * g3 + C64 * g4 + C65 * g5));
  y1 = y6 + err;
}

[[noreturn]] void fail(const Asperity& a, const Model2Params& params, double t_s, const std::string& why) {
  std::ostringstream msg;
  msg.precision(6);
  msg << "Model 2 integrator (evolving contact) failed for the asperity with k = " << a.stiffness_n_per_m
      << " N/m at v_b = " << params.belt_velocity_m_per_s << " m/s, t = " << t_s << " s after its onset: " << why;
  throw ModelError(msg.str());
}

//! The spacing of eps's grid for this asperity [s] (modulation_step_s).
double grid_step_s(const Asperity& a, const Model2Params& params) {
  const double w_max = std::sqrt(a.stiffness_n_per_m * largest_step_factor(a) / a.mass_kg);
  return modulation_step_s(correlation_time_s(params.counterface, params.belt_velocity_m_per_s), w_max);
}

}  // namespace

bool contact_evolves(const Asperity& a, const Model2Params& params) {
  return params.counterface.active() || std::isfinite(a.release_s) || a.wear_rate_per_ms != 0.0 ||
         !a.stiffness_steps.empty();
}

double largest_stiffness_n_per_m(const Asperity& a) { return a.stiffness_n_per_m * largest_step_factor(a); }

double stiffness_at(const Asperity& a, double t_s) {
  double k = a.stiffness_n_per_m * step_factor_at(a, t_s);
  if (t_s > a.onset_s) k *= 1.0 - a.wear_rate_per_ms * (std::min(t_s, a.release_s) - a.onset_s) / MS;
  return k;
}

void integrate_evolving_contact(const Asperity& asperity, const Model2Params& params, double t_end_s,
                                const CounterfaceStream& stream, Model2Integration& out) {
  const double k = asperity.stiffness_n_per_m;
  const double m = asperity.mass_kg;
  if (!(k > 0.0) || !(m > 0.0) || !std::isfinite(k) || !std::isfinite(m)) {
    std::ostringstream msg;
    msg << "Model 2 needs a positive stiffness and mass, got k = " << k << " N/m, m = " << m << " kg";
    throw InputError(msg.str());
  }
  const double tol = params.relative_tolerance;
  if (!(tol > 0.0) || !(tol < 1.0) || !(t_end_s >= 0.0) || !std::isfinite(t_end_s)) {
    std::ostringstream msg;
    msg << "Model 2 relative_tolerance = " << tol << " must lie in (0, 1) and the end time " << t_end_s
        << " s must be finite and >= 0";
    throw InputError(msg.str());
  }
  // Wear must leave a positive stiffness until the release (after it k is frozen).
  const double worn_until_s = std::min(t_end_s, asperity.release_s - asperity.onset_s);
  const double wear_left = 1.0 - asperity.wear_rate_per_ms * worn_until_s / MS;
  if (!(wear_left > 0.0)) {
    std::ostringstream why;
    why << "wear_rate_per_ms = " << asperity.wear_rate_per_ms << " wears its stiffness to zero "
        << 1.0 / asperity.wear_rate_per_ms << " ms after the onset, before its release or the end of the run";
    fail(asperity, params, worn_until_s, why.str());
  }

  const double w0 = std::sqrt(k / m);
  const double kappa_max = largest_step_factor(asperity);
  // The length scale of integrate_model2 (its error control's unit).
  const double length_m = model2_length_scale(asperity, params, k, w0);
  const double velocity_scale = w0 * length_m;
  const double accel_scale = w0 * velocity_scale;

  EvolvingSystem sys(asperity, params, length_m, w0);
  sys.multiply_stiffness(step_factor_at(asperity, asperity.onset_s));
  const double tau_end = w0 * t_end_s;

  // eps's grid (only while in contact: after the release friction is gone).
  std::optional<ModulationSequence> eps;
  double grid_tau = INF;  // the grid spacing in tau
  if (params.counterface.active()) {
    const double step = grid_step_s(asperity, params);
    const double nodes = std::min(t_end_s, asperity.release_s - asperity.onset_s) / step;
    if (!(nodes <= MAX_MODULATION_NODES)) {
      std::ostringstream msg;
      msg << "[counterface] correlation_length_m = " << params.counterface.correlation_length_m
          << " m at v_b = " << params.belt_velocity_m_per_s << " m/s samples the friction modulation every " << step
          << " s: " << nodes << " nodes for the asperity with k = " << k << " N/m, more than "
          << MAX_MODULATION_NODES << "; use a longer correlation length or a shorter run";
      throw InputError(msg.str());
    }
    eps.emplace(stream, params.counterface.friction_modulation_rms,
                correlation_time_s(params.counterface, params.belt_velocity_m_per_s), step);
    grid_tau = w0 * step;
    sys.set_modulation(0.0, eps->value(), grid_tau, eps->next_value());
  }
  // Stiffness steps after the onset, in tau.
  std::vector<std::pair<double, double>> steps;
  for (const StiffnessStep& s : asperity.stiffness_steps)
    if (s.time_s > asperity.onset_s) steps.emplace_back(w0 * (s.time_s - asperity.onset_s), s.factor);
  std::size_t next_step = 0;

  auto next_node_tau = [&]() { return eps ? static_cast<double>(eps->index() + 1) * grid_tau : INF; };
  auto segment_end = [&]() {
    double end = tau_end;
    if (sys.in_contact()) end = std::min({end, sys.tau_release(), next_node_tau()});
    if (next_step < steps.size()) end = std::min(end, steps[next_step].first);
    return end;
  };

  out.knots.clear();
  out.pieces.clear();
  if (eps) {
    // A step ends at every node of eps's grid (the grid is finer than MAX_STEP), and after
    // the release at most every MAX_STEP: room for them at once rather than by doubling,
    // which would hold the old and the new arrays together; the dense output of the one
    // asperity in turn is what a long run's peak memory is made of (docs/output-files.md).
    const double contact_s = std::min(t_end_s, asperity.release_s - asperity.onset_s);
    const double steps_expected = contact_s / grid_step_s(asperity, params) +
                                  (t_end_s - contact_s) * w0 * std::sqrt(kappa_max) / MAX_STEP +
                                  static_cast<double>(steps.size()) + 16.0;
    const auto room = static_cast<std::size_t>(1.02 * steps_expected);
    out.knots.reserve(room + 1);
    out.pieces.reserve(room);
  }
  out.accepted_steps = 0;
  out.oscillator_steps = 0;
  out.rejected_steps = 0;
  out.natural_frequency_rad_per_s = w0;
  auto push_knot = [&](double tau, const Vec2& y, const Vec2& f) {
    out.knots.push_back({tau / w0, y[0] * length_m, y[1] * velocity_scale, f[1] * accel_scale});
  };

  double tau = 0.0;
  Vec2 y{asperity.initial_displacement_m / length_m, asperity.initial_velocity_m_per_s / velocity_scale};
  Vec2 f, f_tau, y1, err;
  Mat2 jac;
  if (sys.tau_release() <= 0.0) sys.release();
  sys.derivatives(tau, y, f, jac, f_tau);
  if (!y.allFinite() || !f.allFinite()) fail(asperity, params, 0.0, "non-finite initial state");
  push_knot(0.0, y, f);
  out.knots.back().x_m = asperity.initial_displacement_m;
  out.knots.back().v_m_per_s = asperity.initial_velocity_m_per_s;

  const double max_step = MAX_STEP / std::sqrt(kappa_max);
  double h = std::min({1e-4, max_step, tau_end});
  double seg_end = segment_end();
  double h_prev_accepted = 0.0;
  double err_prev_accepted = 0.0;
  bool first_step = true;
  bool last_rejected = false;

  // Crosses the boundary at seg_end (tau is there): the next node of eps, the stiffness
  // steps, the release. True when x'' jumps there (a step, the release).
  auto cross_boundary = [&]() {
    bool jump = false;
    if (eps && sys.in_contact() && tau == next_node_tau()) {
      eps->advance();
      sys.set_modulation(tau, eps->value(), next_node_tau(), eps->next_value());
    }
    while (next_step < steps.size() && steps[next_step].first <= tau) {
      sys.multiply_stiffness(steps[next_step++].second);
      jump = true;
    }
    if (sys.in_contact() && tau >= sys.tau_release()) {
      sys.release();
      jump = true;
    }
    seg_end = segment_end();
    return jump;
  };

  while (tau < tau_end) {
    if (out.accepted_steps + out.rejected_steps >= MAX_STEPS)
      fail(asperity, params, tau / w0, "step budget of " + std::to_string(MAX_STEPS) + " exhausted");
    // Land exactly on the segment's end rather than leave a sliver (up to 1 % longer).
    double h_step = h;
    bool to_boundary = false;
    if (tau + 1.01 * h_step >= seg_end) {
      h_step = seg_end - tau;
      to_boundary = true;
    }
    // A boundary within rounding of the last knot (a node of eps a few ulps before a step
    // or the end): crossed where the knot is, no step taken.
    if (to_boundary && h_step <= 1e-12 * std::max(1.0, tau)) {
      tau = seg_end;
      const bool jump = cross_boundary();
      sys.derivatives(tau, y, f, jac, f_tau);
      out.knots.back().t_s = tau / w0;
      out.knots.back().a_m_per_s2 = f[1] * accel_scale;
      if (jump && !out.pieces.empty()) out.pieces.back().kind = PieceKind::cubic;
      continue;
    }
    if (h_step <= 1e-14 * std::max(1.0, tau)) {
      std::ostringstream why;
      why << "step size underflow (h = " << h_step / w0 << " s)";
      fail(asperity, params, tau / w0, why.str());
    }
    rodas4_step(sys, tau, y, f, jac, f_tau, h_step, y1, err);
    double e = error_norm(err, y, y1, tol);
    if (!std::isfinite(e) || !y1.allFinite()) e = INF;
    double fac = std::clamp(std::sqrt(std::sqrt(e)) / SAFE, 1.0 / MAX_GROWTH, MAX_SHRINK);
    if (e > 1.0) {
      ++out.rejected_steps;
      h = first_step ? 0.1 * h_step : h_step / fac;
      last_rejected = true;
      continue;
    }
    if (!first_step) {
      // Gustafsson (1994) predictive controller, as in rodas.f.
      double fac_pred = (h_prev_accepted / h_step) * std::sqrt(std::sqrt(e * e / err_prev_accepted)) / SAFE;
      fac = std::max(fac, std::clamp(fac_pred, 1.0 / MAX_GROWTH, MAX_SHRINK));
    }
    first_step = false;
    h_prev_accepted = h_step;
    err_prev_accepted = std::max(1e-2, e);
    const double zeta_e = -0.5 * jac(1, 1);

    tau = to_boundary ? seg_end : tau + h_step;
    y = y1;
    // x'' jumps at a stiffness step and at the release: the piece that ends there is the
    // cubic Hermite through (x, x'), the knot carries x'' of the segment that begins.
    const bool jump = to_boundary && cross_boundary();
    sys.derivatives(tau, y, f, jac, f_tau);
    push_knot(tau, y, f);
    out.pieces.push_back({jump || zeta_e > 1.0 ? PieceKind::cubic : PieceKind::quintic});
    ++out.accepted_steps;

    double h_new = std::min(h_step / fac, max_step);
    // A step cut short by a boundary says nothing against the longer one planned.
    if (to_boundary) h_new = std::max(h_new, std::min(h, max_step));
    if (last_rejected) h_new = std::min(h_new, h_step);
    last_rejected = false;
    h = h_new;
  }
  // The last knot exactly at the end (it may sit within rounding of it).
  out.knots.back().t_s = t_end_s;
}

void modulation_factors(const Asperity& a, const Model2Params& params, const CounterfaceStream& stream,
                        std::span<const double> times_s, std::vector<double>& factor) {
  factor.assign(times_s.size(), 1.0);
  if (!params.counterface.active()) return;
  const double step = grid_step_s(a, params);
  ModulationSequence eps(stream, params.counterface.friction_modulation_rms,
                         correlation_time_s(params.counterface, params.belt_velocity_m_per_s), step);
  for (std::size_t j = 0; j < times_s.size(); ++j) {
    const double t = times_s[j] - a.onset_s;
    if (t < 0.0 || t > a.release_s - a.onset_s) continue;
    const auto node = static_cast<std::uint64_t>(std::floor(t / step));
    while (eps.index() < node) eps.advance();
    const double fraction = t / step - static_cast<double>(node);
    factor[j] = 1.0 + eps.value() + fraction * (eps.next_value() - eps.value());
  }
}

}  // namespace stengmc
