#include "inverse/atom_shapes.hpp"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <exception>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "tribology/model2.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

namespace {

// The reference frame the nodes are simulated in: omega0 = 1e7 rad/s (k = m omega0^2), so a
// radian is 100 ns; any other frame gives the same u(theta).
constexpr double REFERENCE_OMEGA = 1e7;
// Past the pick-up's end theta_p the table's rows (each ending its pick-up at its own
// theta_p) are not interpolated for this many of theta_p's steps between nodes, nor less
// than this many table steps: the stick is written out there instead.
constexpr double KINK_NODE_STEPS = 2.5;
constexpr double KINK_TABLE_STEPS = 1.0;
// Representations overlap by this many nodes each side of the split.
constexpr double SPLIT_OVERLAP_NODES = 3.0;

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

//! One node's motion in its reference frame: u, du/dtheta and X at theta = first + i step.
struct NodeMotion {
  std::vector<double> u, slope, x;
};

//! One node's forward run from the onset to theta = `end` [rad], in the reference frame.
class NodeRun {
 public:
  NodeRun(const KnownDevice& device, const FrictionRatios& ratios, double pi, double zeta, double end)
      : v_b_(device.model.belt_velocity_m_per_s), m_(device.asperity.mass_kg), params_(device.model) {
    Asperity a = device.asperity;
    a.stiffness_n_per_m = m_ * REFERENCE_OMEGA * REFERENCE_OMEGA;
    a.normal_load_n = pi * m_ * REFERENCE_OMEGA * v_b_ / ratios.reference();
    a.element.length_m = 1.0;  // the element plays no part in the motion
    a.onset_s = 0.0;
    a.initial_displacement_m = a.initial_velocity_m_per_s = 0.0;
    params_.damping_n_s_per_m = 2.0 * zeta * m_ * REFERENCE_OMEGA;
    asperity_ = a;
    solution_ = solve_model2_motion(a, params_, end / REFERENCE_OMEGA);
  }

  //! The motion at theta = first + i step, i < count.
  [[nodiscard]] NodeMotion sample(double first, double step, std::size_t count) const {
    std::vector<double> times(count);
    for (std::size_t i = 0; i < count; ++i) times[i] = (first + step * static_cast<double>(i)) / REFERENCE_OMEGA;
    MotionSamples s;
    solution_.motion->sample(times, false, s);
    const StribeckFriction friction(params_, asperity_.normal_load_n);
    NodeMotion out;
    out.u.resize(count);
    out.slope.resize(count);
    out.x.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double v = s.v_m_per_s[i], x = s.x_m[i];
      out.u[i] = v / v_b_;
      out.x[i] = x * REFERENCE_OMEGA / v_b_;
      // du/dtheta from the equation itself (m x'' = F - k x - c x').
      const double acceleration =
          (friction.force(v_b_ - v) - asperity_.stiffness_n_per_m * x - params_.damping_n_s_per_m * v) / m_;
      out.slope[i] = acceleration / (REFERENCE_OMEGA * v_b_);
    }
    return out;
  }

 private:
  double v_b_, m_;
  Model2Params params_;
  Asperity asperity_;
  Model2Solution solution_;
};

//! L(theta) = -ln A of the envelope in radians, dA/dtheta = -zeta A + Pi G(A), A(0) = 1:
//! on a fine step over the first 50 rad (G changes fast while A is near 1), a coarse one
//! after, until L >= 5 (A < 0.007, where G is linear in A); beyond, L grows linearly.
class ThetaEnvelope {
 public:
  ThetaEnvelope(const FrictionRatios& ratios, double pi, double zeta) {
    auto slope = [&](double L) {
      const double a = std::exp(-L);
      const double g = a > 1e-12 ? ratios.averaged(a) / a : ratios.averaged(1e-9) / 1e-9;
      return zeta - pi * g;
    };
    double y = 0.0;
    auto advance = [&](double step) {
      const double h = step / 4.0;  // 4 classical Runge–Kutta substeps per stored step
      for (int sub = 0; sub < 4; ++sub) {
        const double k1 = slope(y), k2 = slope(y + 0.5 * h * k1), k3 = slope(y + 0.5 * h * k2), k4 = slope(y + h * k3);
        y += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
      }
      return y;
    };
    fine_.push_back(0.0);
    while (static_cast<double>(fine_.size() - 1) * FINE < SWITCH) fine_.push_back(advance(FINE));
    coarse_.push_back(y);
    while (y < 5.0 && coarse_.size() < 100000) coarse_.push_back(advance(COARSE));
    if (coarse_.size() < 2) coarse_.push_back(advance(COARSE));
  }

  //! L at theta >= 0, and dL/dtheta.
  double operator()(double theta, double* slope) const {
    theta = std::max(0.0, theta);
    const std::vector<double>& t = theta < SWITCH ? fine_ : coarse_;
    const double step = theta < SWITCH ? FINE : COARSE;
    const double x = (theta < SWITCH ? theta : theta - SWITCH) / step;
    const auto i = std::min(static_cast<std::size_t>(x), t.size() - 2);
    const double f = x - static_cast<double>(i);  // > 1 past the end: linear extrapolation
    if (slope) *slope = (t[i + 1] - t[i]) / step;
    return t[i] + f * (t[i + 1] - t[i]);
  }

 private:
  static constexpr double FINE = 0.25, COARSE = 2.0, SWITCH = 50.0;  // [rad]
  std::vector<double> fine_, coarse_;
};

}  // namespace

double AtomShapes::tail_frequency_ratio(double pi, double zeta, const FrictionRatios& ratios) {
  const double effective = zeta + pi * ratios.linear_damping();
  return std::sqrt(std::max(0.0, 1.0 - effective * effective));
}

double AtomShapes::pickup_phase(double pi) { return std::asin(std::min(1.0, 1.0 / pi)); }

double AtomShapes::decay_phase(double theta, double theta_p, double theta_b) {
  return std::min(std::max(theta, 0.0), theta_p) + std::max(0.0, theta - theta_b);
}

double AtomShapes::decay_phase_rate(double theta, double theta_p, double theta_b) {
  return (theta < theta_p ? 1.0 : 0.0) + (theta > theta_b ? 1.0 : 0.0);
}

double AtomShapes::breakaway_phase(double pi, double zeta) {
  return std::asin(std::min(1.0, 1.0 / pi)) + std::sqrt(std::max(0.0, pi * pi - 1.0)) - 2.0 * zeta;
}

AtomShapes::AtomShapes(const KnownDevice& device, const FrictionRatios& ratios, const AtomShapeRange& range,
                       const AtomShapeSettings& settings)
    : ratios_(&ratios), belt_velocity_m_per_s_(device.model.belt_velocity_m_per_s) {
  if (!(range.min_pi > 0.0) || !(range.max_pi > range.min_pi) || !(range.min_zeta > 0.0) || !(range.max_zeta >= range.min_zeta))
    throw Error("AtomShapes: empty range");
  data_.range = range;
  data_.settings = settings;
  const double span = std::log(range.max_pi / range.min_pi);
  const std::size_t pis = std::max<std::size_t>(4, static_cast<std::size_t>(std::ceil(span / settings.log_pi_step)) + 1);
  for (std::size_t j = 0; j < pis; ++j)
    data_.pi_nodes.push_back(range.min_pi * std::exp(span * static_cast<double>(j) / static_cast<double>(pis - 1)));
  const std::size_t zetas = range.max_zeta > range.min_zeta ? std::max<std::size_t>(2, settings.zeta_nodes) : 1;
  const double zspan = std::log(range.max_zeta / range.min_zeta);
  for (std::size_t q = 0; q < zetas; ++q)
    data_.zeta_nodes.push_back(range.min_zeta * std::exp(zetas > 1 ? zspan * static_cast<double>(q) / static_cast<double>(zetas - 1) : 0.0));
  build(device);
  check(device);
}

AtomShapes::AtomShapes(const KnownDevice& device, const FrictionRatios& ratios, AtomShapeData data)
    : ratios_(&ratios), belt_velocity_m_per_s_(device.model.belt_velocity_m_per_s), data_(std::move(data)) {
  const std::size_t nodes = data_.pi_nodes.size() * data_.zeta_nodes.size();
  if (data_.pi_nodes.size() < 4 || data_.zeta_nodes.empty() || data_.onset_values.size() != nodes ||
      data_.breakaway_values.size() != nodes || data_.tail_log_amplitude.size() != nodes)
    throw InputError("the stored atom shapes do not match their own grid (damaged or another format)");
}

void AtomShapes::build(const KnownDevice& device) {
  const AtomShapeSettings& st = data_.settings;
  const std::size_t nz = data_.zeta_nodes.size(), np = data_.pi_nodes.size();
  const std::size_t nodes = np * nz;
  const double overlap = std::exp(SPLIT_OVERLAP_NODES * st.log_pi_step);
  const double onset_end = breakaway_phase(st.split_pi * overlap, 0.0) + st.after_breakaway + 2.0;
  data_.onset_samples = static_cast<std::size_t>(std::ceil(onset_end / st.theta_step)) + 1;
  data_.breakaway_samples = static_cast<std::size_t>(std::ceil((st.before_breakaway + st.after_breakaway + 1.0) / st.theta_step)) + 1;
  for (auto* v : {&data_.onset_values, &data_.onset_slopes, &data_.breakaway_values, &data_.breakaway_slopes})
    v->assign(nodes, {});
  data_.breakaway_share.assign(nodes, 0.0);
  data_.tail_log_amplitude.assign(nodes, 0.0);
  data_.tail_phase.assign(nodes, 0.0);
  const double step = st.theta_step;
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t n = 0; n < nodes; ++n) {
    try {
      const double pi = data_.pi_nodes[n / nz], zeta = data_.zeta_nodes[n % nz];
      const double theta_b = breakaway_phase(pi, zeta);
      const bool small = pi <= st.split_pi * overlap, large = pi >= st.split_pi / overlap;
      // One run from the onset to the end of the tail fit, sampled on the theta grid.
      const double fit_end = theta_b + st.after_breakaway + st.tail_fit_span;
      const std::size_t count = static_cast<std::size_t>(std::ceil(std::max(fit_end, onset_end) / step)) + 2;
      const NodeRun run(device, *ratios_, pi, zeta, step * static_cast<double>(count + 1));
      const NodeMotion motion = run.sample(0.0, step, count);
      const double theta_p = pickup_phase(pi);
      auto damping = [&](double theta) { return std::exp(zeta * decay_phase(theta, theta_p, theta_b)); };  // divides out the viscous decay
      auto decaying = [&](double theta) { return decay_phase_rate(theta, theta_p, theta_b); };
      if (small) {
        auto& values = data_.onset_values[n];
        auto& slopes = data_.onset_slopes[n];
        for (std::size_t i = 0; i < data_.onset_samples; ++i) {
          const double theta = step * static_cast<double>(i), g = damping(theta);
          values.push_back(motion.u[i] * g);
          slopes.push_back((motion.slope[i] + zeta * decaying(theta) * motion.u[i]) * g);
        }
      }
      if (large) {
        // The breakaway piece on its own grid psi = -before + i step (a run sampled there).
        const double first = theta_b - st.before_breakaway;
        const NodeMotion piece = run.sample(first, step, data_.breakaway_samples);
        for (std::size_t i = 0; i < data_.breakaway_samples; ++i) {
          const double theta = first + step * static_cast<double>(i), g = damping(theta);
          data_.breakaway_values[n].push_back(piece.u[i] * g);
          data_.breakaway_slopes[n].push_back((piece.slope[i] + zeta * decaying(theta) * piece.u[i]) * g);
        }
        data_.breakaway_share[n] = (piece.x[0] + 2.0 * zeta * piece.u[0]) / pi;
      }

      // The tail: (eps, phi) fitted over [psi_post - blend - 5, psi_post + tail_fit_span].
      const double fit_first = theta_b + st.after_breakaway - st.blend - 5.0;
      const auto first_i = static_cast<std::size_t>(std::ceil(fit_first / step));
      // Every 4th sample (0.2 rad): a period still holds 30 of them.
      constexpr std::size_t FIT_STRIDE = 4;
      const std::size_t rows = (count - first_i + FIT_STRIDE - 1) / FIT_STRIDE;
      // The tail's frequency: damped by c and by the friction's linear part alike.
      const double nu = tail_frequency_ratio(pi, zeta, *ratios_);
      // The amplitude where the fit starts gives eps's first guess (the envelope is monotone).
      double observed = 0.0;
      for (std::size_t i = first_i; i < std::min(count, first_i + static_cast<std::size_t>(2.0 * PI / step) + 1); ++i)
        observed = std::max(observed, std::abs(motion.u[i]));
      const ThetaEnvelope L(*ratios_, pi, zeta);
      double eps = 0.0;
      {
        const double target = -std::log(std::max(observed, 1e-300));
        double lo = 0.0, hi = 1.0;
        while (L(hi, nullptr) < target && hi < 1e7) hi *= 2.0;
        for (int it = 0; it < 100; ++it) {
          const double mid = 0.5 * (lo + hi);
          (L(mid, nullptr) < target ? lo : hi) = mid;
        }
        eps = 0.5 * (lo + hi) - (fit_first - theta_b);
      }
      auto residual = [&](double e, double ph, Eigen::VectorXd* r, Eigen::MatrixXd* jac) {
        double sum = 0.0;
        for (std::size_t k = 0; k < rows; ++k) {
          const std::size_t i = first_i + k * FIT_STRIDE;
          const double psi = step * static_cast<double>(i) - theta_b;
          double dL = 0.0;
          const double a = std::exp(-L(psi + e, &dL));
          const double phase = nu * psi + ph;
          const double res = motion.u[i] - a * std::cos(phase);
          sum += res * res;
          if (r) (*r)(static_cast<Eigen::Index>(k)) = res;
          if (jac) {
            (*jac)(static_cast<Eigen::Index>(k), 0) = -a * dL * std::cos(phase);
            (*jac)(static_cast<Eigen::Index>(k), 1) = -a * std::sin(phase);
          }
        }
        return sum;
      };
      double phase = 0.0, best = INFINITY;
      for (int qd = 0; qd < 16; ++qd) {
        const double trial = -PI + 2.0 * PI * qd / 16.0;
        const double s = residual(eps, trial, nullptr, nullptr);
        if (s < best) best = s, phase = trial;
      }
      Eigen::VectorXd r(static_cast<Eigen::Index>(rows));
      Eigen::MatrixXd jac(static_cast<Eigen::Index>(rows), 2);
      double current = residual(eps, phase, &r, &jac);
      for (int iteration = 0; iteration < 30; ++iteration) {
        const Eigen::Vector2d delta = (jac.transpose() * jac).ldlt().solve(jac.transpose() * r);
        double shrink = 1.0, trial = INFINITY;
        while (shrink > 1e-6) {
          trial = residual(eps + shrink * delta(0), phase + shrink * delta(1), nullptr, nullptr);
          if (trial < current) break;
          shrink *= 0.5;
        }
        if (!(trial < current)) break;
        eps += shrink * delta(0);
        phase += shrink * delta(1);
        const double gain = current - trial;
        current = residual(eps, phase, &r, &jac);
        if (gain < 1e-10 * current) break;
      }
      // Stored as the envelope's log amplitude where the tail starts (psi_post - blend): the
      // shift eps itself runs to ~ln(1/Pi)/zeta for light loads and moves steeply with zeta.
      // Its viscous part, zeta times the time the asperity has been decaying, is taken out so that
      // what is interpolated varies slowly with zeta (as the heads are).
      data_.tail_log_amplitude[n] = L(st.after_breakaway - st.blend + eps, nullptr) -
                                    zeta * decay_phase(theta_b + st.after_breakaway - st.blend, theta_p, theta_b);
      data_.tail_phase[n] = std::remainder(phase, 2.0 * PI);
    } catch (...) {
#pragma omp critical
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  // Phases unwrapped along Pi (interpolation must not cross a 2 pi jump).
  for (std::size_t q = 0; q < nz; ++q)
    for (std::size_t j = 1; j < np; ++j) {
      double& p = data_.tail_phase[node_index(j, q)];
      const double previous = data_.tail_phase[node_index(j - 1, q)];
      p = previous + std::remainder(p - previous, 2.0 * PI);
    }
}

ShapeWeights AtomShapes::weights(double pi, double zeta) const {
  ShapeWeights w;
  const auto& pn = data_.pi_nodes;
  const auto& zn = data_.zeta_nodes;
  w.zeta = zeta;
  double pi_used = pi;
  if (pi < pn.front()) {
    // Far from the belt's velocity the friction is constant and the shape scales with Pi.
    w.scale = pi / pn.front();
    pi_used = pn.front();
  }
  pi_used = std::min(pi_used, pn.back());
  w.pi = pi_used;
  const double step = std::log(pn[1] / pn[0]);
  const double xh = std::log(pi_used / pn[0]) / step;
  const auto j = static_cast<std::size_t>(std::clamp(std::floor(xh), 1.0, static_cast<double>(pn.size() - 3)));
  const double p = xh - static_cast<double>(j);
  double lw[4], ldw[4];
  lagrange4(p, lw, ldw);
  std::size_t q = 0;
  double wz = 0.0, zstep = 1.0;
  if (zn.size() > 1) {
    zstep = std::log(zn[1] / zn[0]);
    const double xq = std::log(zeta / zn[0]) / zstep;
    q = static_cast<std::size_t>(std::clamp(std::floor(xq), 0.0, static_cast<double>(zn.size() - 2)));
    wz = std::clamp(xq - static_cast<double>(q), -0.5, 1.5);  // a little extrapolation at the ends
  }
  const std::size_t q1 = zn.size() > 1 ? q + 1 : q;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 2; ++b) {
      const int slot = 2 * a + b;
      const double zw = b == 0 ? 1.0 - wz : wz;
      w.node[slot] = node_index(j - 1 + static_cast<std::size_t>(a), b == 0 ? q : q1);
      w.w[slot] = lw[a] * zw;
      w.w_lnpi[slot] = ldw[a] / step * zw;
      w.w_lnzeta[slot] = zn.size() > 1 ? lw[a] * (b == 0 ? -1.0 : 1.0) / zstep : 0.0;
    }
  if (w.scale < 1.0)
    for (double& x : w.w_lnpi) x = 0.0;  // the scaled shape: d/d ln Pi is u itself (head())
  w.small = pi_used < data_.settings.split_pi;
  w.theta_b = breakaway_phase(pi_used, zeta);
  w.theta_p = pickup_phase(pi_used);
  const double root = std::sqrt(std::max(0.0, pi_used * pi_used - 1.0));
  // d theta_b / d ln Pi = Pi (d/dPi)(asin(1/Pi) + sqrt(Pi^2 - 1)) = sqrt(Pi^2 - 1) for Pi > 1.
  w.theta_b_lnpi = w.scale < 1.0 ? 0.0 : root;
  w.theta_b_lnzeta = -2.0 * zeta;
  for (int s = 0; s < 8; ++s) {
    const std::size_t n = w.node[s];
    w.log_amplitude += w.w[s] * data_.tail_log_amplitude[n];
    w.phi += w.w[s] * data_.tail_phase[n];
    w.log_amplitude_lnpi += w.w_lnpi[s] * data_.tail_log_amplitude[n];
    w.phi_lnpi += w.w_lnpi[s] * data_.tail_phase[n];
    w.log_amplitude_lnzeta += w.w_lnzeta[s] * data_.tail_log_amplitude[n];
    w.phi_lnzeta += w.w_lnzeta[s] * data_.tail_phase[n];
    if (!w.small) w.breakaway_share += w.w[s] * data_.breakaway_share[n];
  }
  {
    // The viscous part of the tail's log amplitude, taken out at build (see build()).
    const double start = w.theta_b + data_.settings.after_breakaway - data_.settings.blend;
    const double g = decay_phase(start, w.theta_p, w.theta_b);
    const double root1 = std::sqrt(std::max(0.0, pi_used * pi_used - 1.0));
    const double pickup_lnpi = pi_used > 1.0 && w.scale >= 1.0 ? -1.0 / root1 : 0.0;
    w.log_amplitude += zeta * g;
    w.log_amplitude_lnpi += zeta * pickup_lnpi;
    w.log_amplitude_lnzeta += zeta * g;
  }
  if (w.scale < 1.0) {
    // The tail scales as the head: its log amplitude drops by ln(scale), one for one in ln Pi.
    w.log_amplitude -= std::log(w.scale);
    w.log_amplitude_lnpi = -1.0;
  }
  return w;
}

ShapePoint AtomShapes::head(const ShapeWeights& w, double theta) const {
  const AtomShapeSettings& st = data_.settings;
  const double step = st.theta_step;
  ShapePoint out;
  if (theta < 0.0) return out;
  // Interpolates the rows of `values`/`slopes` at coordinate `x` (>= 0) from their first sample.
  auto rows = [&](const std::vector<std::vector<double>>& values, const std::vector<std::vector<double>>& slopes, double x,
                   double& value, double& d_lnpi, double& d_lnzeta, double& d_x) {
    const double position = x / step;
    const std::size_t last = values[w.node[0]].size() - 1;
    const auto i = std::min(static_cast<std::size_t>(std::max(0.0, position)), last - 1);
    const double t = std::clamp(position - static_cast<double>(i), 0.0, 1.0);
    const double t2 = t * t, t3 = t2 * t;
    const double h00 = 2 * t3 - 3 * t2 + 1, h10 = (t3 - 2 * t2 + t) * step, h01 = -2 * t3 + 3 * t2, h11 = (t3 - t2) * step;
    const double d00 = (6 * t2 - 6 * t) / step, d10 = 3 * t2 - 4 * t + 1, d01 = (-6 * t2 + 6 * t) / step, d11 = 3 * t2 - 2 * t;
    value = d_lnpi = d_lnzeta = d_x = 0.0;
    for (int s = 0; s < 8; ++s) {
      if (w.w[s] == 0.0 && w.w_lnpi[s] == 0.0 && w.w_lnzeta[s] == 0.0) continue;
      const double* v = values[w.node[s]].data();
      const double* g = slopes[w.node[s]].data();
      const double val = h00 * v[i] + h10 * g[i] + h01 * v[i + 1] + h11 * g[i + 1];
      const double der = d00 * v[i] + d10 * g[i] + d01 * v[i + 1] + d11 * g[i + 1];
      value += w.w[s] * val;
      d_lnpi += w.w_lnpi[s] * val;
      d_lnzeta += w.w_lnzeta[s] * val;
      d_x += w.w[s] * der;
    }
  };
  const double psi = theta - w.theta_b;
  // The viscous decay divided out at build: e^{-zeta g}, g = min(theta, theta_p) + max(0, psi),
  // the time the asperity has moved relative to the belt.
  const double theta_p = w.theta_p;
  const double g = decay_phase(theta, theta_p, w.theta_b);
  const double g_theta = decay_phase_rate(theta, theta_p, w.theta_b);
  const double root = std::sqrt(std::max(0.0, w.pi * w.pi - 1.0));
  const double g_lnpi = (theta >= theta_p && w.pi > 1.0 && w.scale >= 1.0 ? -1.0 / root : 0.0) -
                        (psi > 0.0 ? w.theta_b_lnpi : 0.0);
  const double g_lnzeta = psi > 0.0 ? -w.theta_b_lnzeta : 0.0;
  auto damped = [&](double value, double d_lnpi, double d_lnzeta, double d_theta, bool breakaway_frame) {
    const double decay = std::exp(-w.zeta * g);
    // In the breakaway frame the rows hold functions of psi: at fixed theta, psi moves with theta_b.
    const double lnpi = d_lnpi - (breakaway_frame ? d_theta * w.theta_b_lnpi : 0.0);
    const double lnzeta = d_lnzeta - (breakaway_frame ? d_theta * w.theta_b_lnzeta : 0.0);
    out.u = decay * value;
    out.u_theta = decay * (d_theta - w.zeta * g_theta * value);
    out.u_lnpi = decay * (lnpi - w.zeta * g_lnpi * value);
    out.u_lnzeta = decay * (lnzeta - w.zeta * (g + g_lnzeta) * value);
  };
  double value = 0.0, d_lnpi = 0.0, d_lnzeta = 0.0, d_x = 0.0;
  // The pick-up (Pi > 1): a free oscillation under the constant friction F_s from rest,
  // u = Pi e^{-zeta theta} sin(nu theta) / nu, until it reaches the belt's velocity at
  // theta_p, a kink the table cannot follow (it moves with Pi); and just past it, where the
  // neighbouring nodes' rows still hold their own kinks, the stick written out.
  const bool kinked = w.pi > 1.0 && w.scale >= 1.0;
  const double kink_window =
      kinked ? std::max(KINK_TABLE_STEPS * step, KINK_NODE_STEPS * data_.settings.log_pi_step / std::max(root, 1e-3)) : 0.0;
  // (Capped at the breakaway: near Pi = 1 the stick is shorter than the window, and the kink
  // weaker in proportion, sqrt(Pi^2 - 1), so the table's rows may take it over there.)
  const double stick_end = w.small ? std::min(theta_p + kink_window, w.theta_b) : w.theta_b - st.before_breakaway;
  if (kinked && theta < theta_p) {
    const double nu = std::sqrt(std::max(0.0, 1.0 - w.zeta * w.zeta));
    const double decay = std::exp(-w.zeta * theta), sine = std::sin(nu * theta), cosine = std::cos(nu * theta);
    out.u = w.pi * decay * sine / nu;
    out.u_theta = w.pi * decay * (cosine - w.zeta * sine / nu);
    out.u_lnpi = out.u;
    out.u_lnzeta = -w.zeta * theta * out.u;
  } else if (kinked && theta < stick_end) {
    // Carried by the belt, with the creep of the friction's regularisation at the force share
    // y = (X + 2 zeta u) / Pi, X grown from its pick-up value Pi (1 - cos theta_p) at the belt's
    // rate, linear in theta up to the share the breakaway piece starts at (large Pi).
    const double start_share = (w.pi * (1.0 - std::cos(theta_p)) + 2.0 * w.zeta) / w.pi;
    const double rate = w.small ? 1.0 / w.pi : (w.breakaway_share - start_share) / (stick_end - theta_p);
    const double y = start_share + rate * (theta - theta_p);
    const double v_b = belt_velocity_m_per_s_;
    const double dy = 1e-7;
    const double creep = ratios_->creep_velocity(y);
    out.u = 1.0 - creep / v_b;
    out.u_theta = -(ratios_->creep_velocity(y + dy) - creep) / dy * rate / v_b;
  } else if (w.small) {
    rows(data_.onset_values, data_.onset_slopes, theta, value, d_lnpi, d_lnzeta, d_x);
    damped(value, d_lnpi, d_lnzeta, d_x, false);
  } else {
    rows(data_.breakaway_values, data_.breakaway_slopes, psi + st.before_breakaway, value, d_lnpi, d_lnzeta, d_x);
    damped(value, d_lnpi, d_lnzeta, d_x, true);
  }
  if (w.scale < 1.0) {
    // Below the smallest node the shape is proportional to Pi.
    out.u *= w.scale;
    out.u_theta *= w.scale;
    out.u_lnzeta *= w.scale;
    out.u_lnpi = out.u;
  }
  return out;
}

void AtomShapes::check(const KnownDevice& device) {
  // Midpoints of the Pi grid spread over the range, at a mid zeta: compared with a run there.
  const std::size_t np = data_.pi_nodes.size();
  constexpr std::size_t CHECKS = 8;
  std::vector<double> errors(CHECKS, 0.0);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t c = 0; c < CHECKS; ++c) {
    const std::size_t j = 1 + (np - 3) * (2 * c + 1) / (2 * CHECKS);
    const double pi = std::sqrt(data_.pi_nodes[j] * data_.pi_nodes[j + 1]);
    const double zeta = std::sqrt(data_.zeta_nodes.front() * data_.zeta_nodes.back());
    const ShapeWeights w = weights(pi, zeta);
    const double end = head_end(w);
    const double step = data_.settings.theta_step / 3.0;
    const auto count = static_cast<std::size_t>(end / step);
    const NodeMotion exact = NodeRun(device, *ratios_, pi, zeta, step * static_cast<double>(count + 1)).sample(0.0, step, count);
    double e = 0.0, n = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      const double d = head(w, step * static_cast<double>(i)).u - exact.u[i];
      e += d * d;
      n += exact.u[i] * exact.u[i];
    }
    errors[c] = std::sqrt(e / n);
  }
  data_.check_error = *std::max_element(errors.begin(), errors.end());
}

}  // namespace stengmc
