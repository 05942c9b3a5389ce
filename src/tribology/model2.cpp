#include "tribology/model2.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "tribology/hermite_motion.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {
namespace {

// v_r = v_b - x' on one step of the dense output, as a quartic in s in [0, 1].
struct RelativeVelocity {
  std::array<double, 5> c;  // x'(s) = sum c[n] s^n
  double belt_velocity;
  [[nodiscard]] double operator()(double s) const {
    return belt_velocity - (c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * c[4]))));
  }
};

// Root of v_r on [sa, sb] (v_r(sa), v_r(sb) of opposite signs) by the Illinois variant of
// regula falsi (Dowell & Jarratt 1971): superlinear, and never leaves the bracket.
double locate_sign_change(const RelativeVelocity& vr, double sa, double fa, double sb, double fb) {
  int side = 0;
  for (int iter = 0; iter < 100 && (sb - sa) > 1e-15; ++iter) {
    const double sc = (fa * sb - fb * sa) / (fa - fb);
    const double fc = vr(sc);
    if (fc == 0.0) return sc;
    if ((fc < 0.0) == (fb < 0.0)) {
      sb = sc;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      sa = sc;
      fa = fc;
      if (side == +1) fb *= 0.5;
      side = +1;
    }
  }
  return 0.5 * (sa + sb);
}

// Overtake / regrip events: sign changes of v_r on the dense output. A step is skipped
// when |v_r| at its start exceeds the bound sum_{n>=1} |c_n| on the change of x' over the
// step (no zero possible: most steps); otherwise it is probed at s = 1/4, 1/2, 3/4 and its
// end, so a pair of crossings inside one step (v_r grazing zero) is still seen unless
// it is narrower than a quarter step.
std::vector<Event> find_events(const HermiteMotion& motion, double belt_velocity) {
  std::vector<Event> events;
  constexpr std::array<double, 3> PROBES{0.25, 0.5, 0.75};
  for (std::size_t i = 0; i + 1 < motion.knot_count(); ++i) {
    const RelativeVelocity vr{motion.velocity_polynomial(i), belt_velocity};
    double fa = belt_velocity - motion.knot(i).v_m_per_s;
    const double change_bound = std::abs(vr.c[1]) + std::abs(vr.c[2]) + std::abs(vr.c[3]) + std::abs(vr.c[4]);
    if (std::abs(fa) > change_bound) continue;
    const double t0 = motion.knot(i).t_s;
    const double h = motion.knot(i + 1).t_s - t0;
    double sa = 0.0;
    for (std::size_t p = 0; p <= PROBES.size(); ++p) {
      // The step end is taken from the knot itself, as the next step's start will be, so a
      // crossing exactly at a knot is counted once.
      const double sb = p < PROBES.size() ? PROBES[p] : 1.0;
      const double fb = p < PROBES.size() ? vr(sb) : belt_velocity - motion.knot(i + 1).v_m_per_s;
      if ((fa < 0.0) != (fb < 0.0)) {
        const double s = locate_sign_change(vr, sa, fa, sb, fb);
        events.push_back({t0 + s * h, 0, fb < 0.0 ? EventKind::overtake : EventKind::regrip});
      }
      sa = sb;
      fa = fb;
    }
  }
  return events;
}

}  // namespace

double model2_friction(const Model2Params& params, double normal_load_n, double relative_velocity_m_per_s) {
  return StribeckFriction(params, normal_load_n).force(relative_velocity_m_per_s);
}

double damped_natural_frequency_hz(double stiffness_n_per_m, double mass_kg, double damping_n_s_per_m) {
  const double zeta = damping_n_s_per_m / (2.0 * std::sqrt(stiffness_n_per_m * mass_kg));
  // Critically or over-damped: no oscillation, hence no spectral line.
  if (!(zeta < 1.0)) return 0.0;
  return std::sqrt(stiffness_n_per_m / mass_kg) * std::sqrt(1.0 - zeta * zeta) / (2.0 * PI);
}

Trajectory solve_model2(const Asperity& asperity, const Model2Params& params, const TimeGrid& grid) {
  if (grid.count > 0 && !(grid.step_s > 0.0)) {
    std::ostringstream msg;
    msg << "Model 2 output grid step " << grid.step_s << " s must be positive";
    throw InputError(msg.str());
  }
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;
  Model2Integration integration = integrate_model2(asperity, params, t_end);

  Trajectory out;
  out.solver_steps = integration.accepted_steps;
  out.rejected_steps = integration.rejected_steps;
  auto motion = std::make_unique<HermiteMotion>(std::move(integration.knots));

  // Samples come from the dense output rather than from steps forced onto the grid: the
  // steps are typically longer than the 10 ns output step, and forcing them down would
  // multiply the step count with no gain (the quintic's error is far below tolerance).
  const StribeckFriction friction(params, asperity.normal_load_n);
  out.x_m.resize(grid.count);
  out.v_m_per_s.resize(grid.count);
  out.friction_n.resize(grid.count);
  std::size_t interval = 0;
  const std::size_t last_interval = motion->knot_count() >= 2 ? motion->knot_count() - 2 : 0;
  for (std::size_t j = 0; j < grid.count; ++j) {
    const double t = grid.at(j);
    // The grid is increasing: walk the intervals instead of searching each time.
    while (interval < last_interval && motion->knot(interval + 1).t_s < t) ++interval;
    const PhasePoint p = motion->on_interval(interval, t);
    out.x_m[j] = p.x_m;
    out.v_m_per_s[j] = p.v_m_per_s;
    out.friction_n[j] = friction.force(params.belt_velocity_m_per_s - p.v_m_per_s);
  }

  out.events = find_events(*motion, params.belt_velocity_m_per_s);
  out.motion = std::move(motion);
  return out;
}

}  // namespace stengmc
