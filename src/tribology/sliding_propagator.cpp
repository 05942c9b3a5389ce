#include "tribology/sliding_propagator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "tribology/oscillator_flow.hpp"

namespace stengmc {

namespace {

constexpr int Q = PROPAGATOR_NODES;
constexpr int K = PROPAGATOR_TERMS - 1;  // degree of u_p

//! Inverse of V_ik = s_i^(k+2), s_i = (i+1)/Q: the fit of P's coefficients c_2 .. c_{Q+1}
//! to the remainder at the nodes. Computed once (exactly the same matrix every run).
const Eigen::Matrix<double, Q, Q>& fit_inverse() {
  static const Eigen::Matrix<double, Q, Q> inverse = [] {
    Eigen::Matrix<double, Q, Q> v;
    for (int i = 0; i < Q; ++i)
      for (int k = 0; k < Q; ++k) v(i, k) = std::pow(static_cast<double>(i + 1) / Q, k + 2);
    return Eigen::Matrix<double, Q, Q>(v.fullPivLu().inverse());
  }();
  return inverse;
}

//! The frozen system and the polynomial remainder of one step.
class Collocation {
 public:
  Collocation(const ScaledSystem& sys, const Vec2& y, const Vec2& f, const Mat2& jac, double h)
      : sys_(sys), h_(h), zeta_(-0.5 * jac(1, 1)), centre_(f[1] + y[0] + 2.0 * zeta_ * y[1]),
        z0_{y[0] - centre_, y[1]}, half_(OscillatorFlow::over(zeta_, 0.5 * h / Q)), node_(half_.doubled()) {}

  //! g(w): the true acceleration minus the frozen one (it does not depend on u), at
  //! several w at once (the friction law's evaluations then overlap).
  template <std::size_t N>
  void remainders(const std::array<double, N>& w, std::array<double, N>& g) const {
    sys_.friction_terms(w, g);
    for (std::size_t i = 0; i < N; ++i) g[i] = g[i] - centre_ + (2.0 * zeta_ - sys_.two_zeta()) * w[i];
  }

  //! Sets P from the remainder at the nodes and solves for the particular polynomial.
  void fit(const std::array<double, Q>& g_nodes) {
    const Eigen::Map<const Eigen::Matrix<double, Q, 1>> g(g_nodes.data());
    const Eigen::Matrix<double, Q, 1> c = fit_inverse() * g;
    // P(tau) = sum_k d_k tau^k, d_k = c_k / h^k (k = 2 .. K).
    d_.fill(0.0);
    double scale = 1.0 / (h_ * h_);
    for (int k = 2; k <= K; ++k, scale /= h_) d_[static_cast<std::size_t>(k)] = c[k - 2] * scale;
    // Back substitution from the top: a_K = -M^-1 e2 d_K = (d_K, 0), then
    // a_j = M^-1 ((j+1) a_{j+1} - e2 d_j), M^-1 = [[-2 zeta, -1], [1, 0]].
    double next_u = 0.0, next_w = 0.0;  // a_{j+1}
    for (int j = K; j >= 0; --j) {
      const double v0 = (j + 1) * next_u;
      const double v1 = (j + 1) * next_w - d_[static_cast<std::size_t>(j)];
      next_u = -2.0 * zeta_ * v0 - v1;
      next_w = v0;
      p_[static_cast<std::size_t>(j)] = next_u;
      dp_[static_cast<std::size_t>(j)] = j * next_u;  // u_p' = w_p coefficients, shifted
    }
    fitted_ = true;
  }

  //! The remainder at the nodes of the frozen oscillator (before any fit).
  [[nodiscard]] std::array<double, Q> frozen_nodes() const {
    std::array<double, Q> w{};
    double zu = z0_[0], zw = z0_[1];
    for (std::size_t i = 0; i < Q; ++i) {
      node_.apply(zu, zw);
      w[i] = zw;
    }
    std::array<double, Q> g{};
    remainders(w, g);
    return g;
  }

  //! Walks the nodes tau_i = i h / Q of the current solution, the remainder there into
  //! g, and checks the defect g - P there; the end state into `end`. Returns the largest
  //! |defect| at the nodes.
  double walk(std::array<double, Q>& g, Vec2& end) const {
    double zu = 0.0, zw = 0.0;
    free_start(zu, zw);
    const double spacing = h_ / Q;
    std::array<double, Q> w{}, forcing{};
    for (int i = 1; i <= Q; ++i) {
      node_.apply(zu, zw);
      const double tau = i * spacing;
      const Point p = at(zw, tau);
      w[static_cast<std::size_t>(i - 1)] = p.w;
      forcing[static_cast<std::size_t>(i - 1)] = p.forcing;
      if (i == Q) end = {centre_ + displacement_at(zu, tau), p.w};
    }
    remainders(w, g);
    double worst = 0.0;
    for (std::size_t i = 0; i < Q; ++i) worst = std::max(worst, std::abs(g[i] - forcing[i]));
    return worst;
  }

  //! The largest |defect| at the midpoints of the first and the last node interval, where
  //! equispaced interpolation errs most (a separate pass: where the nodes' defect alone
  //! already rejects the sweep, these two remainders are not needed).
  [[nodiscard]] double midpoint_defect() const {
    const double spacing = h_ / Q;
    double zu = 0.0, zw = 0.0;
    free_start(zu, zw);
    auto midpoint_after = [&](double hu, double hw, double tau) {
      half_.apply(hu, hw);
      return at(hw, tau + 0.5 * spacing);
    };
    const Point first = midpoint_after(zu, zw, 0.0);
    for (int i = 1; i < Q; ++i) node_.apply(zu, zw);
    const Point last = midpoint_after(zu, zw, (Q - 1) * spacing);
    std::array<double, 2> g{};
    remainders(std::array<double, 2>{first.w, last.w}, g);
    return std::max(std::max(0.0, std::abs(g[0] - first.forcing)), std::abs(g[1] - last.forcing));
  }

  [[nodiscard]] double zeta() const { return zeta_; }
  [[nodiscard]] double centre() const { return centre_; }
  [[nodiscard]] const std::array<double, K + 1>& particular() const { return p_; }

 private:
  struct Point {
    double w, forcing;
  };
  //! The solution's velocity (free part hw plus the polynomial's) and P at tau.
  [[nodiscard]] Point at(double hw, double tau) const {
    if (!fitted_) return {hw, 0.0};
    double pf = d_[K], pw = dp_[K];
    for (std::size_t j = K; j-- > 0;) pf = pf * tau + d_[j];
    for (std::size_t j = K; j-- > 1;) pw = pw * tau + dp_[j];
    return {hw + pw, pf};
  }
  //! The free oscillator's state at tau = 0: z_h(0) = z_0 - z_p(0), with w_p(0) = p_1
  //! since u_p' = w_p.
  void free_start(double& zu, double& zw) const {
    zu = z0_[0] - p_[0];
    zw = z0_[1] - p_[1];
  }
  //! The solution's displacement (free part hu plus the polynomial's) at tau.
  [[nodiscard]] double displacement_at(double hu, double tau) const {
    if (!fitted_) return hu;
    double pu = p_[K];
    for (std::size_t j = K; j-- > 0;) pu = pu * tau + p_[j];
    return hu + pu;
  }

  const ScaledSystem& sys_;
  double h_;
  double zeta_;
  double centre_;
  Vec2 z0_;
  OscillatorFlow half_;  // flow over half a node spacing
  OscillatorFlow node_;  // and over a whole one
  bool fitted_ = false;
  std::array<double, K + 1> p_{};   // u_p coefficients a_j,u
  std::array<double, K + 1> dp_{};  // j a_j,u: w_p = sum_j dp_j tau^(j-1)
  std::array<double, K + 1> d_{};   // P coefficients
};

}  // namespace

PropagatorStep propagator_step(const ScaledSystem& sys, const Vec2& y, const Vec2& f, const Mat2& jac, double h,
                               double tol) {
  Collocation step(sys, y, f, jac, h);
  std::array<double, Q> g{};
  PropagatorStep out;
  const double growth = std::exp(std::max(0.0, -step.zeta()) * h);
  auto error_of = [&](double defect) {
    const double bound = h * defect * growth;
    const double e = error_norm({bound, bound}, y, out.y_end, tol);
    return std::isfinite(e) && out.y_end.allFinite() ? e : std::numeric_limits<double>::infinity();
  };
  // Sweep 0 takes the first nodes on the frozen oscillator; sweep 1 walks the solution
  // corrected by their fit. Where its defect is still too large, one more sweep refits on
  // it (the Picard error falls ~h |g'| per sweep; the interpolation error does not).
  // The midpoints' defect is checked only where the nodes' defect would accept the sweep
  // (else the next sweep, or the rejection, follows either way).
  step.fit(step.frozen_nodes());
  double defect = step.walk(g, out.y_end);
  out.error = error_of(defect);
  if (out.error <= 1.0) out.error = error_of(std::max(defect, step.midpoint_defect()));
  if (out.error > 1.0 && std::isfinite(out.error)) {
    step.fit(g);
    defect = step.walk(g, out.y_end);
    out.error = error_of(std::max(defect, step.midpoint_defect()));
  }
  // |z_p(0)| more than PROPAGATOR_CANCELLATION length scales: the parts would cancel.
  out.suitable = std::abs(step.particular()[0]) + std::abs(step.particular()[1]) <= PROPAGATOR_CANCELLATION;
  out.zeta = step.zeta();
  out.centre = step.centre();
  std::copy(step.particular().begin(), step.particular().end(), out.particular.begin());
  return out;
}

}  // namespace stengmc
