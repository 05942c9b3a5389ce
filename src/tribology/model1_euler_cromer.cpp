// Model 1, `euler_cromer` solver: the paper's fixed-step scheme, kept to reproduce its figures
// (MODEL.md §1). Semi-implicit (symplectic) Euler, Cromer (1981, Am. J. Phys. 49:455): the
// velocity is updated first and the new velocity moves the position, with the paper's stick
// rule: a velocity update that reaches or crosses zero is replaced by zero and the static
// friction test decides between sticking and sliding back. First order in the step.
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "tribology/model1.hpp"

namespace stengmc {

namespace {

//! Start of a straight piece of x(t): x_m + slope (t - t_s) until the next knot.
struct Knot {
  double t_s = 0.0;          //!< [s]
  double x_m = 0.0;          //!< [m]
  double slope_m_per_s = 0.0;  //!< x' on the piece that starts here [m/s]
};

//! Dense output: x piecewise linear through the scheme's steps, x' = the step's slope, since
//! x_{n+1} = x_n + h v_{n+1}. Runs of steps stuck at zero velocity share one piece.
class PiecewiseLinearMotion final : public Motion {
 public:
  PiecewiseLinearMotion(std::vector<Knot> knots, double initial_velocity)
      : knots_(std::move(knots)), initial_velocity_(initial_velocity) {
    // Interior knots only: the first is t = 0, the last the end of the grid.
    for (std::size_t i = 1; i + 1 < knots_.size(); ++i) breakpoints_.push_back(knots_[i].t_s);
  }

  [[nodiscard]] PhasePoint at(double t_s, Side side) const override {
    auto before = [](const Knot& k, double t) { return k.t_s < t; };
    auto after = [](double t, const Knot& k) { return t < k.t_s; };
    // x from the piece starting at or before t, so that x at a knot is its stored value.
    const auto right = std::upper_bound(knots_.begin(), knots_.end(), t_s, after);
    const Knot& piece = right == knots_.begin() ? knots_.front() : *(right - 1);
    const double x = piece.x_m + (t_s - piece.t_s) * piece.slope_m_per_s;
    if (side == Side::right) return {x, piece.slope_m_per_s};
    // Left limit of x': the piece ending at t; before the first step, the initial velocity.
    const auto left = std::lower_bound(knots_.begin(), knots_.end(), t_s, before);
    if (left == knots_.begin()) return {x, initial_velocity_};
    return {x, (left - 1)->slope_m_per_s};
  }

  [[nodiscard]] const std::vector<double>& breakpoints() const override { return breakpoints_; }

 private:
  std::vector<Knot> knots_;
  double initial_velocity_;
  std::vector<double> breakpoints_;
};

}  // namespace

Trajectory solve_model1_euler_cromer(const Asperity& asperity, const Model1Params& params,
                                     const TimeGrid& grid) {
  validate_model1(asperity, params, grid);
  const std::size_t substeps = params.euler_cromer_substeps;
  const double h = grid.step_s / static_cast<double>(substeps);
  const double m = asperity.mass_kg;
  const double k = asperity.stiffness_n_per_m;
  const double static_force = params.friction.static_coefficient * asperity.normal_load_n;
  const double kinetic_force = params.friction.kinetic_coefficient * asperity.normal_load_n;
  const std::size_t steps = grid.count > 0 ? (grid.count - 1) * substeps : 0;
  // Step times built from the grid so that every substeps-th one is exactly a grid time.
  auto step_time = [&](std::size_t n) {
    return grid.at(n / substeps) + static_cast<double>(n % substeps) * h;
  };
  auto sign = [](double value) { return value > 0.0 ? 1 : -1; };

  Trajectory out;
  out.x_m.resize(grid.count);
  out.v_m_per_s.resize(grid.count);
  out.friction_n.resize(grid.count);
  double x = asperity.initial_displacement_m;
  double v = asperity.initial_velocity_m_per_s;
  int direction = v > 0.0 ? 1 : (v < 0.0 ? -1 : 0);  // 0: stuck
  auto record = [&](std::size_t j, double spring_force) {
    out.x_m[j] = x;
    out.v_m_per_s[j] = v;
    // MODEL.md §1: mu_k N sign(x') while slipping, the spring force k (x0 - x) while stuck.
    out.friction_n[j] = direction != 0 ? kinetic_force * direction : spring_force;
  };
  if (grid.count > 0) {
    record(0, k * (imposed_displacement(params, asperity, 0.0) - x));
  }

  std::vector<Knot> knots;
  for (std::size_t n = 0; n < steps; ++n) {
    const double t = step_time(n);
    const double t_next = step_time(n + 1);
    const double force = k * (imposed_displacement(params, asperity, t) - x);
    if (direction == 0 && std::abs(force) > static_force) {
      direction = sign(force);
      out.events.push_back({t, 0, EventKind::slip});
    }
    if (direction != 0) {
      const double v_new = v + h * (force - kinetic_force * direction) / m;
      if (direction * v_new <= 0.0) {
        // The paper's rule: the velocity does not cross zero within a step; it stops, and
        // static friction decides whether it stays.
        v = 0.0;
        if (std::abs(force) <= static_force) {
          direction = 0;
          out.events.push_back({t_next, 0, EventKind::stick});
        } else {
          direction = sign(force);
          out.events.push_back({t_next, 0, EventKind::reversal});
        }
      } else {
        v = v_new;
      }
    } else {
      v = 0.0;
    }
    if (knots.empty() || v != 0.0 || knots.back().slope_m_per_s != 0.0) knots.push_back({t, x, v});
    x += h * v;  // Euler-Cromer: the updated velocity moves the position
    if ((n + 1) % substeps == 0) {
      record((n + 1) / substeps, k * (imposed_displacement(params, asperity, t_next) - x));
    }
  }
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;
  knots.push_back({t_end, x, v});
  out.solver_steps = steps;
  out.motion = std::make_unique<PiecewiseLinearMotion>(std::move(knots),
                                                       asperity.initial_velocity_m_per_s);
  return out;
}

}  // namespace stengmc
