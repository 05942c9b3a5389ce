#include "inverse/onset_steps.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/constants.hpp"

namespace stengmc {

namespace {

//! The row of the least-squares solution over j = -W..W that gives the ramp's height: a cubic
//! in j plus a ramp from 0 at j = 0 to 1 at j = ramp / step.
Eigen::VectorXd step_filter(std::size_t half_window, double ramp_samples) {
  const auto w = static_cast<Eigen::Index>(half_window);
  Eigen::MatrixXd design(2 * w + 1, 5);
  for (Eigen::Index row = 0; row < design.rows(); ++row) {
    const double j = static_cast<double>(row - w);
    const double x = j / static_cast<double>(w);
    design.row(row) << 1.0, x, x * x, x * x * x, std::clamp(j / ramp_samples, 0.0, 1.0);
  }
  return design.completeOrthogonalDecomposition().pseudoInverse().row(4).transpose();
}

}  // namespace

std::vector<OnsetStep> onset_steps(const KnownDevice& device, double stiffest_n_per_m, double noise_sigma_v,
                                   const RecordGrid& grid, std::span<const double> v) {
  const double scale = device.voltage_scale_v();  // signed as sigma
  const double friction = device.sliding_friction_n();
  const double h = grid.step_s;
  const StengElement& e = device.asperity.element;
  if (!(std::abs(scale) > 0.0) || !(friction > 0.0) || !(h > 0.0) || !(stiffest_n_per_m > 0.0)) return {};
  const double ramp_s = device.asperity.mass_kg * device.model.belt_velocity_m_per_s / friction;
  if (device.circuit.load_resistance_ohm * device.circuit.load_capacitance_f > ramp_s) return {};
  // The window: at most 0.6 of the stiffest line's period across it (the cubic follows the
  // others' motion there to a few tenths of a unit at worst), with the ramp and two samples
  // after it in its second half.
  const double period_s = 2.0 * PI / device.angular_frequency(stiffest_n_per_m);
  const auto half_window = std::min(STEP_MAX_HALF_WINDOW, static_cast<std::size_t>(std::floor(0.3 * period_s / h)));
  const double ramp_samples = std::max(ramp_s / h, 1e-6);
  if (half_window < 4 || ramp_samples > static_cast<double>(half_window) - 2.0) return {};
  const std::size_t width = 2 * half_window + 1;
  if (v.size() < width + 2 * half_window) return {};
  const Eigen::VectorXd c = step_filter(half_window, ramp_samples);

  // U over R sigma w v_b: V = U / (1 - gamma U) undone.
  const double gamma = EPSILON_0 / (e.charge_density_c_per_m2 * e.effective_thickness_m);
  std::vector<double> u(v.size());
  for (std::size_t m = 0; m < v.size(); ++m) u[m] = v[m] / (1.0 + gamma * v[m]) / scale;
  // h at ramp start m + W, for each window start m.
  std::vector<double> height(v.size() - width + 1);
  for (std::size_t m = 0; m < height.size(); ++m) {
    double s = 0.0;
    for (std::size_t j = 0; j < width; ++j) s += c(static_cast<Eigen::Index>(j)) * u[m + j];
    height[m] = s;
  }
  const double height_se = std::abs(noise_sigma_v / scale) * c.norm();
  const double least = std::max(STEP_MIN_UNITS, STEP_MIN_SIGMAS * height_se);
  std::vector<std::size_t> peaks;
  // From the W-th window on: before it the window holds the record's first samples, where every
  // asperity in contact at t = 0 ramps up at once (n units, which the cubic cannot take).
  for (std::size_t m = half_window; m + 1 < height.size(); ++m) {
    if (!(height[m] >= least && height[m] >= height[m - 1] && height[m] > height[m + 1])) continue;
    // Two maxima within a window are one step (the larger).
    if (!peaks.empty() && m - peaks.back() < half_window) {
      if (height[m] > height[peaks.back()]) peaks.back() = m;
    } else {
      peaks.push_back(m);
    }
  }
  std::vector<OnsetStep> out;
  for (std::size_t m : peaks) out.push_back({grid.at(m + half_window), height[m]});
  return out;
}

}  // namespace stengmc
