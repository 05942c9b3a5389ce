#include "inverse/load_prior.hpp"

#include <algorithm>
#include <boost/random/uniform_real_distribution.hpp>
#include <cmath>

#include "core/constants.hpp"
#include "core/random_stream.hpp"
#include "surface/load_spread.hpp"

namespace stengmc {

namespace {
constexpr std::size_t DRAWS = 200'000;
constexpr double KERNEL = 0.05;    // Gaussian kernel sd in ln rho
constexpr double TABLE_STEP = 0.01;
// The table's own seed: the prior's density is a property of the prior, not of any run.
constexpr std::uint64_t SEED = 0x10ad;
}  // namespace

LoadPrior::LoadPrior(const InversePrior& prior) {
  const double tau = prior.parameter_tolerance;
  fixed_ = prior.load_cv[1] == 0.0 && tau == 0.0;
  if (fixed_) return;
  RandomEngine engine = random_stream(SEED, 0, StreamKind::draws);
  boost::random::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> x(DRAWS);
  // One spread law per CV on a fine grid of the range (solving for the separation each draw
  // would cost more than the whole table needs).
  constexpr std::size_t CVS = 64;
  std::vector<LoadSpread> spreads;
  for (std::size_t c = 0; c < CVS; ++c) {
    const double cv = prior.load_cv[0] + (prior.load_cv[1] - prior.load_cv[0]) * (static_cast<double>(c) + 0.5) / CVS;
    spreads.emplace_back(1.0, cv);
  }
  for (double& v : x) {
    const LoadSpread& spread = spreads[std::min(CVS - 1, static_cast<std::size_t>(unit(engine) * CVS))];
    const double rho = spread.draw(engine).load_n * (1.0 + tau * (2.0 * unit(engine) - 1.0)) * (1.0 + tau * (2.0 * unit(engine) - 1.0));
    v = std::log(std::max(rho, 1e-300));
  }
  std::sort(x.begin(), x.end());
  support_ = {std::exp(x[DRAWS / 10000]), std::exp(x[DRAWS - 1 - DRAWS / 10000])};
  double mean = 0.0, square = 0.0;
  for (double v : x) mean += v / DRAWS;
  for (double v : x) square += (v - mean) * (v - mean) / DRAWS;
  mean_log_ = mean;
  sd_log_ = std::sqrt(square);
  // Kernel density on a grid over the sample's range (the 1e-6 quantiles) plus 4 kernels.
  first_ = std::max(x.front(), std::log(support_.first) - 3.0) - 4.0 * KERNEL;
  const double last = x.back() + 4.0 * KERNEL;
  step_ = TABLE_STEP;
  const auto points = static_cast<std::size_t>(std::ceil((last - first_) / step_)) + 1;
  std::vector<double> density(points, 0.0);
  const double norm = 1.0 / (DRAWS * KERNEL * std::sqrt(2.0 * PI));
  for (double v : x) {
    const auto lo = static_cast<std::ptrdiff_t>(std::floor((v - 5.0 * KERNEL - first_) / step_));
    const auto hi = static_cast<std::ptrdiff_t>(std::ceil((v + 5.0 * KERNEL - first_) / step_));
    for (std::ptrdiff_t i = std::max<std::ptrdiff_t>(0, lo); i <= std::min<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(points) - 1, hi); ++i) {
      const double z = (first_ + step_ * static_cast<double>(i) - v) / KERNEL;
      density[static_cast<std::size_t>(i)] += norm * std::exp(-0.5 * z * z);
    }
  }
  log_density_.resize(points);
  for (std::size_t i = 0; i < points; ++i) log_density_[i] = std::log(std::max(density[i], 1e-300));
}

double LoadPrior::log_density(double log_ratio) const {
  if (fixed_) return 0.0;
  const double x = (log_ratio - first_) / step_;
  const double last = static_cast<double>(log_density_.size() - 1);
  // Beyond the table: falling as a Gaussian tail of the kernel's width would.
  if (x <= 0.0) return log_density_.front() - 0.5 * std::pow(x * step_ / KERNEL, 2) - 50.0 * (-x) * step_ / KERNEL;
  if (x >= last) return log_density_.back() - 0.5 * std::pow((x - last) * step_ / KERNEL, 2) - 50.0 * (x - last) * step_ / KERNEL;
  const auto i = static_cast<std::size_t>(x);
  const double f = x - static_cast<double>(i);
  return log_density_[i] + f * (log_density_[i + 1] - log_density_[i]);
}

}  // namespace stengmc
