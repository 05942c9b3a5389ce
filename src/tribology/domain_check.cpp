#include "tribology/domain_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"

namespace stengmc {

namespace {

//! Halvings more than enough to reach adjacent doubles from any finite interval.
constexpr int max_halvings = 200;

//! The peak bracket must shrink to this fraction of the sample interval before the
//! tangent bound may declare the peak below l: near a resolved maximum |x'| no longer grows
//! towards the peak at that scale (it is 1/64 of a half period even at the Nyquist rate).
constexpr double bound_width_fraction = 1.0 / 64.0;

std::string seconds_text(double t_s) {
  char text[64];
  std::snprintf(text, sizeof text, "%.10g", t_s);
  return text;
}

void require_finite_displacement(double x_m, double t_s) {
  // NaN compares false with l, so unchecked it would read as "x reached l" (or not).
  if (!std::isfinite(x_m)) throw ModelError("displacement is not finite at t = " + seconds_text(t_s) + " s");
}

//! Motion state at t, refusing a non-finite displacement or velocity.
PhasePoint checked_at(const Motion& motion, double t_s, Side side = Side::right) {
  const PhasePoint p = motion.at(t_s, side);
  require_finite_displacement(p.x_m, t_s);
  if (!std::isfinite(p.v_m_per_s)) throw ModelError("velocity is not finite at t = " + seconds_text(t_s) + " s");
  return p;
}

//! First t in (lo, hi] with x(t) >= l, given x(lo) < l <= x(hi) and one crossing between.
double bisect_crossing(const Motion& motion, double lo, double hi, double length_m) {
  for (int i = 0; i < max_halvings && std::nextafter(lo, hi) < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (checked_at(motion, mid).x_m < length_m ? lo : hi) = mid;
  }
  return hi;
}

//! Exit inside (a, b) through an interior maximum, given x(a), x(b) < l and the one-sided
//! velocities start.v >= 0 >= end.v (not both 0).
std::optional<double> exit_through_peak(const Motion& motion, double a, double b, PhasePoint start, PhasePoint end,
                                        double length_m) {
  // Bisect on the sign of x'. Where x' is exactly 0 (a stick plateau) the bracket moves
  // away from the zero end, so it closes on the plateau at the top, not on a stick at
  // the start or end of the interval.
  const bool zero_is_before_peak = start.v_m_per_s == 0.0;
  double lo = a;
  double hi = b;
  PhasePoint at_lo = start;
  PhasePoint at_hi = end;
  const double bound_width = bound_width_fraction * (b - a);
  for (int i = 0; i < max_halvings && std::nextafter(lo, hi) < hi; ++i) {
    if (hi - lo <= bound_width && at_lo.v_m_per_s > 0.0 && at_hi.v_m_per_s < 0.0) {
      // x on [lo, hi] rises at most at x'(lo) before the peak or falls at most at |x'(hi)|
      // after it (|x'| not growing towards the peak on one side): x_max <= this bound.
      // Not with a stick end (x' = 0): a slip pulse next to it can be faster than both ends.
      const double x_bound = std::max(at_lo.x_m, at_hi.x_m) + (hi - lo) * std::max(at_lo.v_m_per_s, -at_hi.v_m_per_s);
      if (x_bound < length_m) return std::nullopt;
    }
    const double mid = 0.5 * (lo + hi);
    const PhasePoint p = checked_at(motion, mid);
    // x(a) < l <= x(mid) with one maximum between: exactly one crossing in (a, mid].
    if (p.x_m >= length_m) return bisect_crossing(motion, a, mid, length_m);
    if (p.v_m_per_s > 0.0 || (p.v_m_per_s == 0.0 && zero_is_before_peak)) {
      lo = mid;
      at_lo = p;
    } else {
      hi = mid;
      at_hi = p;
    }
  }
  // Closed on the maximum to adjacent doubles, with x < l at every point evaluated.
  return std::nullopt;
}

}  // namespace

namespace {

//! The scan of first_domain_exit, with the one-sided velocities at each interval's ends
//! from `start_velocity(j)` (right limit at t_j) and `end_velocity(j)` (left limit at
//! t_j+1).
template <class Start, class End>
std::optional<double> scan(const Motion& motion, std::span<const double> times_s, std::span<const double> x_m,
                           double length_m, const Start& start_velocity, const End& end_velocity) {
  if (times_s.size() != x_m.size())
    throw Error("first_domain_exit: " + std::to_string(times_s.size()) + " times but " + std::to_string(x_m.size()) +
                " displacements");
  // All samples first: an exit found early must not hide a NaN the caller would write out.
  for (std::size_t j = 0; j < x_m.size(); ++j) require_finite_displacement(x_m[j], times_s[j]);
  if (x_m.empty()) return std::nullopt;
  if (x_m[0] >= length_m) return times_s[0];
  // A motion that bounds itself below l has no exit to look for.
  if (motion.displacement_bound() < length_m) return std::nullopt;

  for (std::size_t j = 0; j + 1 < x_m.size(); ++j) {
    const double a = times_s[j];
    const double b = times_s[j + 1];
    if (x_m[j + 1] >= length_m) return bisect_crossing(motion, a, b, length_m);
    // One-sided limits: a piecewise-linear motion's slope jumps at the samples, and its
    // maxima sit at samples (checked above); within an interval its slope has one sign.
    const PhasePoint start{x_m[j], start_velocity(j)};
    const PhasePoint end{x_m[j + 1], end_velocity(j)};
    const bool rises_then_falls = start.v_m_per_s >= 0.0 && end.v_m_per_s <= 0.0 &&
                                  !(start.v_m_per_s == 0.0 && end.v_m_per_s == 0.0);
    if (!rises_then_falls) continue;
    if (const auto exit = exit_through_peak(motion, a, b, start, end, length_m)) return exit;
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> first_domain_exit(const Motion& motion, std::span<const double> times_s,
                                        std::span<const double> x_m, double length_m) {
  return scan(
      motion, times_s, x_m, length_m, [&](std::size_t j) { return checked_at(motion, times_s[j], Side::right).v_m_per_s; },
      [&](std::size_t j) { return checked_at(motion, times_s[j + 1], Side::left).v_m_per_s; });
}

std::optional<double> first_domain_exit(const Motion& motion, std::span<const double> times_s,
                                        const MotionSamples& samples, double length_m) {
  auto finite = [&](double v, std::size_t j) {
    if (!std::isfinite(v)) throw ModelError("velocity is not finite at t = " + seconds_text(times_s[j]) + " s");
    return v;
  };
  return scan(
      motion, times_s, samples.x_m, length_m, [&](std::size_t j) { return finite(samples.v_m_per_s[j], j); },
      [&](std::size_t j) { return finite(samples.v_left(j + 1), j + 1); });
}

}  // namespace stengmc
