#include "tribology/sampled_motion.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace stengmc {

Interpolation parse_interpolation(std::string_view text, std::string_view where) {
  if (text == "spline") return Interpolation::spline;
  if (text == "linear") return Interpolation::linear;
  throw InputError(std::string(where) + ": interpolation = \"" + std::string(text) +
                   "\" is not known; expected \"spline\" or \"linear\"");
}

std::string_view interpolation_name(Interpolation interpolation) {
  return interpolation == Interpolation::spline ? "spline" : "linear";
}

namespace {

//! Knot slopes of the not-a-knot cubic spline (de Boor, A Practical Guide to Splines,
//! ch. IV; the same tridiagonal system as scipy's CubicSpline). Continuous x'' at the
//! knots and a continuous x''' at the second and second-to-last knots.
std::vector<double> not_a_knot_slopes(const std::vector<double>& t, const std::vector<double>& x) {
  const std::size_t n = t.size();
  std::vector<double> dt(n - 1);
  std::vector<double> secant(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    dt[i] = t[i + 1] - t[i];
    secant[i] = (x[i + 1] - x[i]) / dt[i];
  }
  // Scale time to O(1) so the matrix is well conditioned whatever the sample step.
  const double scale = 1.0 / dt[0];
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * n);
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(n));
  auto at = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double a = dt[i] * scale;
    const double b = dt[i - 1] * scale;
    entries.emplace_back(at(i), at(i - 1), a);
    entries.emplace_back(at(i), at(i), 2.0 * (a + b));
    entries.emplace_back(at(i), at(i + 1), b);
    rhs[at(i)] = 3.0 * (a * secant[i - 1] + b * secant[i]);
  }
  {
    const double h0 = dt[0] * scale;
    const double h1 = dt[1] * scale;
    const double d = h0 + h1;
    entries.emplace_back(0, 0, h1);
    entries.emplace_back(0, 1, d);
    rhs[0] = ((h0 + 2.0 * d) * h1 * secant[0] + h0 * h0 * secant[1]) / d;
  }
  {
    const double h0 = dt[n - 2] * scale;  // last interval
    const double h1 = dt[n - 3] * scale;  // second to last
    const double d = h0 + h1;
    entries.emplace_back(at(n - 1), at(n - 1), h1);
    entries.emplace_back(at(n - 1), at(n - 2), d);
    rhs[at(n - 1)] = (h0 * h0 * secant[n - 3] + (2.0 * d + h0) * h1 * secant[n - 2]) / d;
  }
  Eigen::SparseMatrix<double> matrix(at(n), at(n));
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(matrix);
  if (lu.info() != Eigen::Success) throw Error("cubic spline: the not-a-knot system is singular");
  const Eigen::VectorXd slopes = lu.solve(rhs);
  return {slopes.data(), slopes.data() + slopes.size()};
}

}  // namespace

SampledMotion::SampledMotion(std::vector<double> times_s, std::vector<double> displacement_m,
                             Interpolation interpolation)
    : t_(std::move(times_s)), x_(std::move(displacement_m)), interpolation_(interpolation) {
  const std::size_t minimum = interpolation_ == Interpolation::spline ? 4 : 2;
  if (t_.size() != x_.size()) throw InputError("sampled motion: times and displacements differ in length");
  if (t_.size() < minimum)
    throw InputError("sampled motion: " + std::string(interpolation_name(interpolation_)) + " interpolation needs at least " +
                     std::to_string(minimum) + " samples, got " + std::to_string(t_.size()));
  for (std::size_t i = 1; i < t_.size(); ++i)
    if (!(t_[i] > t_[i - 1])) throw InputError("sampled motion: sample times must be strictly increasing");
  if (interpolation_ == Interpolation::spline) {
    slope_ = not_a_knot_slopes(t_, x_);
  } else {
    breakpoints_.assign(t_.begin() + 1, t_.end() - 1);  // x' jumps at every inner sample
  }
}

PhasePoint SampledMotion::at(double t_s, Side side) const {
  // Interval i with t_[i] <= t <= t_[i+1]; at a knot, `side` picks the interval.
  auto upper = side == Side::left ? std::lower_bound(t_.begin(), t_.end(), t_s)
                                  : std::upper_bound(t_.begin(), t_.end(), t_s);
  std::size_t i = upper == t_.begin() ? 0 : static_cast<std::size_t>(upper - t_.begin()) - 1;
  i = std::min(i, t_.size() - 2);
  const double h = t_[i + 1] - t_[i];
  const double s = (t_s - t_[i]) / h;
  const double dx = x_[i + 1] - x_[i];
  if (interpolation_ == Interpolation::linear) return {x_[i] + s * dx, dx / h};
  // Cubic Hermite on the interval with the spline's knot slopes.
  const double m0 = slope_[i] * h;
  const double m1 = slope_[i + 1] * h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double x = (2 * s3 - 3 * s2 + 1) * x_[i] + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * x_[i + 1] + (s3 - s2) * m1;
  const double dxds = (6 * s2 - 6 * s) * x_[i] + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * x_[i + 1] + (3 * s2 - 2 * s) * m1;
  return {x, dxds / h};
}

}  // namespace stengmc
