#include "inverse/record_fit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.hpp"

namespace stengmc {

void sort_atoms(FitState& state) {
  std::sort(state.atoms.begin(), state.atoms.end(),
            [](const AtomParameters& a, const AtomParameters& b) { return a.stiffness_n_per_m < b.stiffness_n_per_m; });
}

namespace {

//! `normal` (atoms in the order of `before`, per_atom parameters each, then the shared ones)
//! with its atoms' rows and columns in the order of `after`, the same atoms sorted.
Eigen::MatrixXd sorted_normal_matrix(const Eigen::MatrixXd& normal, const FitState& before, const FitState& after,
                                     std::size_t per_atom) {
  const std::size_t n = before.atoms.size();
  // Which atom of `before` each of `after` is (identical parameters; identical atoms have
  // identical rows, so either of them will do).
  std::vector<Eigen::Index> index(static_cast<std::size_t>(normal.rows()));
  std::vector<bool> used(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const AtomParameters& a = after.atoms[i];
    std::size_t from = n;
    for (std::size_t k = 0; k < n && from == n; ++k) {
      const AtomParameters& b = before.atoms[k];
      if (!used[k] && a.stiffness_n_per_m == b.stiffness_n_per_m && a.load_n == b.load_n && a.onset_s == b.onset_s) from = k;
    }
    if (from == n) throw Error("RecordFit: the sorted atoms are not those fitted");
    used[from] = true;
    for (std::size_t p = 0; p < per_atom; ++p) index[i * per_atom + p] = static_cast<Eigen::Index>(from * per_atom + p);
  }
  for (std::size_t c = n * per_atom; c < index.size(); ++c) index[c] = static_cast<Eigen::Index>(c);
  Eigen::MatrixXd out(normal.rows(), normal.cols());
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    for (Eigen::Index c = 0; c < out.cols(); ++c) out(r, c) = normal(index[static_cast<std::size_t>(r)], index[static_cast<std::size_t>(c)]);
  return out;
}

}  // namespace

RecordFit::RecordFit(const RecordModel& model, const FitLayout& layout, const LoadPrior& loads, std::span<const double> record)
    : model_(&model), layout_(layout), loads_(&loads), record_(record) {
  if (record.size() != model.samples()) throw Error("RecordFit: the record and the model's grid differ in length");
  set_noise(Whitener(), 1.0);
}

void RecordFit::set_noise(const Whitener& whitener, double sigma_v) {
  whitener_ = whitener;
  sigma_v_ = sigma_v > 0.0 ? sigma_v : 1.0;
  whitened_record_.assign(record_.begin(), record_.end());
  whitener_.apply(whitened_record_, whitened_record_);
  whitened_ones_.assign(record_.size(), 1.0);
  whitener_.apply(whitened_ones_, whitened_ones_);
}

double RecordFit::load_penalty(double load_n) const {
  if (!layout_.load_per_atom) return 0.0;
  return -2.0 * loads_->log_density(std::log(load_n / layout_.nominal_load_n));
}

double RecordFit::solve_linear(FitState& s, std::span<const double> unit, std::vector<double>& r, std::vector<double>& wunit) const {
  const std::size_t m_count = record_.size();
  wunit.assign(unit.begin(), unit.end());
  whitener_.apply(wunit, wunit);
  const double* y = whitened_record_.data();
  const double* one = whitened_ones_.data();
  double a = 1.0, b = 0.0;
  if (layout_.amplitude_free || layout_.offset_free) {
    double mm = 0, m1 = 0, o1 = 0, my = 0, oy = 0;
    for (std::size_t j = 0; j < m_count; ++j) {
      mm += wunit[j] * wunit[j], m1 += wunit[j] * one[j], o1 += one[j] * one[j], my += wunit[j] * y[j], oy += one[j] * y[j];
    }
    if (layout_.amplitude_free && layout_.offset_free) {
      const double det = mm * o1 - m1 * m1;
      a = det > 0.0 ? (my * o1 - oy * m1) / det : 1.0;
      if (!(a >= layout_.min_amplitude && a <= layout_.max_amplitude) || !(mm > 0.0))
        a = std::clamp(mm > 0.0 ? a : 1.0, layout_.min_amplitude, layout_.max_amplitude);
      b = (oy - a * m1) / o1;
    } else if (layout_.amplitude_free) {
      a = mm > 0.0 ? std::clamp(my / mm, layout_.min_amplitude, layout_.max_amplitude) : 1.0;
    } else {
      b = (oy - m1) / o1;
    }
  }
  s.amplitude = a;
  s.offset_v = b;
  r.resize(m_count);
  double sum = 0.0;
  for (std::size_t j = 0; j < m_count; ++j) {
    r[j] = y[j] - a * wunit[j] - b * one[j];
    sum += r[j] * r[j];
  }
  return sum;
}

std::vector<double> RecordFit::residual(FitState& state) const {
  std::vector<double> unit(record_.size()), r, wunit;
  AtomSums sums;
  sums.reset(record_.size());
  for (const AtomParameters& a : state.atoms) model_->add(a, state.damping_rate_per_s, sums);
  model_->unit_voltage(sums, unit);
  solve_linear(state, unit, r, wunit);
  for (std::size_t j = 0; j < r.size(); ++j) r[j] = record_[j] - state.amplitude * unit[j] - state.offset_v;
  return r;
}

double RecordFit::whitened_rss(FitState& state) const {
  std::vector<double> unit(record_.size()), r, wunit;
  AtomSums sums;
  sums.reset(record_.size());
  for (const AtomParameters& a : state.atoms) model_->add(a, state.damping_rate_per_s, sums);
  model_->unit_voltage(sums, unit);
  return solve_linear(state, unit, r, wunit);
}

OrderFit RecordFit::refine(FitState s, const std::vector<bool>& active, bool shared, bool normal_matrix,
                           std::size_t max_iterations) {
  const std::size_t m_count = record_.size();
  const FitLayout& L = layout_;
  shared = shared && L.shared() > 0 && !s.atoms.empty();
  const std::size_t n = s.atoms.size();
  // Which atoms move: all when the shared parameters do (they change every atom).
  std::vector<std::size_t> moving;
  for (std::size_t i = 0; i < n; ++i)
    if (shared || active.empty() || active[i]) moving.push_back(i);
  const std::size_t per_atom = L.per_atom();
  // Not const: the final J^T J is taken with every parameter free (the lambdas read these).
  std::size_t p_count = moving.size() * per_atom + (shared ? L.shared() : 0);
  const AtomLibrary& lib = model_->atoms();
  const double log_k_min = std::log(lib.min_stiffness()), log_k_max = std::log(lib.max_stiffness());

  // The parameter vector and its bounds.
  auto pack = [&](const FitState& st) {
    Eigen::VectorXd x(static_cast<Eigen::Index>(p_count));
    Eigen::Index c = 0;
    for (std::size_t i : moving) {
      const AtomParameters& a = st.atoms[i];
      x(c++) = std::log(a.stiffness_n_per_m);
      if (L.load_per_atom) x(c++) = std::log(a.load_n / L.nominal_load_n);
      if (L.onset_free) x(c++) = a.onset_s;
    }
    if (shared) {
      if (L.damping_free) x(c++) = std::log(st.damping_rate_per_s);
      if (L.load_shared) x(c++) = std::log(st.load_factor);
    }
    return x;
  };
  auto clamp_into = [&](Eigen::VectorXd& x) {
    Eigen::Index c = 0;
    for (std::size_t k = 0; k < moving.size(); ++k) {
      x(c) = std::clamp(x(c), log_k_min, log_k_max), ++c;
      if (L.load_per_atom) x(c) = std::clamp(x(c), L.min_log_load, L.max_log_load), ++c;
      if (L.onset_free) x(c) = std::clamp(x(c), L.onset_min_s, L.onset_max_s), ++c;
    }
    if (shared) {
      if (L.damping_free) x(c) = std::clamp(x(c), std::log(L.min_damping_rate), std::log(L.max_damping_rate)), ++c;
      if (L.load_shared) x(c) = std::clamp(x(c), L.min_log_load, L.max_log_load), ++c;
    }
  };
  auto unpack = [&](const Eigen::VectorXd& x, FitState& st) {
    Eigen::Index c = 0;
    for (std::size_t i : moving) {
      AtomParameters& a = st.atoms[i];
      a.stiffness_n_per_m = std::exp(x(c++));
      if (L.load_per_atom) a.load_n = L.nominal_load_n * std::exp(x(c++));
      if (L.onset_free) a.onset_s = x(c++);
    }
    if (shared) {
      if (L.damping_free) st.damping_rate_per_s = std::exp(x(c++));
      if (L.load_shared) st.load_factor = std::exp(x(c++));
    }
    if (L.load_shared)
      for (AtomParameters& a : st.atoms) a.load_n = L.nominal_load_n * st.load_factor;
  };

  // Atoms that do not move are summed once.
  AtomSums& frozen = work_.frozen;
  frozen.reset(m_count);
  {
    std::vector<bool> is_moving(n, false);
    for (std::size_t i : moving) is_moving[i] = true;
    for (std::size_t i = 0; i < n; ++i)
      if (!is_moving[i]) model_->add(s.atoms[i], s.damping_rate_per_s, frozen);
  }
  const double sigma2 = sigma_v_ * sigma_v_;
  std::vector<double>& unit = work_.unit;
  std::vector<double>& wunit = work_.wunit;
  std::vector<double>& r = work_.residual;
  unit.resize(m_count);
  // Each evaluation writes its atom's values whole: kept from the last refit, they are not reallocated.
  std::vector<AtomValues>& values = work_.values;
  values.resize(moving.size());
  AtomSums& sums = work_.sums;
  // The objective at `st` (linear parameters solved into it): whitened RSS / sigma^2 plus the
  // loads' prior; with `normal`, the normal equations of the whitened, projected Jacobian
  // P J (P projects out the linear parameters' columns): (P J)^T (P J) into `normal` and
  // (P J)^T r into `gradient`. P J itself is never formed: with Q an orthonormal basis of
  // those columns and B = Q^T J, (P J)^T (P J) = J^T J - B^T B and (P J)^T r = J^T r - B^T Q^T r,
  // which spares an M x p product and its subtraction at every step.
  auto evaluate = [&](FitState& st, Eigen::MatrixXd* normal, Eigen::VectorXd* gradient, double* rss_out, double* penalty_out) {
    sums = frozen;
    for (std::size_t k = 0; k < moving.size(); ++k)
      model_->add(st.atoms[moving[k]], st.damping_rate_per_s, sums, &values[k], normal != nullptr);
    model_->unit_voltage(sums, unit);
    const double rss = solve_linear(st, unit, r, wunit);
    double penalty = 0.0;
    for (const AtomParameters& a : st.atoms) penalty += load_penalty(a.load_n);
    if (rss_out) *rss_out = rss;
    if (penalty_out) *penalty_out = penalty;
    if (normal) {
      // Not zeroed as a whole (M x p, 4 MB at 16 atoms): an atom's own columns are written
      // whole, the shared ones zeroed and summed over atoms.
      work_.jacobian.resize(m_count * p_count);
      Eigen::Map<Eigen::MatrixXd> jacobian(work_.jacobian.data(), static_cast<Eigen::Index>(m_count), static_cast<Eigen::Index>(p_count));
      const double scale = st.amplitude * model_->volts_per_unit();
      Eigen::Index c = 0;
      auto set = [&](const AtomValues& v, const std::vector<double>& d, Eigen::Index column) {
        double* col = jacobian.col(column).data();
        std::fill(col, col + v.first, 0.0);
        for (std::size_t j = 0; j < d.size(); ++j) col[v.first + j] = scale * d[j];
      };
      auto add = [&](const AtomValues& v, const std::vector<double>& d, Eigen::Index column) {
        double* col = jacobian.col(column).data();
        for (std::size_t j = 0; j < d.size(); ++j) col[v.first + j] += scale * d[j];
      };
      for (std::size_t k = 0; k < moving.size(); ++k) {
        set(values[k], values[k].d_lnk, c++);
        if (L.load_per_atom) set(values[k], values[k].d_lnn, c++);
        if (L.onset_free) set(values[k], values[k].d_onset, c++);
      }
      if (shared) {
        if (L.damping_free) {
          jacobian.col(c).setZero();
          for (std::size_t k = 0; k < moving.size(); ++k) add(values[k], values[k].d_lnd, c);
          ++c;
        }
        if (L.load_shared) {
          jacobian.col(c).setZero();
          for (std::size_t k = 0; k < moving.size(); ++k) add(values[k], values[k].d_lnn, c);
          ++c;
        }
      }
      for (Eigen::Index col = 0; col < jacobian.cols(); ++col) {
        std::span<double> column(jacobian.col(col).data(), m_count);
        whitener_.apply(column, column);
      }
      const Eigen::Map<const Eigen::VectorXd> residual_vector(r.data(), static_cast<Eigen::Index>(m_count));
      normal->setZero(jacobian.cols(), jacobian.cols());
      normal->selfadjointView<Eigen::Lower>().rankUpdate(jacobian.transpose());
      *normal = normal->selfadjointView<Eigen::Lower>();
      *gradient = jacobian.transpose() * residual_vector;
      // Variable projection: the linear parameters' columns projected out.
      std::vector<const double*> linear;
      if (L.amplitude_free) linear.push_back(wunit.data());
      if (L.offset_free) linear.push_back(whitened_ones_.data());
      if (!linear.empty()) {
        Eigen::MatrixXd q(static_cast<Eigen::Index>(m_count), static_cast<Eigen::Index>(linear.size()));
        for (std::size_t l = 0; l < linear.size(); ++l)
          q.col(static_cast<Eigen::Index>(l)) = Eigen::Map<const Eigen::VectorXd>(linear[l], static_cast<Eigen::Index>(m_count));
        const Eigen::HouseholderQR<Eigen::MatrixXd> qr(q);
        const Eigen::MatrixXd basis = qr.householderQ() * Eigen::MatrixXd::Identity(q.rows(), q.cols());
        const Eigen::MatrixXd b = basis.transpose() * jacobian;
        *normal -= b.transpose() * b;
        *gradient -= b.transpose() * (basis.transpose() * residual_vector);
      }
    }
    return rss / sigma2 + penalty;
  };
  // Gradient and curvature of the loads' prior term in the parameter vector.
  auto prior_terms = [&](const Eigen::VectorXd& x, Eigen::VectorXd& gradient, Eigen::VectorXd& curvature) {
    gradient.setZero(x.size());
    curvature.setZero(x.size());
    if (!L.load_per_atom) return;
    for (std::size_t k = 0; k < moving.size(); ++k) {
      const Eigen::Index c = static_cast<Eigen::Index>(k * per_atom + 1);
      const double h = 1e-3;
      const double f0 = -2.0 * loads_->log_density(x(c)), fp = -2.0 * loads_->log_density(x(c) + h),
                   fm = -2.0 * loads_->log_density(x(c) - h);
      gradient(c) = (fp - fm) / (2.0 * h);
      curvature(c) = std::max(0.0, (fp - 2.0 * f0 + fm) / (h * h));
    }
  };

  // When every parameter is free, J^T J at the final point is the last one the iterations
  // made, its atoms in their order before the sort: permuted, not computed again (a full
  // refit's last Jacobian, and half the cost of a refit of no iterations).
  const bool all_free = moving.size() == n && shared == (L.shared() > 0) && p_count > 0;
  OrderFit fit;
  Eigen::VectorXd x = pack(s);
  clamp_into(x);
  unpack(x, s);
  Eigen::MatrixXd normal_jj;    // (P J)^T (P J) at x
  Eigen::VectorXd jacobian_r;   // (P J)^T r at x
  double rss = 0.0, penalty = 0.0;
  double objective = evaluate(s, p_count > 0 ? &normal_jj : nullptr, &jacobian_r, &rss, &penalty);
  if (p_count > 0) {
    double lambda = 1e-3;
    FitState trial_state = s;
    double trial_rss = 0.0, trial_penalty = 0.0;
    for (std::size_t iteration = 0; iteration < max_iterations; ++iteration) {
      fit.iterations = iteration + 1;
      Eigen::VectorXd prior_gradient, prior_curvature;
      prior_terms(x, prior_gradient, prior_curvature);
      // Minimising rss / sigma^2 + penalty: (J^T J / sigma^2 + P) dx = J^T r / sigma^2 - grad(penalty) / 2.
      const Eigen::MatrixXd normal = normal_jj / sigma2;
      const Eigen::VectorXd gradient = jacobian_r / sigma2 - 0.5 * prior_gradient;
      bool accepted = false, converged = false;
      // Converged when the objective (in units of sigma^2) no longer moves by this.
      const double tolerance = 1e-6 + 1e-12 * objective;
      while (lambda < 1e10) {
        Eigen::MatrixXd damped = normal;
        for (Eigen::Index i = 0; i < damped.rows(); ++i) damped(i, i) += 0.5 * prior_curvature(i) + lambda * normal(i, i) + 1e-300;
        Eigen::VectorXd trial_x = x + damped.ldlt().solve(gradient);
        clamp_into(trial_x);
        trial_state = s;
        unpack(trial_x, trial_state);
        const double trial_objective = evaluate(trial_state, nullptr, nullptr, &trial_rss, &trial_penalty);
        if (trial_objective < objective) {
          const double gain = objective - trial_objective;
          x = trial_x;
          s = trial_state;
          converged = gain < tolerance;
          lambda = std::max(lambda / 3.0, 1e-12);
          accepted = true;
          if (converged && !(normal_matrix && all_free)) {
            // The last step: its Jacobian would not be used (the final J^T J is asked for, or
            // can be taken from the iterations, only when every parameter is free).
            objective = trial_objective, rss = trial_rss, penalty = trial_penalty;
          } else {
            objective = evaluate(s, &normal_jj, &jacobian_r, &rss, &penalty);  // the Jacobian at the new point
          }
          break;
        }
        lambda *= 4.0;
      }
      if (!accepted || converged) break;
    }
  }
  const FitState unsorted = s;
  sort_atoms(s);
  fit.residual_v2 = rss;
  fit.penalty = penalty;
  fit.state = s;
  if (normal_matrix && !s.atoms.empty() && all_free) {
    fit.normal_matrix = sorted_normal_matrix(normal_jj, unsorted, s, per_atom);
  } else if (normal_matrix && !s.atoms.empty()) {
    // J^T J over every free parameter of the whole fit: all atoms, and the shared ones.
    moving.resize(s.atoms.size());
    std::iota(moving.begin(), moving.end(), 0);
    shared = L.shared() > 0;
    p_count = moving.size() * per_atom + (shared ? L.shared() : 0);
    frozen.reset(m_count);
    values.resize(moving.size());
    Eigen::VectorXd unused_gradient;
    FitState final_state = fit.state;
    evaluate(final_state, &fit.normal_matrix, &unused_gradient, nullptr, nullptr);
  }
  return fit;
}

}  // namespace stengmc
