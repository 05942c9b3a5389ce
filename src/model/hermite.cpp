#include "model/hermite.hpp"

namespace stengmc {

PhasePoint quintic_hermite(const MotionKnot& a, const MotionKnot& b, double t_s) {
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

PhasePoint cubic_hermite(const MotionKnot& a, const MotionKnot& b, double t_s) {
  const double h = b.t_s - a.t_s;
  const double s = (t_s - a.t_s) / h;
  const double s2 = s * s;
  const double dx = b.x_m - a.x_m;
  // x = x_a + dx (3 s^2 - 2 s^3) + h [v_a (s - 2 s^2 + s^3) + v_b (s^3 - s^2)].
  const double x = a.x_m + dx * s2 * (3.0 - 2.0 * s) + h * (a.v_m_per_s * s * (1.0 - s) * (1.0 - s) + b.v_m_per_s * s2 * (s - 1.0));
  const double v = dx / h * 6.0 * s * (1.0 - s) + a.v_m_per_s * (1.0 - s) * (1.0 - 3.0 * s) + b.v_m_per_s * s * (3.0 * s - 2.0);
  return {x, v};
}

std::array<double, 5> cubic_hermite_velocity(const MotionKnot& a, const MotionKnot& b) {
  const double h = b.t_s - a.t_s;
  const double d = (b.x_m - a.x_m) / h;
  const double v0 = a.v_m_per_s;
  const double v1 = b.v_m_per_s;
  // x'(s) = 6 d s (1 - s) + v0 (1 - 4 s + 3 s^2) + v1 (3 s^2 - 2 s).
  return {v0, 6.0 * d - 4.0 * v0 - 2.0 * v1, -6.0 * d + 3.0 * v0 + 3.0 * v1, 0.0, 0.0};
}

std::array<double, 5> quintic_hermite_velocity(const MotionKnot& a, const MotionKnot& b) {
  const double h = b.t_s - a.t_s;
  // The derivative basis of quintic_hermite, collected by powers of s.
  const double d = (b.x_m - a.x_m) / h;
  const double v0 = a.v_m_per_s;
  const double v1 = b.v_m_per_s;
  const double ha0 = h * a.a_m_per_s2;
  const double ha1 = h * b.a_m_per_s2;
  return {v0, ha0, 30.0 * d - 18.0 * v0 - 12.0 * v1 - 4.5 * ha0 + 1.5 * ha1,
          -60.0 * d + 32.0 * v0 + 28.0 * v1 + 6.0 * ha0 - 4.0 * ha1,
          30.0 * d - 15.0 * v0 - 15.0 * v1 - 2.5 * ha0 + 2.5 * ha1};
}

}  // namespace stengmc
