#include "inverse/atom_table.hpp"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "inverse/forward_atom.hpp"

namespace stengmc {

namespace {

//! 4-point Lagrange weights (and their derivatives in p) at offset p in [0, 1] from node 0
//! of nodes -1, 0, 1, 2.
void lagrange4(double p, double w[4], double dw[4]) {
  w[0] = -p * (p - 1.0) * (p - 2.0) / 6.0;
  w[1] = (p + 1.0) * (p - 1.0) * (p - 2.0) / 2.0;
  w[2] = -(p + 1.0) * p * (p - 2.0) / 2.0;
  w[3] = (p + 1.0) * p * (p - 1.0) / 6.0;
  dw[0] = -(3.0 * p * p - 6.0 * p + 2.0) / 6.0;
  dw[1] = (3.0 * p * p - 4.0 * p - 1.0) / 2.0;
  dw[2] = -(3.0 * p * p - 2.0 * p - 2.0) / 2.0;
  dw[3] = (3.0 * p * p - 1.0) / 6.0;
}

double envelope_span(const RecordGrid& grid) { return grid.at(grid.samples - 1) + 5e-6; }

// Breakaway times are known to ~20 % from the closed form; heads reach this far past it.
constexpr double BREAKAWAY_MARGIN = 1.2;

//! Nodes of a grid of ln k with `step` over [k_min, k_max], at least `fewest`.
std::size_t log_grid_points(double k_min, double k_max, double step, std::size_t fewest) {
  return std::max<std::size_t>(fewest, static_cast<std::size_t>(std::ceil(std::log(k_max / k_min) / step)) + 1);
}

double breakaway_time_of(const KnownDevice& device, double k) {
  return device.sliding_friction_n() / (k * device.model.belt_velocity_m_per_s);
}

//! Samples every head holds: the softest asperity breaks away last, and every head is
//! stored that long (on whole samples; a record shorter than that is all head).
std::size_t head_samples_of(const KnownDevice& device, const RecordGrid& grid, double k_min, const AtomTableSettings& settings) {
  const double head_end = breakaway_time_of(device, k_min) * BREAKAWAY_MARGIN + settings.head_after_breakaway_s;
  return std::min(grid.samples, static_cast<std::size_t>(std::ceil(std::max(0.0, head_end - grid.start_s) / grid.step_s)));
}

}  // namespace

AtomTableRuns atom_table_runs(const KnownDevice& device, const RecordGrid& grid, double k_min, double k_max,
                              const AtomTableSettings& settings) {
  AtomTableRuns runs;
  const std::size_t heads = log_grid_points(k_min, k_max, settings.head_log_step, 4);
  runs.full = log_grid_points(k_min, k_max, settings.tail_log_step, 6) + std::min(settings.checks, heads - 1);
  runs.heads = heads;
  runs.head_samples = head_samples_of(device, grid, k_min, settings);
  return runs;
}

// ---------------------------------------------------------------- geometry of the table

std::size_t AtomTable::tail_points() const {
  return log_grid_points(data_.min_stiffness_n_per_m, data_.max_stiffness_n_per_m, data_.settings.tail_log_step, 6);
}

std::size_t AtomTable::head_points() const {
  return log_grid_points(data_.min_stiffness_n_per_m, data_.max_stiffness_n_per_m, data_.settings.head_log_step, 4);
}

double AtomTable::breakaway_time(double k) const { return breakaway_time_of(device_, k); }

double AtomTable::equilibrium_displacement(double k) const { return device_.sliding_friction_n() / k; }

std::size_t AtomTable::blend_start(double k) const {
  const double head_end = breakaway_time(k) * BREAKAWAY_MARGIN + data_.settings.head_after_breakaway_s;
  const auto end = static_cast<std::size_t>(std::ceil(std::max(0.0, head_end - grid_.start_s) / grid_.step_s));
  return std::min(tail_start_, end) - std::min(std::min(tail_start_, end), blend_samples_);
}

void AtomTable::finish() {
  tail_start_ = head_samples_of(device_, grid_, data_.min_stiffness_n_per_m, data_.settings);
  blend_samples_ = static_cast<std::size_t>(std::ceil(data_.settings.blend_s / grid_.step_s));
  data_.head_samples = tail_start_;
}

// ---------------------------------------------------------------- construction

AtomTable::AtomTable(const KnownDevice& device, const RecordGrid& grid, double min_stiffness_n_per_m,
                     double max_stiffness_n_per_m, const AtomTableSettings& settings)
    : device_(device), grid_(grid), envelope_(device, envelope_span(grid), grid.step_s) {
  if (!(min_stiffness_n_per_m > 0.0) || !(max_stiffness_n_per_m > min_stiffness_n_per_m))
    throw InputError("atom table: the stiffness range [" + format_number(min_stiffness_n_per_m) + ", " +
                     format_number(max_stiffness_n_per_m) + "] N/m is empty");
  data_.min_stiffness_n_per_m = min_stiffness_n_per_m;
  data_.max_stiffness_n_per_m = max_stiffness_n_per_m;
  data_.settings = settings;
  finish();
  build_tails();
  make_splines();
  build_heads();
  check();
}

void AtomTable::make_splines() {
  const std::size_t points = tail_points();
  const double log_min = std::log(data_.min_stiffness_n_per_m);
  const double step = std::log(data_.max_stiffness_n_per_m / data_.min_stiffness_n_per_m) / static_cast<double>(points - 1);
  // Cubic B-splines on the uniform ln k grid (Boost.Math), end slopes estimated from the data.
  shift_spline_.emplace(data_.tail_shift_s.begin(), data_.tail_shift_s.end(), log_min, step);
  phase_spline_.emplace(data_.tail_phase_rad.begin(), data_.tail_phase_rad.end(), log_min, step);
}

AtomTable::AtomTable(const KnownDevice& device, const RecordGrid& grid, AtomTableData data)
    : device_(device), grid_(grid), data_(std::move(data)), envelope_(device, envelope_span(grid), grid.step_s) {
  const std::size_t stored_head_samples = data_.head_samples;
  finish();
  if (data_.head_samples != stored_head_samples || data_.heads.size() != head_points() * data_.head_samples ||
      data_.head_slopes.size() != data_.heads.size() ||
      data_.tail_shift_s.size() != tail_points() || data_.tail_phase_rad.size() != tail_points())
    throw InputError("the stored atom table does not match its own range and grid (damaged or another format)");
  make_splines();
}

void AtomTable::build_tails() {
  const std::size_t points = tail_points();
  data_.tail_shift_s.assign(points, 0.0);
  data_.tail_phase_rad.assign(points, 0.0);
  data_.tail_fit_error.assign(points, 0.0);
  const double log_min = std::log(data_.min_stiffness_n_per_m);
  const double step = std::log(data_.max_stiffness_n_per_m / data_.min_stiffness_n_per_m) / static_cast<double>(points - 1);
  const std::vector<double> times = grid_.times();
  const double scale = device_.voltage_scale_v() / device_.model.belt_velocity_m_per_s;  // R sigma w [V s/m]
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t j = 0; j < points; ++j) {
    try {
      const double k = std::exp(log_min + step * static_cast<double>(j));
      const std::vector<double> v = simulate_forward_atom(device_, k, times).voltage_v;
      // Fit over the tail and the cross-fade before it, where tail and head must agree.
      const std::size_t first = blend_start(k) > 50 ? blend_start(k) - 50 : 0;
      const double omega = device_.angular_frequency(k);
      const double tb = breakaway_time(k);
      // Residual of the tail model over [first, end) at corrections (de, dphi).
      auto residual = [&](double de, double dphi, Eigen::VectorXd* r, Eigen::MatrixXd* jac) {
        double sum = 0.0;
        for (std::size_t m = first; m < grid_.samples; ++m) {
          const double t = times[m];
          const double a = envelope_.at(t - tb + de);
          const double phase = omega * (t - tb) + dphi;
          const double model = scale * a * std::cos(phase);
          const double e = v[m] - model;
          sum += e * e;
          if (r) (*r)(static_cast<Eigen::Index>(m - first)) = e;
          if (jac) {
            (*jac)(static_cast<Eigen::Index>(m - first), 0) = scale * envelope_.slope(t - tb + de) * std::cos(phase);
            (*jac)(static_cast<Eigen::Index>(m - first), 1) = -scale * a * std::sin(phase);
          }
        }
        return sum;
      };
      // Coarse scan of the phase (the closed-form breakaway is close, but not to a fraction of a
      // period everywhere), then Gauss–Newton on both corrections.
      double best_phase = 0.0, best = INFINITY;
      for (int q = 0; q < 32; ++q) {
        const double dphi = -PI + 2.0 * PI * q / 32.0;
        const double s = residual(0.0, dphi, nullptr, nullptr);
        if (s < best) best = s, best_phase = dphi;
      }
      double de = 0.0, dphi = best_phase;
      const auto rows = static_cast<Eigen::Index>(grid_.samples - first);
      Eigen::VectorXd r(rows);
      Eigen::MatrixXd jac(rows, 2);
      double current = residual(de, dphi, &r, &jac);
      for (int iteration = 0; iteration < 50; ++iteration) {
        const Eigen::Vector2d delta = (jac.transpose() * jac).ldlt().solve(jac.transpose() * r);
        double trial_de = de + delta(0), trial_phase = dphi + delta(1);
        double trial = residual(trial_de, trial_phase, nullptr, nullptr);
        double shrink = 1.0;
        while (trial > current && shrink > 1e-4) {
          shrink *= 0.5;
          trial_de = de + shrink * delta(0);
          trial_phase = dphi + shrink * delta(1);
          trial = residual(trial_de, trial_phase, nullptr, nullptr);
        }
        if (!(trial < current) || current - trial < 1e-14 * current) break;
        const bool converged = std::abs(delta(1)) < 1e-10 && std::abs(delta(0)) * omega < 1e-10;
        de = trial_de;
        dphi = trial_phase;
        current = residual(de, dphi, &r, &jac);
        if (converged) break;
      }
      double norm = 0.0;
      for (std::size_t m = first; m < grid_.samples; ++m) norm += v[m] * v[m];
      data_.tail_shift_s[j] = de;
      data_.tail_phase_rad[j] = std::remainder(dphi, 2.0 * PI);
      data_.tail_fit_error[j] = std::sqrt(current / norm);
    } catch (...) {
#pragma omp critical
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  // The phase correction is continuous in k: unwrap it so the spline sees a smooth curve.
  for (std::size_t j = 1; j < points; ++j)
    data_.tail_phase_rad[j] =
        data_.tail_phase_rad[j - 1] + std::remainder(data_.tail_phase_rad[j] - data_.tail_phase_rad[j - 1], 2.0 * PI);
}

void AtomTable::build_heads() {
  const std::size_t points = head_points();
  const std::size_t h = data_.head_samples;
  data_.heads.assign(points * h, 0.0);
  data_.head_slopes.assign(points * h, 0.0);
  if (h == 0) return;
  const double log_min = std::log(data_.min_stiffness_n_per_m);
  const double step = std::log(data_.max_stiffness_n_per_m / data_.min_stiffness_n_per_m) / static_cast<double>(points - 1);
  std::vector<double> times = grid_.times();
  times.resize(h);
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t j = 0; j < points; ++j) {
    try {
      const double k = std::exp(log_min + step * static_cast<double>(j));
      const ForwardAtom atom = simulate_forward_atom(device_, k, times);
      std::copy(atom.voltage_v.begin(), atom.voltage_v.end(), data_.heads.begin() + static_cast<std::ptrdiff_t>(j * h));
      std::copy(atom.slope_v_per_s.begin(), atom.slope_v_per_s.end(),
                data_.head_slopes.begin() + static_cast<std::ptrdiff_t>(j * h));
    } catch (...) {
#pragma omp critical
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

void AtomTable::check() {
  const std::size_t points = head_points();
  const std::size_t checks = std::min(data_.settings.checks, points - 1);
  data_.check_error = 0.0;
  if (checks == 0) return;
  const double log_min = std::log(data_.min_stiffness_n_per_m);
  const double step = std::log(data_.max_stiffness_n_per_m / data_.min_stiffness_n_per_m) / static_cast<double>(points - 1);
  const std::vector<double> times = grid_.times();
  std::vector<double> errors(checks, 0.0);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t c = 0; c < checks; ++c) {
    // Midpoints of head intervals spread over the range: the worst place to interpolate.
    const std::size_t j = (points - 1) * (2 * c + 1) / (2 * checks);
    const double k = std::exp(log_min + step * (static_cast<double>(j) + 0.5));
    const std::vector<double> exact = simulate_forward_atom(device_, k, times).voltage_v;
    std::vector<double> approx(grid_.samples);
    evaluate(k, approx);
    double e = 0.0, n = 0.0;
    for (std::size_t m = 0; m < grid_.samples; ++m) e += (exact[m] - approx[m]) * (exact[m] - approx[m]), n += exact[m] * exact[m];
    errors[c] = std::sqrt(e / n);
  }
  data_.check_error = *std::max_element(errors.begin(), errors.end());
}

// ---------------------------------------------------------------- evaluation

void AtomTable::tail_parameters(double k, double& shift_s, double& phase_rad) const {
  const std::size_t points = tail_points();
  const double log_min = std::log(data_.min_stiffness_n_per_m);
  const double step = std::log(data_.max_stiffness_n_per_m / data_.min_stiffness_n_per_m) / static_cast<double>(points - 1);
  const double x = std::clamp(std::log(k), log_min, log_min + step * static_cast<double>(points - 1));
  shift_s = (*shift_spline_)(x);
  phase_rad = (*phase_spline_)(x);
}

void AtomTable::evaluate(double k, std::span<double> value, std::span<double> d_dlnk, std::span<double> d_dt) const {
  if (value.size() != grid_.samples || (!d_dlnk.empty() && d_dlnk.size() != grid_.samples) ||
      (!d_dt.empty() && d_dt.size() != grid_.samples))
    throw Error("AtomTable::evaluate: output spans must hold one value per sample");
  k = std::clamp(k, data_.min_stiffness_n_per_m, data_.max_stiffness_n_per_m);
  const bool derivative = !d_dlnk.empty();
  const bool slope = !d_dt.empty();
  const std::size_t blend_first = blend_start(k);
  const std::size_t head_end = std::min(tail_start_, blend_first + blend_samples_);

  // Tail: R sigma w A(t - tb + de) cos(omega (t - tb) + dphi).
  const double x = std::clamp(std::log(k), std::log(data_.min_stiffness_n_per_m), std::log(data_.max_stiffness_n_per_m));
  const double de = (*shift_spline_)(x), dphi = (*phase_spline_)(x);
  const double omega = device_.angular_frequency(k);
  const double tb = breakaway_time(k);
  // d/d ln k of the pieces: tb ~ 1/k, omega^2 = k/m - d^2.
  const double dtb = -tb;
  const double domega = k / (2.0 * device_.asperity.mass_kg * omega);
  const double dde = shift_spline_->prime(x), ddphi = phase_spline_->prime(x);
  const double scale = device_.voltage_scale_v() / device_.model.belt_velocity_m_per_s;
  if (blend_first < grid_.samples) {
    const double u0 = grid_.at(blend_first) - tb;  // t - tb at the first tail sample
    // The envelope table has the record's step (both constructors make it so), so every
    // sample sits at the same fraction between two table entries: one index and one weight
    // for the whole loop.
    const std::vector<double>& env = envelope_.values();
    const std::vector<double>& env_slope = envelope_.slopes();
    const double position = std::max(0.0, (u0 + de) / envelope_.step_s());
    const auto base = static_cast<std::size_t>(position);
    const double f = position - static_cast<double>(base);
    const double c_step = std::cos(omega * grid_.step_s), s_step = std::sin(omega * grid_.step_s);
    const double dphase_base = -omega * dtb + ddphi, dphase_per_s = domega;
    const double envelope_shift = dde - dtb;
    // The envelope table spans the record and more (envelope_span): no index runs past it.
    const std::size_t count = std::min(grid_.samples - blend_first, env.size() - 1 - base);
    // Blocks of 256 samples: cos/sin by rotation inside, re-seeded at each block's start
    // against round-off drift.
    constexpr std::size_t BLOCK = 256;
    for (std::size_t first = 0; first < count; first += BLOCK) {
      const std::size_t end = std::min(count, first + BLOCK);
      const double u_first = u0 + static_cast<double>(first) * grid_.step_s;
      double c = std::cos(omega * u_first + dphi), s = std::sin(omega * u_first + dphi);
      const double* e = env.data() + base + first;
      const double* es = env_slope.data() + base + first;
      double* out = value.data() + blend_first + first;
      for (std::size_t i = 0; i < end - first; ++i) {
        const double a = e[i] + f * (e[i + 1] - e[i]);
        out[i] = scale * a * c;
        if (derivative || slope) {
          const double a_slope = es[i] + f * (es[i + 1] - es[i]);
          const std::size_t m = blend_first + first + i;
          if (derivative) {
            const double u = u_first + static_cast<double>(i) * grid_.step_s;
            d_dlnk[m] = scale * (a_slope * envelope_shift * c - a * s * (dphase_per_s * u + dphase_base));
          }
          if (slope) d_dt[m] = scale * (a_slope * c - a * omega * s);
        }
        const double cn = c * c_step - s * s_step;
        s = s * c_step + c * s_step;
        c = cn;
      }
    }
  }

  // Head: cubic Lagrange in ln k over the fine grid, cross-faded into the tail.
  if (head_end == 0) return;
  const std::size_t h = data_.head_samples;
  const std::size_t hp = head_points();
  const double log_min = std::log(data_.min_stiffness_n_per_m);
  const double head_step = std::log(data_.max_stiffness_n_per_m / data_.min_stiffness_n_per_m) / static_cast<double>(hp - 1);
  const double xh = (std::log(k) - log_min) / head_step;
  const auto j = static_cast<std::size_t>(std::clamp(std::floor(xh), 1.0, static_cast<double>(hp - 3)));
  const double p = xh - static_cast<double>(j);
  double w[4], dw[4];
  lagrange4(p, w, dw);
  const double* rows[4];
  const double* slope_rows[4];
  for (int q = 0; q < 4; ++q) {
    const std::size_t offset = (j - 1 + static_cast<std::size_t>(q)) * h;
    rows[q] = data_.heads.data() + offset;
    slope_rows[q] = data_.head_slopes.data() + offset;
  }
  const std::size_t blend_length = head_end - blend_first;
  const double fade_rate = 1.0 / (static_cast<double>(blend_length + 1) * grid_.step_s);  // d fade / dt
  for (std::size_t m = 0; m < head_end; ++m) {
    const double head = w[0] * rows[0][m] + w[1] * rows[1][m] + w[2] * rows[2][m] + w[3] * rows[3][m];
    double dhead = 0.0, head_slope = 0.0;
    if (derivative) dhead = (dw[0] * rows[0][m] + dw[1] * rows[1][m] + dw[2] * rows[2][m] + dw[3] * rows[3][m]) / head_step;
    if (slope) head_slope = w[0] * slope_rows[0][m] + w[1] * slope_rows[1][m] + w[2] * slope_rows[2][m] + w[3] * slope_rows[3][m];
    if (m < blend_first) {
      value[m] = head;
      if (derivative) d_dlnk[m] = dhead;
      if (slope) d_dt[m] = head_slope;
    } else {
      const double fade = static_cast<double>(m - blend_first + 1) / static_cast<double>(blend_length + 1);
      if (slope) d_dt[m] = (1.0 - fade) * head_slope + fade * d_dt[m] + fade_rate * (value[m] - head);
      value[m] = (1.0 - fade) * head + fade * value[m];
      if (derivative) d_dlnk[m] = (1.0 - fade) * dhead + fade * d_dlnk[m];
    }
  }
}

double AtomTable::energy(double k) const {
  std::vector<double> v(grid_.samples);
  evaluate(k, v);
  double e = 0.0;
  for (double x : v) e += x * x;
  return e;
}

}  // namespace stengmc
