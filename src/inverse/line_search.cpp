#include "inverse/line_search.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace stengmc {

LineSearch::LineSearch(const RecordModel& model, LineProposals& proposals, std::span<const double> record,
                       const LineSearchOptions& options)
    : model_(&model), proposals_(&proposals), record_(record), options_(options) {
  if (record.size() != model.samples()) throw Error("LineSearch: the record and the model's grid differ in length");
}

std::vector<double> LineSearch::residual(std::span<const double> k) const {
  std::vector<double> r(record_.size());
  residual_norm(k, nullptr, r);
  return r;
}

double LineSearch::residual_norm(std::span<const double> k, Eigen::MatrixXd* jacobian, std::vector<double>& r) const {
  r.resize(record_.size());
  model_->evaluate(k, r, jacobian);
  double sum = 0.0;
  for (std::size_t m = 0; m < r.size(); ++m) {
    r[m] = record_[m] - r[m];
    sum += r[m] * r[m];
  }
  return sum;
}

OrderFit LineSearch::refine(std::vector<double> k, const std::vector<bool>& active, bool normal_matrix) {
  OrderFit fit;
  const std::size_t m_count = record_.size();
  std::vector<std::size_t> moving;
  for (std::size_t i = 0; i < k.size(); ++i)
    if (active.empty() || active[i]) moving.push_back(i);
  const auto n = static_cast<Eigen::Index>(moving.size());
  const double lo = std::log(model_->atoms().min_stiffness()), hi = std::log(model_->atoms().max_stiffness());
  // The atoms that stay put are summed once.
  AtomSums frozen;
  frozen.reset(m_count);
  for (std::size_t i = 0; i < k.size(); ++i)
    if (!(active.empty() || active[i])) model_->add(k[i], frozen);
  AtomSums sums;
  std::vector<double> voltage(m_count);
  // Squared residual at `trial` (the moving atoms' values), with their Jacobian columns.
  auto evaluate = [&](const std::vector<double>& trial, Eigen::MatrixXd& jacobian, std::vector<double>& r) {
    sums = frozen;
    jacobian.resize(static_cast<Eigen::Index>(m_count), n);
    for (Eigen::Index j = 0; j < n; ++j)
      model_->add(trial[moving[static_cast<std::size_t>(j)]], sums, std::span<double>(jacobian.col(j).data(), m_count));
    model_->voltage(sums, voltage);
    r.resize(m_count);
    double sum = 0.0;
    for (std::size_t m = 0; m < m_count; ++m) {
      r[m] = record_[m] - voltage[m];
      sum += r[m] * r[m];
    }
    return sum;
  };
  std::vector<double> r, trial_r;
  Eigen::MatrixXd jacobian, trial_jacobian;
  double rss = evaluate(k, jacobian, r);
  if (n > 0) {
    double lambda = 1e-3;
    std::vector<double> trial = k;
    for (std::size_t iteration = 0; iteration < options_.max_iterations; ++iteration) {
      fit.iterations = iteration + 1;
      const Eigen::Map<const Eigen::VectorXd> residual_vector(r.data(), static_cast<Eigen::Index>(r.size()));
      const Eigen::MatrixXd normal = jacobian.transpose() * jacobian;
      const Eigen::VectorXd gradient = jacobian.transpose() * residual_vector;
      bool accepted = false;
      double step_size = 0.0;
      while (lambda < 1e10) {
        Eigen::MatrixXd damped = normal;
        for (Eigen::Index i = 0; i < n; ++i) damped(i, i) += lambda * normal(i, i) + 1e-300;
        const Eigen::VectorXd delta = damped.ldlt().solve(gradient);
        step_size = delta.cwiseAbs().maxCoeff();
        for (Eigen::Index j = 0; j < n; ++j) {
          const std::size_t i = moving[static_cast<std::size_t>(j)];
          trial[i] = std::exp(std::clamp(std::log(k[i]) + delta(j), lo, hi));
        }
        const double trial_rss = evaluate(trial, trial_jacobian, trial_r);
        if (trial_rss < rss) {
          const double gain = rss - trial_rss;
          k = trial;
          r.swap(trial_r);
          jacobian.swap(trial_jacobian);
          const double previous = rss;
          rss = trial_rss;
          lambda = std::max(lambda / 3.0, 1e-12);
          accepted = true;
          if (gain <= 1e-12 * previous) step_size = 0.0;  // converged
          break;
        }
        lambda *= 4.0;
      }
      if (!accepted || step_size < 1e-10) break;
    }
  }
  // Ascending order, the normal matrix permuted with it.
  std::vector<std::size_t> order(k.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return k[a] < k[b]; });
  fit.residual_v2 = rss;
  fit.stiffness_n_per_m.resize(k.size());
  for (std::size_t i = 0; i < order.size(); ++i) fit.stiffness_n_per_m[i] = k[order[i]];
  if (normal_matrix && !k.empty()) {
    Eigen::MatrixXd full;
    model_->evaluate(fit.stiffness_n_per_m, voltage, &full);
    fit.normal_matrix = full.transpose() * full;
  }
  return fit;
}

double LineSearch::exact_score(double k, std::span<const double> residual) const {
  std::vector<double> atom(residual.size());
  model_->atoms().evaluate(k, atom);
  double dot = 0.0, energy = 0.0;
  for (std::size_t m = 0; m < atom.size(); ++m) {
    dot += residual[m] * atom[m];
    energy += atom[m] * atom[m];
  }
  return 2.0 * dot - energy;
}

LineCandidate LineSearch::best_addition(std::span<const double> residual) {
  const std::vector<LineCandidate> candidates = proposals_->propose(residual, options_.candidates);
  LineCandidate best{model_->atoms().min_stiffness(), -INFINITY};
  const double lo = std::log(model_->atoms().min_stiffness()), hi = std::log(model_->atoms().max_stiffness());
  const double d = model_->atoms().device().damping_rate_per_s();
  for (const LineCandidate& c : candidates) {
    // Golden-section search of the exact score in ln k over +-2 line widths (d / pi in f:
    // 2 d / omega in ln omega, twice that in ln k) around the proposal.
    const double omega = model_->atoms().device().angular_frequency(c.stiffness_n_per_m);
    const double half_width = 2.0 * 2.0 * (2.0 * d / omega);
    double a = std::max(lo, std::log(c.stiffness_n_per_m) - half_width);
    double b = std::min(hi, std::log(c.stiffness_n_per_m) + half_width);
    constexpr double GOLDEN = 0.6180339887498949;
    double x1 = b - GOLDEN * (b - a), x2 = a + GOLDEN * (b - a);
    double f1 = exact_score(std::exp(x1), residual), f2 = exact_score(std::exp(x2), residual);
    // 10 steps shrink the bracket to 0.8 % of its width, 0.03 line widths: enough for a start
    // the joint fit then polishes.
    for (int iteration = 0; iteration < 10; ++iteration) {
      if (f1 > f2) {
        b = x2, x2 = x1, f2 = f1;
        x1 = b - GOLDEN * (b - a);
        f1 = exact_score(std::exp(x1), residual);
      } else {
        a = x1, x1 = x2, f1 = f2;
        x2 = a + GOLDEN * (b - a);
        f2 = exact_score(std::exp(x2), residual);
      }
    }
    const double x = f1 > f2 ? x1 : x2;
    const double score = std::max(f1, f2);
    if (score > best.score_v2) best = {std::exp(x), score};
  }
  return best;
}

std::vector<OrderFit> LineSearch::search(std::size_t max_count, std::size_t min_count) {
  std::vector<OrderFit> fits;
  fits.push_back(refine({}));
  std::size_t stop = max_count;  // the greedy count; fits go on extra_orders beyond it
  const double d = model_->atoms().device().damping_rate_per_s();
  for (std::size_t n = 1; n <= max_count && (n <= stop + options_.extra_orders || n <= min_count); ++n) {
    const OrderFit& previous = fits.back();
    const LineCandidate best = best_addition(residual(previous.stiffness_n_per_m));
    std::vector<double> k = previous.stiffness_n_per_m;
    k.push_back(best.stiffness_n_per_m);
    // The new atom and its neighbours move: a line width d / pi is 2 d / omega in ln omega,
    // twice that in ln k.
    const double window = NEIGHBOURHOOD_WIDTHS * 4.0 * d / model_->atoms().device().angular_frequency(best.stiffness_n_per_m);
    std::vector<bool> active(k.size());
    for (std::size_t i = 0; i < k.size(); ++i) active[i] = std::abs(std::log(k[i] / best.stiffness_n_per_m)) < window;
    fits.push_back(refine(std::move(k), active, false));
    // Judged on the joint refit, not on the addition alone: an atom that only becomes
    // useful once its neighbours move is still found.
    const double gain = fits[n - 1].residual_v2 - fits[n].residual_v2;
    if (stop == max_count && gain < options_.stop_fraction * proposals_->atom_energy(best.stiffness_n_per_m))
      stop = n - 1;
  }
  // The orders the posterior weighs, refitted in full (none below min_count: it weighs none).
  for (std::size_t n = std::max(stop > 0 ? stop - 1 : 0, min_count); n < fits.size(); ++n)
    if (n > 0) fits[n] = refine(fits[n].stiffness_n_per_m);
  return fits;
}

}  // namespace stengmc
