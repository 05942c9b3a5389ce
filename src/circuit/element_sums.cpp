#include "circuit/element_sums.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

#include "core/constants.hpp"
#include "circuit/circuit_errors.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "model/hermite.hpp"

namespace stengmc {

namespace {

// Radau IIA, s = 3 (Hairer & Wanner, Solving ODEs II, Table 5.6), as in circuit_solver.cpp.
constexpr int STAGES = 3;
const double SQRT6 = std::sqrt(6.0);
const std::array<double, STAGES> RADAU_C{(4.0 - SQRT6) / 10.0, (4.0 + SQRT6) / 10.0, 1.0};
const Eigen::Matrix3d RADAU_A = (Eigen::Matrix3d() <<
    (88.0 - 7.0 * SQRT6) / 360.0, (296.0 - 169.0 * SQRT6) / 1800.0, (-2.0 + 3.0 * SQRT6) / 225.0,
    (296.0 + 169.0 * SQRT6) / 1800.0, (88.0 + 7.0 * SQRT6) / 360.0, (-2.0 - 3.0 * SQRT6) / 225.0,
    (16.0 - SQRT6) / 36.0, (16.0 + SQRT6) / 36.0, 1.0 / 9.0).finished();

constexpr std::size_t PROGRESS_BATCH = 256;

//! Monomial coefficients (s^0 .. s^5) of the quintic through values f and s-slopes d at
//! s = 0, 1/2, 1, from the data (f0, d0, fm, dm, f1, d1): coefficients = basis() * data.
const Eigen::Matrix<double, 6, 6>& basis() {
  static const Eigen::Matrix<double, 6, 6> inverse = [] {
    Eigen::Matrix<double, 6, 6> conditions = Eigen::Matrix<double, 6, 6>::Zero();
    const std::array<double, 3> nodes{0.0, 0.5, 1.0};
    for (int n = 0; n < 3; ++n)
      for (int k = 0; k < 6; ++k) {
        const double s = nodes[static_cast<std::size_t>(n)];
        conditions(2 * n, k) = std::pow(s, k);
        conditions(2 * n + 1, k) = k == 0 ? 0.0 : k * std::pow(s, k - 1);
      }
    return Eigen::Matrix<double, 6, 6>(conditions.fullPivLu().inverse());
  }();
  return inverse;
}

//! Weights turning the Hermite data into the value and the s-slope at s.
struct NodeWeights {
  Eigen::Matrix<double, 1, 6> value;
  Eigen::Matrix<double, 1, 6> slope;
};

NodeWeights weights_at(double s) {
  Eigen::Matrix<double, 1, 6> powers, slopes;
  for (int k = 0; k < 6; ++k) {
    powers(k) = std::pow(s, k);
    slopes(k) = k == 0 ? 0.0 : k * std::pow(s, k - 1);
  }
  return {powers * basis(), slopes * basis()};
}

}  // namespace

void ElementSums::reset(std::span<const double> times_s) {
  for (std::size_t j = 1; j < times_s.size(); ++j)
    if (!(times_s[j] > times_s[j - 1])) throw InputError("circuit: times must be strictly increasing");
  times_.assign(times_s.begin(), times_s.end());
  const std::size_t m = times_.size();
  const std::size_t intervals = m > 0 ? m - 1 : 0;
  elements_ = 0;
  capacitance_at_zero_ = 0.0;
  for (auto* v : {&p_, &k_, &dp_right_, &dk_right_, &dp_left_, &dk_left_}) v->assign(m, 0.0);
  for (auto* v : {&p_mid_, &k_mid_, &dp_mid_, &dk_mid_}) v->assign(intervals, 0.0);
  exceptions_.clear();
  element_kinks_.clear();
  fine_tables_.clear();
  excerpts_.clear();
}

bool ElementSums::add(const StengElement& element, const MotionSamples& samples, const Motion& motion) {
  const std::size_t m = times_.size();
  if (samples.x_m.size() != m || samples.v_m_per_s.size() != m || (m > 0 && samples.mid_x_m.size() != m - 1))
    throw Error("circuit: an element's samples do not match the grid (midpoints needed)");
  const double cw = element.charge_density_c_per_m2 * element.width_m;
  const double g = EPSILON_0 * element.width_m / element.effective_thickness_m;
  capacitance_at_zero_ += g * element.length_m;
  ++elements_;
  const double* x = samples.x_m.data();
  const double* v = samples.v_m_per_s.data();
  for (std::size_t j = 0; j < m; ++j) {
    p_[j] += cw * x[j];
    k_[j] += g * x[j];
    dp_right_[j] += cw * v[j];
    dk_right_[j] += g * v[j];
  }
  const double* v_left = samples.v_left_m_per_s.empty() ? v : samples.v_left_m_per_s.data();
  for (std::size_t j = 0; j < m; ++j) {
    dp_left_[j] += cw * v_left[j];
    dk_left_[j] += g * v_left[j];
  }
  // Intervals with a kink or fine structure strictly inside: this element is evaluated
  // there exactly. Both lists are walked against the grid together.
  const double resolution = m >= 2 ? (times_.back() - times_.front()) / static_cast<double>(m - 1) : 0.0;
  const std::vector<double>& kinks = motion.breakpoints();
  const std::vector<double> fine = motion.fine_structure(resolution);
  std::vector<char> flags(m > 0 ? m - 1 : 0, 0);  // per interval: 1 kink, 2 fine structure
  auto mark = [&](const std::vector<double>& list, char flag) {
    std::size_t j = 0;
    for (const double t : list) {
      while (j < m && times_[j] < t) ++j;  // first sample at or after t
      if (j == 0 || j == m || times_[j] == t) continue;  // outside, or on a sample (one-sided limits)
      flags[j - 1] |= flag;
    }
  };
  mark(kinks, 1);
  mark(fine, 2);
  const std::size_t kinks_index = element_kinks_.size();
  const std::size_t first = exceptions_.size();  // this element's exceptions start here
  bool has_kink = false;
  for (std::size_t j = 0; j + 1 < m; ++j) {
    if (flags[j] != 0) {
      Exception e{j, &motion, 0, kinks_index, (flags[j] & 2) != 0, cw, g, x[j], v[j], x[j + 1], v_left[j + 1]};
      if ((flags[j] & 1) != 0) {
        has_kink = true;
      } else {  // fine structure only: record it, the motion may go
        e.motion = nullptr;
        e.table = fine_tables_.size();
        const double ta = times_[j], h = times_[j + 1] - ta;
        for (std::size_t k = 0; k <= FINE_STRUCTURE_POINTS; ++k) {
          const bool end = k == FINE_STRUCTURE_POINTS;
          const PhasePoint q = motion.at(end ? times_[j + 1] : ta + h * static_cast<double>(k) / FINE_STRUCTURE_POINTS,
                                         end ? Side::left : Side::right);
          fine_tables_.push_back(q.x_m);
          fine_tables_.push_back(q.v_m_per_s);
        }
      }
      exceptions_.push_back(e);
      continue;
    }
    p_mid_[j] += cw * samples.mid_x_m[j];
    k_mid_[j] += g * samples.mid_x_m[j];
    dp_mid_[j] += cw * samples.mid_v_m_per_s[j];
    dk_mid_[j] += g * samples.mid_v_m_per_s[j];
  }
  if (!has_kink) return false;
  element_kinks_.push_back(kinks);
  // The intervals with a kink are this element's exceptions that carry the motion: its
  // excerpt over them replaces it, so the motion itself may go.
  std::size_t lo = m, hi = 0;
  for (std::size_t e = first; e < exceptions_.size(); ++e)
    if (exceptions_[e].motion != nullptr) {
      lo = std::min(lo, exceptions_[e].interval);
      hi = std::max(hi, exceptions_[e].interval + 1);
    }
  std::shared_ptr<const Motion> part = motion.excerpt(times_[lo], times_[hi]);
  if (!part) return true;
  for (std::size_t e = first; e < exceptions_.size(); ++e)
    if (exceptions_[e].motion != nullptr) exceptions_[e].motion = part.get();
  excerpts_.push_back(std::move(part));
  return false;
}

//! The solve, with the tables it shares between intervals.
struct SummedCircuitSolver {
  const ElementSums& sums;
  const CircuitParams& params;
  double load_conductance = 0.0;
  double base_capacitance = 0.0;  // C_L + sum eps0 w l / d0
  // Weights of the nodes of an interval without kinks (in step order): value and s-slope
  // of the Hermite quintic, six per node; and the nodes' C, S, alpha of the interval at hand.
  std::vector<NodeWeights> node_weights;
  std::vector<double> value_weights, slope_weights;
  std::vector<double> node_capacitance, node_source, node_alpha;
  std::vector<std::size_t> exception_order;  // exceptions sorted by interval
  std::size_t next = 0;  // position in exception_order

  SummedCircuitSolver(const ElementSums& s, const CircuitParams& p) : sums(s), params(p) {
    load_conductance = 1.0 / p.load_resistance_ohm;
    base_capacitance = p.load_capacitance_f + s.capacitance_at_zero_;
    const auto substeps = static_cast<double>(p.substeps);
    for (std::size_t m = 0; m < p.substeps; ++m)
      for (int st = 0; st < STAGES; ++st) {
        const bool end = m + 1 == p.substeps && st == STAGES - 1;
        NodeWeights w = weights_at(end ? 1.0 : (static_cast<double>(m) + RADAU_C[static_cast<std::size_t>(st)]) / substeps);
        if (end) {  // exactly the end data
          w.value.setZero();
          w.slope.setZero();
          w.value(4) = 1.0;
          w.slope(5) = 1.0;
        }
        node_weights.push_back(w);
      }
    // Six per node: weights[6 n + i].
    const std::size_t nodes = node_weights.size();
    for (std::size_t n = 0; n < nodes; ++n)
      for (Eigen::Index i = 0; i < 6; ++i) {
        value_weights.push_back(node_weights[n].value(i));
        slope_weights.push_back(node_weights[n].slope(i));
      }
    node_capacitance.resize(nodes);
    node_source.resize(node_capacitance.size());
    node_alpha.resize(node_capacitance.size());
    exception_order.resize(s.exceptions_.size());
    std::iota(exception_order.begin(), exception_order.end(), 0);
    std::stable_sort(exception_order.begin(), exception_order.end(), [&](std::size_t a, std::size_t b) {
      return s.exceptions_[a].interval < s.exceptions_[b].interval;
    });
  }

  //! One Radau IIA step of U' = alpha U + beta over h, from the stage coefficients: the
  //! last stage of (I - h A diag(alpha)) U = u 1 + h A beta, by Gaussian elimination. For
  //! alpha <= 0 the matrix is I plus h |alpha| times A's columns (A is invertible, condition
  //! ~10), so elimination in order needs no pivoting (multipliers stay below ~2).
  //! `ha` is h A.
  static double radau_step(double u, const double (&ha)[STAGES][STAGES], const double (&alpha)[STAGES],
                           const double (&beta)[STAGES]) {
    double m[STAGES][STAGES], r[STAGES];
    for (int i = 0; i < STAGES; ++i) {
      r[i] = u;
      for (int k = 0; k < STAGES; ++k) {
        m[i][k] = (i == k ? 1.0 : 0.0) - ha[i][k] * alpha[k];
        r[i] += ha[i][k] * beta[k];
      }
    }
    for (int pivot = 0; pivot < STAGES - 1; ++pivot)
      for (int i = pivot + 1; i < STAGES; ++i) {
        const double factor = m[i][pivot] / m[pivot][pivot];
        for (int k = pivot + 1; k < STAGES; ++k) m[i][k] -= factor * m[pivot][k];
        r[i] -= factor * r[pivot];
      }
    return r[STAGES - 1] / m[STAGES - 1][STAGES - 1];
  }

  static void scaled_radau_matrix(double h, double (&ha)[STAGES][STAGES]) {
    for (int i = 0; i < STAGES; ++i)
      for (int k = 0; k < STAGES; ++k) ha[i][k] = h * RADAU_A(i, k);
  }

  //! An element's fine-structure table at t in the interval [ta, ta + h], by cubic Hermite
  //! interpolation between the two recorded points around it.
  PhasePoint fine_table_at(const ElementSums::Exception& ex, double ta, double h, double t) const {
    const double* table = sums.fine_tables_.data() + ex.table;
    const double spacing = h / FINE_STRUCTURE_POINTS;
    const double position = (t - ta) / spacing;
    const auto k = static_cast<std::size_t>(std::clamp(std::floor(position), 0.0, FINE_STRUCTURE_POINTS - 1.0));
    const MotionKnot a{0.0, table[2 * k], table[2 * k + 1], 0.0};
    const MotionKnot b{spacing, table[2 * k + 2], table[2 * k + 3], 0.0};
    return cubic_hermite(a, b, (position - static_cast<double>(k)) * spacing);
  }

  double alpha_at(double capacitance, double t) const {
    if (capacitance <= 0.0) throw_capacitance_not_positive(t, capacitance);
    return -load_conductance / capacitance;
  }

  //! U over interval j (from U at its start), no kink inside.
  double regular_interval(std::size_t j, double u) {
    const double t0 = sums.times_[j], h = sums.times_[j + 1] - t0;
    // P' data over h (slopes in s are h P'): S = (1/h) d/ds P; K's slopes times h.
    const double p[6] = {sums.p_[j] / h, sums.dp_right_[j], sums.p_mid_[j] / h, sums.dp_mid_[j], sums.p_[j + 1] / h,
                         sums.dp_left_[j + 1]};
    const double kk[6] = {sums.k_[j], h * sums.dk_right_[j], sums.k_mid_[j], h * sums.dk_mid_[j], sums.k_[j + 1],
                          h * sums.dk_left_[j + 1]};
    const std::size_t nodes = node_capacitance.size();
    // C and S at every node, six weights each (in step order).
    for (std::size_t n = 0; n < nodes; ++n) {
      const double* wv = value_weights.data() + 6 * n;
      const double* ws = slope_weights.data() + 6 * n;
      node_capacitance[n] = base_capacitance - (wv[0] * kk[0] + wv[1] * kk[1] + wv[2] * kk[2] + wv[3] * kk[3] +
                                                wv[4] * kk[4] + wv[5] * kk[5]);
      node_source[n] = ws[0] * p[0] + ws[1] * p[1] + ws[2] * p[2] + ws[3] * p[3] + ws[4] * p[4] + ws[5] * p[5];
    }
    for (std::size_t n = 0; n < nodes; ++n) {
      if (!(node_capacitance[n] > 0.0)) {
        const std::size_t m = n / STAGES;
        (void)alpha_at(node_capacitance[n],
                       t0 + h * (static_cast<double>(m) + RADAU_C[n % STAGES]) / static_cast<double>(params.substeps));
      }
      node_alpha[n] = -load_conductance / node_capacitance[n];
    }
    double ha[STAGES][STAGES];
    scaled_radau_matrix(h / static_cast<double>(params.substeps), ha);
    double alpha[STAGES], beta[STAGES];
    for (std::size_t m = 0; m < params.substeps; ++m) {
      for (std::size_t st = 0; st < STAGES; ++st) {
        alpha[st] = node_alpha[STAGES * m + st];
        beta[st] = node_source[STAGES * m + st];
      }
      u = radau_step(u, ha, alpha, beta);
    }
    return u;
  }

  //! U over interval j, which holds kinks of the exceptions [first, last) of exception_order.
  double exceptional_interval(std::size_t j, double u, std::size_t first, std::size_t last) const {
    const double ta = sums.times_[j], tb = sums.times_[j + 1], h = tb - ta;
    Eigen::Matrix<double, 6, 1> p, kk;
    double p0 = sums.p_[j], dp0 = sums.dp_right_[j], p1 = sums.p_[j + 1], dp1 = sums.dp_left_[j + 1];
    double k0 = sums.k_[j], dk0 = sums.dk_right_[j], k1 = sums.k_[j + 1], dk1 = sums.dk_left_[j + 1];
    std::vector<double> cuts;
    bool fine = false;
    for (std::size_t e = first; e < last; ++e) {
      const ElementSums::Exception& ex = sums.exceptions_[exception_order[e]];
      p0 -= ex.charge_per_m * ex.x_start;
      dp0 -= ex.charge_per_m * ex.v_start;
      p1 -= ex.charge_per_m * ex.x_end;
      dp1 -= ex.charge_per_m * ex.v_end;
      k0 -= ex.capacitance_per_m * ex.x_start;
      dk0 -= ex.capacitance_per_m * ex.v_start;
      k1 -= ex.capacitance_per_m * ex.x_end;
      dk1 -= ex.capacitance_per_m * ex.v_end;
      fine = fine || ex.fine;
      if (ex.motion == nullptr) continue;  // no kink here, only fine structure
      const std::vector<double>& kinks = sums.element_kinks_[ex.kinks];
      for (auto it = std::upper_bound(kinks.begin(), kinks.end(), ta); it != kinks.end() && *it < tb; ++it)
        cuts.push_back(*it);
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    cuts.push_back(tb);
    p << p0, h * dp0, sums.p_mid_[j], h * sums.dp_mid_[j], p1, h * dp1;
    kk << k0, h * dk0, sums.k_mid_[j], h * sums.dk_mid_[j], k1, h * dk1;
    const Eigen::Matrix<double, 6, 1> pc = basis() * p;  // monomial coefficients in s
    const Eigen::Matrix<double, 6, 1> kc = basis() * kk;
    auto regular_at = [&](double t, double& source, double& k_sum) {
      const double s = (t - ta) / h;
      double value = kc[5], slope = 5.0 * pc[5];
      for (int i = 4; i >= 0; --i) value = value * s + kc[i];
      for (int i = 4; i >= 1; --i) slope = slope * s + i * pc[i];  // d/ds of the P quintic
      source = slope / h;
      k_sum = value;
    };
    const std::size_t steps = params.substeps * (fine ? FINE_STRUCTURE_REFINEMENT : 1);
    const auto substeps = static_cast<double>(steps);
    double t = ta;
    for (const double piece_end : cuts) {
      const double span = piece_end - t;
      double t_step = t;
      for (std::size_t m = 1; m <= steps; ++m) {
        const double t_next = m == steps ? piece_end : t + span * (static_cast<double>(m) / substeps);
        const double hs = t_next - t_step;
        double alpha[STAGES], beta[STAGES];
        for (int st = 0; st < STAGES; ++st) {
          // The last node is the step's end exactly, from the left (a kink belongs to
          // the next step).
          const bool at_end = st == STAGES - 1;
          const double tn = at_end ? t_next : t_step + RADAU_C[static_cast<std::size_t>(st)] * hs;
          const Side side = at_end ? Side::left : Side::right;
          double source = 0.0, k_sum = 0.0;
          regular_at(tn, source, k_sum);
          for (std::size_t e = first; e < last; ++e) {
            const ElementSums::Exception& ex = sums.exceptions_[exception_order[e]];
            const PhasePoint q = ex.motion != nullptr ? ex.motion->at(tn, side) : fine_table_at(ex, ta, h, tn);
            source += ex.charge_per_m * q.v_m_per_s;
            k_sum += ex.capacitance_per_m * q.x_m;
          }
          alpha[st] = alpha_at(base_capacitance - k_sum, tn);
          beta[st] = source;
        }
        double ha[STAGES][STAGES];
        scaled_radau_matrix(hs, ha);
        u = radau_step(u, ha, alpha, beta);
        t_step = t_next;
      }
      t = piece_end;
    }
    return u;
  }

  void solve(std::size_t samples, Progress* progress, SummedCircuit& out) {
    const std::vector<double>& t = sums.times_;
    samples = std::min(samples, t.size());
    out.voltage_v.assign(samples, 0.0);
    out.charge_c.assign(samples, 0.0);
    out.dv_dt_v_per_s.assign(samples, 0.0);
    if (samples == 0) return;
    // V(t0) = 0 and Q(t0) = 0; V' from the right there, the motion the first interval sees.
    {
      const double capacitance = base_capacitance - sums.k_[0];
      (void)alpha_at(capacitance, t[0]);
      out.dv_dt_v_per_s[0] = sums.dp_right_[0] / capacitance;
      if (!std::isfinite(out.dv_dt_v_per_s[0])) throw_non_finite("voltage slope", t[0]);
    }
    double u = 0.0;  // U = C V
    std::size_t unreported = 1;
    for (std::size_t j = 0; j + 1 < samples; ++j) {
      std::size_t last = next;
      while (last < exception_order.size() && sums.exceptions_[exception_order[last]].interval == j) ++last;
      u = last == next ? regular_interval(j, u) : exceptional_interval(j, u, next, last);
      next = last;
      // At the output time: C from the samples themselves, V = U / C, Q = P - P0 - U.
      const double capacitance = base_capacitance - sums.k_[j + 1];
      (void)alpha_at(capacitance, t[j + 1]);
      const double voltage = u / capacitance;
      const double charge = (sums.p_[j + 1] - sums.p_[0]) - u;
      if (!std::isfinite(voltage)) throw_non_finite("voltage", t[j + 1]);
      if (!std::isfinite(charge)) throw_non_finite("delivered charge", t[j + 1]);
      out.voltage_v[j + 1] = voltage;
      out.charge_c[j + 1] = charge;
      out.dv_dt_v_per_s[j + 1] =
          (sums.dp_left_[j + 1] + sums.dk_left_[j + 1] * voltage - voltage * load_conductance) / capacitance;
      if (progress != nullptr && ++unreported == PROGRESS_BATCH) {
        progress->advance(unreported);
        unreported = 0;
      }
    }
    if (progress != nullptr) progress->advance(unreported);
  }
};

SummedCircuit solve_summed_circuit(const ElementSums& sums, std::size_t samples, const CircuitParams& params,
                                   Progress* progress) {
  SummedCircuit out;
  solve_summed_circuit(sums, samples, params, out, progress);
  return out;
}

void solve_summed_circuit(const ElementSums& sums, std::size_t samples, const CircuitParams& params, SummedCircuit& out,
                          Progress* progress) {
  if (!(params.load_resistance_ohm > 0.0) || !std::isfinite(params.load_resistance_ohm))
    throw InputError("circuit: load resistance must be a positive finite number of ohms");
  if (!(params.load_capacitance_f >= 0.0) || !std::isfinite(params.load_capacitance_f))
    throw InputError("circuit: load capacitance must be >= 0 F");
  if (params.substeps == 0) throw InputError("circuit: substeps must be >= 1");
  SummedCircuitSolver solver(sums, params);
  solver.solve(samples, progress, out);
}

void element_traces(const StengElement& element, const MotionSamples& samples, const SummedCircuit& circuit,
                    std::span<const double> times_s, std::size_t element_number, std::vector<double>& current_a,
                    std::vector<double>& charge_c) {
  const std::size_t count = circuit.voltage_v.size();
  const double cw = element.charge_density_c_per_m2 * element.width_m;
  const double g = EPSILON_0 * element.width_m / element.effective_thickness_m;
  current_a.resize(count);
  charge_c.resize(count);
  if (count == 0) return;
  const double initial = cw * samples.x_m[0] - g * (element.length_m - samples.x_m[0]) * circuit.voltage_v[0];
  for (std::size_t j = 0; j < count; ++j) {
    // Left limits, as V' is; the first sample sees the first interval (right limit).
    const double v = j == 0 ? samples.v_m_per_s[0] : samples.v_left(j);
    const double x = samples.x_m[j];
    const double voltage = circuit.voltage_v[j];
    const double capacitance = g * (element.length_m - x);
    current_a[j] = cw * v + g * v * voltage - capacitance * circuit.dv_dt_v_per_s[j];
    charge_c[j] = (cw * x - capacitance * voltage) - initial;
    if (!std::isfinite(current_a[j]) || !std::isfinite(charge_c[j]))
      throw_non_finite("current or charge of element " + std::to_string(element_number), times_s[j]);
  }
}

CircuitResult solve_circuit_streamed(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                                     std::span<const double> times, const CircuitParams& params, Progress* progress) {
  if (elements.size() != motions.size()) throw Error("circuit: one motion per element is needed");
  ElementSums sums(times);
  std::vector<MotionSamples> samples(elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i) {
    motions[i]->sample(times, true, samples[i]);
    sums.add(elements[i], samples[i], *motions[i]);
  }
  SummedCircuit circuit = solve_summed_circuit(sums, times.size(), params, progress);
  CircuitResult result;
  result.current_a.resize(elements.size());
  result.element_charge_c.resize(elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i)
    element_traces(elements[i], samples[i], circuit, times, i + 1, result.current_a[i], result.element_charge_c[i]);
  result.voltage_v = std::move(circuit.voltage_v);
  result.charge_c = std::move(circuit.charge_c);
  return result;
}

}  // namespace stengmc
