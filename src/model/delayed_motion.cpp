#include "model/delayed_motion.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

DelayedMotion::DelayedMotion(std::unique_ptr<Motion> from_onset, double onset_s, double rest_displacement_m)
    : from_onset_(std::move(from_onset)), onset_s_(onset_s), rest_displacement_m_(rest_displacement_m) {
  breakpoints_.push_back(onset_s_);
  for (const double t : from_onset_->breakpoints())
    if (t > 0.0) breakpoints_.push_back(t + onset_s_);
}

PhasePoint DelayedMotion::at(double t_s, Side side) const {
  if (t_s < onset_s_ || (t_s == onset_s_ && side == Side::left)) return {rest_displacement_m_, 0.0};
  return from_onset_->at(t_s - onset_s_, side);
}

std::vector<double> DelayedMotion::fine_structure(double resolution_s) const {
  std::vector<double> out = from_onset_->fine_structure(resolution_s);
  for (double& t : out) t += onset_s_;
  return out;
}

double DelayedMotion::displacement_bound() const {
  return std::max(from_onset_->displacement_bound(), rest_displacement_m_);
}

std::unique_ptr<Motion> DelayedMotion::excerpt(double t0_s, double t1_s) const {
  // at() evaluates the inner motion at t - onset only for t >= onset: the same differences here.
  std::unique_ptr<Motion> inner = from_onset_->excerpt(std::max(0.0, t0_s - onset_s_), std::max(0.0, t1_s - onset_s_));
  if (!inner) return nullptr;
  return std::make_unique<DelayedMotion>(std::move(inner), onset_s_, rest_displacement_m_);
}

void DelayedMotion::sample(std::span<const double> times_s, bool midpoints, MotionSamples& out) const {
  const std::size_t count = times_s.size();
  const auto first_after = static_cast<std::size_t>(std::lower_bound(times_s.begin(), times_s.end(), onset_s_) - times_s.begin());
  MotionSamples after;
  if (first_after < count) {
    std::vector<double> shifted(times_s.begin() + static_cast<std::ptrdiff_t>(first_after), times_s.end());
    for (double& t : shifted) t -= onset_s_;
    from_onset_->sample(shifted, midpoints, after);
  }
  out.x_m.assign(first_after, rest_displacement_m_);
  out.v_m_per_s.assign(first_after, 0.0);
  out.x_m.insert(out.x_m.end(), after.x_m.begin(), after.x_m.end());
  out.v_m_per_s.insert(out.v_m_per_s.end(), after.v_m_per_s.begin(), after.v_m_per_s.end());
  out.v_left_m_per_s.clear();
  if (!after.v_left_m_per_s.empty()) {
    out.v_left_m_per_s.assign(first_after, 0.0);
    out.v_left_m_per_s.insert(out.v_left_m_per_s.end(), after.v_left_m_per_s.begin(), after.v_left_m_per_s.end());
  }
  out.mid_x_m.clear();
  out.mid_v_m_per_s.clear();
  if (!midpoints || count == 0) return;
  // Midpoints before the onset are at rest; the one straddling it is evaluated directly.
  const std::size_t resting = first_after == 0 ? 0 : first_after - 1;
  out.mid_x_m.assign(resting, rest_displacement_m_);
  out.mid_v_m_per_s.assign(resting, 0.0);
  if (first_after > 0 && first_after < count) {
    const PhasePoint p = at(0.5 * (times_s[first_after - 1] + times_s[first_after]));
    out.mid_x_m.push_back(p.x_m);
    out.mid_v_m_per_s.push_back(p.v_m_per_s);
  }
  out.mid_x_m.insert(out.mid_x_m.end(), after.mid_x_m.begin(), after.mid_x_m.end());
  out.mid_v_m_per_s.insert(out.mid_v_m_per_s.end(), after.mid_v_m_per_s.begin(), after.mid_v_m_per_s.end());
  if (first_after == count) {  // never in contact within the grid
    out.mid_x_m.assign(count - 1, rest_displacement_m_);
    out.mid_v_m_per_s.assign(count - 1, 0.0);
  }
}

}  // namespace stengmc
