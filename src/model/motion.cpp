#include "model/motion.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

double Motion::displacement_bound() const { return INFINITY; }

std::unique_ptr<Motion> Motion::excerpt(double /*t0_s*/, double /*t1_s*/) const { return nullptr; }

void Motion::sample(std::span<const double> times_s, bool midpoints, MotionSamples& out) const {
  const std::size_t count = times_s.size();
  out.x_m.resize(count);
  out.v_m_per_s.resize(count);
  out.v_left_m_per_s.clear();
  out.mid_x_m.resize(midpoints && count > 0 ? count - 1 : 0);
  out.mid_v_m_per_s.resize(out.mid_x_m.size());
  // Left limits are separate only at the samples that are breakpoints: walk both sorted lists.
  const std::vector<double>& kinks = breakpoints();
  auto kink = std::lower_bound(kinks.begin(), kinks.end(), count > 0 ? times_s.front() : 0.0);
  for (std::size_t j = 0; j < count; ++j) {
    const double t = times_s[j];
    const PhasePoint p = at(t, Side::right);
    out.x_m[j] = p.x_m;
    out.v_m_per_s[j] = p.v_m_per_s;
    while (kink != kinks.end() && *kink < t) ++kink;
    if (kink != kinks.end() && *kink == t) {
      if (out.v_left_m_per_s.empty()) out.v_left_m_per_s.assign(out.v_m_per_s.begin(), out.v_m_per_s.end());
      out.v_left_m_per_s[j] = at(t, Side::left).v_m_per_s;
    } else if (!out.v_left_m_per_s.empty()) {
      out.v_left_m_per_s[j] = p.v_m_per_s;
    }
    if (j + 1 < count && midpoints) {
      const PhasePoint m = at(0.5 * (t + times_s[j + 1]), Side::right);
      out.mid_x_m[j] = m.x_m;
      out.mid_v_m_per_s[j] = m.v_m_per_s;
    }
  }
}

}  // namespace stengmc
