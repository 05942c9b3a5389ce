#include "tribology/hermite_motion.hpp"

#include <algorithm>
#include <sstream>
#include <utility>

#include "core/error.hpp"

namespace stengmc {

HermiteMotion::HermiteMotion(std::vector<MotionKnot> knots) : knots_(std::move(knots)) {
  if (knots_.empty()) throw ModelError("HermiteMotion needs at least one knot");
  for (std::size_t i = 1; i < knots_.size(); ++i) {
    if (!(knots_[i].t_s > knots_[i - 1].t_s)) {
      std::ostringstream msg;
      msg << "HermiteMotion knot times must increase: t[" << i - 1 << "] = " << knots_[i - 1].t_s
          << " s, t[" << i << "] = " << knots_[i].t_s << " s";
      throw ModelError(msg.str());
    }
  }
}

std::size_t HermiteMotion::interval_of(double t_s) const {
  if (knots_.size() < 2) return 0;
  // First knot with time > t; the interval starts one before it.
  const auto it = std::upper_bound(knots_.begin(), knots_.end(), t_s,
                                   [](double t, const MotionKnot& k) { return t < k.t_s; });
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - knots_.begin() - 1, 0));
  return std::min(i, knots_.size() - 2);
}

PhasePoint HermiteMotion::on_interval(std::size_t i, double t_s) const {
  if (knots_.size() < 2) return {knots_[0].x_m, knots_[0].v_m_per_s};
  const MotionKnot& a = knots_[i];
  const MotionKnot& b = knots_[i + 1];
  const double h = b.t_s - a.t_s;
  const double s = (t_s - a.t_s) / h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  // Quintic Hermite basis on [0, 1] (value, h*slope, h^2*curvature at each end), written
  // with the end-value difference so that a constant offset in x cancels exactly.
  const double b_step = s3 * (10.0 + s * (-15.0 + 6.0 * s));        // H3 = 1 - H0
  const double b_v0 = s * (1.0 + s2 * (-6.0 + s * (8.0 - 3.0 * s))); // H1
  const double b_a0 = 0.5 * s2 * (1.0 + s * (-3.0 + s * (3.0 - s)));  // H2
  const double b_v1 = s3 * (-4.0 + s * (7.0 - 3.0 * s));             // H4
  const double b_a1 = 0.5 * s3 * (1.0 + s * (-2.0 + s));             // H5
  const double d_step = 30.0 * s2 * (1.0 + s * (-2.0 + s));          // H3'
  const double d_v0 = 1.0 + s2 * (-18.0 + s * (32.0 - 15.0 * s));    // H1'
  const double d_a0 = 0.5 * s * (2.0 + s * (-9.0 + s * (12.0 - 5.0 * s)));  // H2'
  const double d_v1 = s2 * (-12.0 + s * (28.0 - 15.0 * s));          // H4'
  const double d_a1 = 0.5 * s2 * (3.0 + s * (-8.0 + 5.0 * s));       // H5'
  const double dx = b.x_m - a.x_m;
  const double h2 = h * h;
  const double x = a.x_m + dx * b_step + h * (a.v_m_per_s * b_v0 + b.v_m_per_s * b_v1) +
                   h2 * (a.a_m_per_s2 * b_a0 + b.a_m_per_s2 * b_a1);
  const double v = dx / h * d_step + a.v_m_per_s * d_v0 + b.v_m_per_s * d_v1 +
                   h * (a.a_m_per_s2 * d_a0 + b.a_m_per_s2 * d_a1);
  return {x, v};
}

std::array<double, 5> HermiteMotion::velocity_polynomial(std::size_t i) const {
  if (knots_.size() < 2) return {knots_[0].v_m_per_s, 0.0, 0.0, 0.0, 0.0};
  const MotionKnot& a = knots_[i];
  const MotionKnot& b = knots_[i + 1];
  const double h = b.t_s - a.t_s;
  // The derivative basis of on_interval, collected by powers of s.
  const double d = (b.x_m - a.x_m) / h;
  const double v0 = a.v_m_per_s;
  const double v1 = b.v_m_per_s;
  const double ha0 = h * a.a_m_per_s2;
  const double ha1 = h * b.a_m_per_s2;
  return {v0, ha0, 30.0 * d - 18.0 * v0 - 12.0 * v1 - 4.5 * ha0 + 1.5 * ha1,
          -60.0 * d + 32.0 * v0 + 28.0 * v1 + 6.0 * ha0 - 4.0 * ha1,
          30.0 * d - 15.0 * v0 - 15.0 * v1 - 2.5 * ha0 + 2.5 * ha1};
}

PhasePoint HermiteMotion::at(double t_s, Side /*side*/) const {
  const double t0 = knots_.front().t_s;
  const double t1 = knots_.back().t_s;
  const double slack = 1e-9 * std::max(t1 - t0, std::abs(t1));
  if (!(t_s >= t0 - slack && t_s <= t1 + slack)) {
    std::ostringstream msg;
    msg << "Model 2 motion asked for t = " << t_s << " s outside its range [" << t0 << ", " << t1 << "] s";
    throw ModelError(msg.str());
  }
  const double t = std::clamp(t_s, t0, t1);
  return on_interval(interval_of(t), t);
}

}  // namespace stengmc
