#include "inverse/envelope_family.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace stengmc {

namespace {

// Nodes in ln beta this far apart: L is interpolated linearly in beta between them, exact
// where G is linear in A, and the rest (the first cycles, A near 1) varies slowly with beta.
constexpr double LOG_BETA_STEP = 0.05;
// Runge–Kutta steps per table step: the step (10 ns) times the envelope's fastest rate after
// the head (~1e6 1/s) is ~1e-2, so one classical step errs by ~1e-10 of L.
constexpr int SUBSTEPS = 1;
// Samples between exact exponentials when evaluating: A is interpolated geometrically in
// between (exact for an exponential decay; the curvature of L over 8 steps leaves < 1e-6).
constexpr std::size_t EXP_BLOCK = 8;

//! dL/ds = d - beta G(A) / A with A = e^{-L}.
double slope_of(const FrictionRatios& ratios, double beta, double d, double L) {
  const double a = std::exp(-L);
  const double g = a > 1e-12 ? ratios.averaged(a) / a : ratios.averaged(1e-9) / 1e-9;
  return d - beta * g;
}

}  // namespace

EnvelopeFamily::EnvelopeFamily(const FrictionRatios& ratios, const EnvelopeFamilyRange& range) : ratios_(&ratios), range_(range) {
  if (!(range.min_beta_per_s > 0.0) || !(range.max_beta_per_s >= range.min_beta_per_s) || !(range.step_s > 0.0) ||
      !(range.span_s > 0.0) || !(range.min_damping_rate_per_s >= 0.0) ||
      !(range.max_damping_rate_per_s >= range.min_damping_rate_per_s))
    throw Error("EnvelopeFamily: empty range");
  const double log_span = std::log(range.max_beta_per_s / range.min_beta_per_s);
  const std::size_t beta_count = std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(log_span / LOG_BETA_STEP)) + 1);
  for (std::size_t i = 0; i < beta_count; ++i)
    beta_nodes_.push_back(range.min_beta_per_s * std::exp(log_span * static_cast<double>(i) / static_cast<double>(beta_count - 1)));
  if (range.max_damping_rate_per_s > range.min_damping_rate_per_s)
    d_nodes_ = {range.min_damping_rate_per_s, 0.5 * (range.min_damping_rate_per_s + range.max_damping_rate_per_s),
                range.max_damping_rate_per_s};
  else
    d_nodes_ = {range.min_damping_rate_per_s};
  samples_ = static_cast<std::size_t>(std::ceil(range.span_s / range.step_s)) + 2;
  tables_.resize(beta_nodes_.size() * d_nodes_.size() * samples_);
  const double h = range.step_s / SUBSTEPS;
  for (std::size_t i = 0; i < beta_nodes_.size(); ++i)
    for (std::size_t q = 0; q < d_nodes_.size(); ++q) {
      double* L = &tables_[(i * d_nodes_.size() + q) * samples_];
      const double beta = beta_nodes_[i], d = d_nodes_[q];
      double y = 0.0;
      L[0] = 0.0;
      // Classical Runge–Kutta on L: smooth once A leaves 1, where the table is used.
      for (std::size_t j = 1; j < samples_; ++j) {
        for (int sub = 0; sub < SUBSTEPS; ++sub) {
          const double k1 = slope_of(ratios, beta, d, y);
          const double k2 = slope_of(ratios, beta, d, y + 0.5 * h * k1);
          const double k3 = slope_of(ratios, beta, d, y + 0.5 * h * k2);
          const double k4 = slope_of(ratios, beta, d, y + h * k3);
          y += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
        }
        L[j] = y;
      }
    }
}

void EnvelopeFamily::bracket_beta(double beta, std::size_t& i, double& w) const {
  beta = std::clamp(beta, beta_nodes_.front(), beta_nodes_.back());
  const double x = std::log(beta / beta_nodes_.front()) / std::log(beta_nodes_[1] / beta_nodes_[0]);
  i = std::min(static_cast<std::size_t>(std::max(0.0, x)), beta_nodes_.size() - 2);
  w = (beta - beta_nodes_[i]) / (beta_nodes_[i + 1] - beta_nodes_[i]);
}

void EnvelopeFamily::bracket_d(double d, std::size_t& q, double& w) const {
  if (d_nodes_.size() == 1) {
    q = 0;
    w = 0.0;
    return;
  }
  // Linear in d, extrapolated a little beyond the nodes (a fit may step past the prior).
  q = d <= d_nodes_[1] ? 0 : 1;
  w = (d - d_nodes_[q]) / (d_nodes_[q + 1] - d_nodes_[q]);
}


double EnvelopeFamily::log_amplitude_at(std::size_t i, double wb, std::size_t q, double wd, double s, double* dL_dbeta,
                                        double* dL_dd, double* dL_ds) const {
  const bool two_d = d_nodes_.size() > 1;
  const double* rows[4] = {row(i, q), row(i + 1, q), two_d ? row(i, q + 1) : row(i, q), two_d ? row(i + 1, q + 1) : row(i + 1, q)};
  const double x = std::max(0.0, s / range_.step_s);
  const auto j = std::min(static_cast<std::size_t>(x), samples_ - 2);
  const double f = x - static_cast<double>(j);  // > 1 beyond the table: linear extrapolation
  double a[4], slope[4];
  for (int r = 0; r < 4; ++r) {
    slope[r] = rows[r][j + 1] - rows[r][j];
    a[r] = rows[r][j] + f * slope[r];
  }
  const double lo = a[0] + wb * (a[1] - a[0]), hi = a[2] + wb * (a[3] - a[2]);
  if (dL_dbeta) *dL_dbeta = ((1.0 - wd) * (a[1] - a[0]) + wd * (a[3] - a[2])) / (beta_nodes_[i + 1] - beta_nodes_[i]);
  if (dL_dd) *dL_dd = two_d ? (hi - lo) / (d_nodes_[q + 1] - d_nodes_[q]) : 0.0;
  if (dL_ds) {
    const double slo = slope[0] + wb * (slope[1] - slope[0]), shi = slope[2] + wb * (slope[3] - slope[2]);
    *dL_ds = (slo + wd * (shi - slo)) / range_.step_s;
  }
  return lo + wd * (hi - lo);
}

double EnvelopeFamily::at(double beta, double d, double s) const {
  double a = 0.0;
  evaluate(beta, d, s, std::span<double>(&a, 1));
  return a;
}

double EnvelopeFamily::time_at(double beta, double d, double log_amplitude, double* slope, double* ds_dlnbeta,
                               double* ds_dd) const {
  std::size_t i = 0, q = 0;
  double wb = 0.0, wd = 0.0;
  bracket_beta(beta, i, wb);
  bracket_d(d, q, wd);
  // L rises monotonically with s: bisection over table steps, then the step's linear root.
  auto L = [&](double s) { return log_amplitude_at(i, wb, q, wd, s, nullptr, nullptr, nullptr); };
  std::size_t lo = 0, hi = samples_ - 1;
  double s = 0.0;
  if (log_amplitude <= 0.0) {
    s = 0.0;
  } else if (L(range_.step_s * static_cast<double>(hi)) < log_amplitude) {
    // Beyond the table: the linear extrapolation's root.
    double last_slope = 0.0;
    const double end = range_.step_s * static_cast<double>(hi);
    const double at_end = log_amplitude_at(i, wb, q, wd, end, nullptr, nullptr, &last_slope);
    s = end + (log_amplitude - at_end) / last_slope;
  } else {
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (L(range_.step_s * static_cast<double>(mid)) < log_amplitude ? lo : hi) = mid;
    }
    const double a = L(range_.step_s * static_cast<double>(lo)), b = L(range_.step_s * static_cast<double>(hi));
    s = range_.step_s * (static_cast<double>(lo) + (b > a ? (log_amplitude - a) / (b - a) : 0.0));
  }
  double dL_dbeta = 0.0, dL_dd = 0.0, dL_ds = 0.0;
  log_amplitude_at(i, wb, q, wd, s, &dL_dbeta, &dL_dd, &dL_ds);
  dL_ds = std::max(dL_ds, 1e-300);
  if (slope) *slope = dL_ds;
  // At fixed L: dL/dbeta dbeta + dL/ds ds = 0.
  if (ds_dlnbeta) *ds_dlnbeta = -dL_dbeta * beta / dL_ds;
  if (ds_dd) *ds_dd = -dL_dd / dL_ds;
  return s;
}

void EnvelopeFamily::evaluate(double beta, double d, double first_s, std::span<double> out, std::span<double> d_dlnbeta,
                              std::span<double> d_dd, std::span<double> d_ds) const {
  std::size_t i = 0, q = 0;
  double wb = 0.0, wd = 0.0;
  bracket_beta(beta, i, wb);
  bracket_d(d, q, wd);
  const bool two_d = d_nodes_.size() > 1;
  const double* rows[4] = {row(i, q), row(i + 1, q), two_d ? row(i, q + 1) : row(i, q), two_d ? row(i + 1, q + 1) : row(i + 1, q)};
  // L = c0 r0 + c1 r1 + c2 r2 + c3 r3 (bilinear in beta and d); its beta and d derivatives
  // are other combinations of the same rows.
  const double c[4] = {(1.0 - wb) * (1.0 - wd), wb * (1.0 - wd), (1.0 - wb) * wd, wb * wd};
  const double inv_dbeta = 1.0 / (beta_nodes_[i + 1] - beta_nodes_[i]);
  const double cb[4] = {-(1.0 - wd) * inv_dbeta, (1.0 - wd) * inv_dbeta, -wd * inv_dbeta, wd * inv_dbeta};
  const double inv_dd = two_d ? 1.0 / (d_nodes_[q + 1] - d_nodes_[q]) : 0.0;
  const double cd[4] = {-(1.0 - wb) * inv_dd, -wb * inv_dd, (1.0 - wb) * inv_dd, wb * inv_dd};
  const double step = range_.step_s;
  const std::size_t count = out.size();
  const bool derivatives = !d_dlnbeta.empty() || !d_dd.empty();
  // L and its derivatives at every EXP_BLOCK-th sample from the table (each sample sits at the
  // same fraction between two table entries: the table has the record's step; before s = 0
  // the envelope is 1, past the table L goes on linearly); between them A is interpolated
  // geometrically (exact for an exponential decay) and the derivatives of L linearly.
  auto combine = [&](const double* weights, std::size_t j, double f, double* per_step) {
    double v = 0.0, g = 0.0;
    for (int r = 0; r < 4; ++r) {
      const double a = rows[r][j], b = rows[r][j + 1];
      v += weights[r] * (a + f * (b - a));
      g += weights[r] * (b - a);
    }
    if (per_step) *per_step = g;
    return v;
  };
  const std::size_t nodes = (count + EXP_BLOCK - 1) / EXP_BLOCK + 1;
  thread_local std::vector<double> scratch;  // the family is shared by the threads of a calibration
  scratch.assign(4 * nodes, 0.0);
  double* L = scratch.data();
  double* Ls = L + nodes;
  double* Lb = Ls + nodes;
  double* Ld = Lb + nodes;
  const double x0 = first_s / step;
  for (std::size_t k = 0; k < nodes; ++k) {
    const double x = x0 + static_cast<double>(k * EXP_BLOCK);
    if (x <= 0.0) continue;
    const auto j = std::min(static_cast<std::size_t>(x), samples_ - 2);
    const double f = x - static_cast<double>(j);
    double per_step = 0.0;
    L[k] = combine(c, j, f, &per_step);
    Ls[k] = per_step / step;
    if (derivatives) {
      Lb[k] = combine(cb, j, f, nullptr);
      if (two_d) Ld[k] = combine(cd, j, f, nullptr);
    }
  }
  for (std::size_t k = 0; k + 1 < nodes; ++k) {
    const std::size_t begin = k * EXP_BLOCK, end = std::min(count, begin + EXP_BLOCK);
    if (begin >= end) break;
    const double ratio = std::exp(-(L[k + 1] - L[k]) / static_cast<double>(EXP_BLOCK));
    double a = std::exp(-L[k]);
    for (std::size_t m = begin; m < end; ++m) {
      const double f = static_cast<double>(m - begin) / static_cast<double>(EXP_BLOCK);
      out[m] = a;
      if (!d_ds.empty()) d_ds[m] = -a * (Ls[k] + f * (Ls[k + 1] - Ls[k]));
      if (!d_dlnbeta.empty()) d_dlnbeta[m] = -a * beta * (Lb[k] + f * (Lb[k + 1] - Lb[k]));
      if (!d_dd.empty()) d_dd[m] = -a * (Ld[k] + f * (Ld[k + 1] - Ld[k]));
      a *= ratio;
    }
  }
}

}  // namespace stengmc
