#include "core/format.hpp"
#include "surface/distribution.hpp"

#include <algorithm>
#include <boost/random/uniform_int_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/standard_normal.hpp"

namespace stengmc {

namespace {

constexpr double MIN_MASS = 1e-12;  // truncations keeping less than this are rejected

// Uniform on the open interval (0, 1) from the top 53 bits: (k + 1/2) 2^-53, so that
// quantiles of unbounded laws stay finite. A fixed algorithm, like Boost's.
double open_uniform(RandomEngine& engine) { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; }

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

}  // namespace

// ---------------------------------------------------------------- construction

Distribution::Distribution(Kind kind, double min, double max) : kind_(kind), min_(min), max_(max) {}

Distribution Distribution::continuous(std::string_view name, double first, double second, double min, double max) {
  const ContinuousFamily* family = find_continuous_family(name);
  if (!family) throw Error("Distribution::continuous: no family named " + std::string(name));
  Distribution d(Kind::continuous, family->support_lower, INFINITY);
  d.family_ = family;
  d.law_ = family->make(first, second);
  d.set_truncation(std::max(min, family->support_lower), max);
  return d;
}

Distribution Distribution::normal(double mean, double std, double min, double max) {
  return continuous("normal", mean, std, min, max);
}

Distribution Distribution::lognormal(double median, double sigma_log, double min, double max) {
  return continuous("lognormal", median, sigma_log, min, max);
}

Distribution Distribution::gamma(double shape, double scale, double min, double max) {
  return continuous("gamma", shape, scale, min, max);
}

Distribution Distribution::weibull(double shape, double scale, double min, double max) {
  return continuous("weibull", shape, scale, min, max);
}

std::string_view Distribution::kind_name() const {
  switch (kind_) {
    case Kind::continuous: return family_->name;
    case Kind::uniform: return "uniform";
    case Kind::fixed: return "fixed";
    case Kind::empirical: break;
  }
  return "empirical";
}

Distribution Distribution::uniform(double min, double max) {
  if (!(std::isfinite(min) && std::isfinite(max) && max > min))
    throw InputError("uniform distribution: max = " + format_number(max) + " must be > min = " + format_number(min));
  Distribution d = empirical({{min, max, 1.0}});
  d.kind_ = Kind::uniform;
  return d;
}

Distribution Distribution::fixed(std::vector<double> values) {
  if (values.empty()) throw InputError("fixed distribution: values must hold at least one number");
  for (double v : values)
    if (!std::isfinite(v)) throw InputError("fixed distribution: value " + format_number(v) + " is not finite");
  std::sort(values.begin(), values.end());
  Distribution d(Kind::fixed, values.front(), values.back());
  d.values_ = std::move(values);
  return d;
}

Distribution Distribution::empirical(std::vector<Bin> bins) {
  if (bins.empty()) throw InputError("empirical distribution: no bins");
  double total = 0.0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const Bin& b = bins[i];
    if (!(std::isfinite(b.lower) && std::isfinite(b.upper) && b.upper > b.lower))
      throw InputError("empirical distribution: bin " + std::to_string(i) + " needs lower < upper");
    if (!(b.weight >= 0.0 && std::isfinite(b.weight)))
      throw InputError("empirical distribution: bin " + std::to_string(i) + " has a negative weight");
    if (i > 0 && b.lower < bins[i - 1].upper)
      throw InputError("empirical distribution: bin " + std::to_string(i) + " overlaps the previous one");
    total += b.weight;
  }
  if (!(total > 0.0)) throw InputError("empirical distribution: the weights sum to zero");
  Distribution d(Kind::empirical, bins.front().lower, bins.back().upper);
  double running = 0.0;
  for (Bin& b : bins) {
    b.weight /= total;
    running += b.weight;
    d.cumulative_.push_back(running);
  }
  d.cumulative_.back() = 1.0;  // exact, whatever the rounding of the sum
  d.bins_ = std::move(bins);
  return d;
}

// The family's law at x, with the infinite ends (untruncated sides) exact.
double Distribution::base_cdf(double x) const {
  if (x == INFINITY) return 1.0;
  if (x == -INFINITY) return 0.0;
  return law_->cdf(x);
}

double Distribution::base_sf(double x) const {
  if (x == INFINITY) return 0.0;
  if (x == -INFINITY) return 1.0;
  return law_->sf(x);
}

void Distribution::set_truncation(double min, double max) {
  if (std::isnan(min) || std::isnan(max) || !(max > min))
    throw InputError("truncation: max = " + format_number(max) + " must be > min = " + format_number(min));
  truncated_ = min > min_ || max < max_;
  min_ = std::max(min, min_);
  max_ = std::min(max, max_);
  cdf_min_ = base_cdf(min_);
  sf_min_ = base_sf(min_);
  cdf_max_ = base_cdf(max_);
  sf_max_ = base_sf(max_);
  // Take the difference on the side where it does not cancel (upper-tail truncations).
  mass_ = cdf_min_ > 0.5 ? sf_min_ - sf_max_ : cdf_max_ - cdf_min_;
  if (!(mass_ >= MIN_MASS))
    throw InputError("truncation to [" + format_number(min_) + ", " + format_number(max_) + "] leaves probability " + format_number(mass_) +
                     " < 1e-12");
}

// ---------------------------------------------------------------- sampling and evaluation

// Inverse CDF of the truncated law at p, given q = 1 − p accurately as well: the target
// F(min) + p·mass (= 1 − [S(max) + q·mass]) is inverted on whichever side of the median
// it lies, so neither tail loses precision to 1 − p rounding.
double Distribution::from_probability(double p, double q) const {
  if (kind_ == Kind::fixed) {
    const auto n = values_.size();
    const auto i = static_cast<std::size_t>(std::ceil(p * static_cast<double>(n)));
    return values_[std::min(n - 1, i == 0 ? 0 : i - 1)];
  }
  if (kind_ == Kind::empirical || kind_ == Kind::uniform) {
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), p);
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(it - cumulative_.begin()), bins_.size() - 1);
    const double below = i == 0 ? 0.0 : cumulative_[i - 1];
    const Bin& b = bins_[i];
    return std::clamp(b.lower + (b.upper - b.lower) * (p - below) / b.weight, b.lower, b.upper);
  }
  const double lower_target = cdf_min_ + p * mass_;
  const double x = lower_target <= 0.5 ? law_->quantile(lower_target)
                                       : law_->quantile_complement(std::max(sf_max_ + q * mass_, 1e-300));
  return std::clamp(x, min_, max_);
}

double Distribution::sample(RandomEngine& engine) const {
  if (!truncated_) {
    switch (kind_) {
      case Kind::continuous: return law_->sample(engine);
      case Kind::uniform: return boost::random::uniform_real_distribution<double>(min_, max_)(engine);
      case Kind::fixed:
        return values_[boost::random::uniform_int_distribution<std::size_t>(0, values_.size() - 1)(engine)];
      case Kind::empirical: break;
    }
  }
  const double p = open_uniform(engine);
  return from_probability(p, 1.0 - p);
}

double Distribution::quantile(double p) const { return from_probability(p, 1.0 - p); }

double Distribution::quantile_of_normal_score(double z) const { return from_probability(phi_cdf(z), phi_cdf(-z)); }

double Distribution::cdf(double x) const {
  if (x < min_) return 0.0;
  if (x >= max_) return 1.0;
  if (kind_ == Kind::fixed)
    return static_cast<double>(std::upper_bound(values_.begin(), values_.end(), x) - values_.begin()) /
           static_cast<double>(values_.size());
  if (kind_ == Kind::empirical || kind_ == Kind::uniform) {
    double f = 0.0;
    for (const Bin& b : bins_) f += b.weight * std::clamp((x - b.lower) / (b.upper - b.lower), 0.0, 1.0);
    return std::min(f, 1.0);
  }
  const double f = cdf_min_ > 0.5 ? (sf_min_ - base_sf(x)) / mass_ : (base_cdf(x) - cdf_min_) / mass_;
  return std::clamp(f, 0.0, 1.0);
}

double Distribution::pdf(double x) const {
  if (x < min_ || x > max_ || kind_ == Kind::fixed) return 0.0;
  if (kind_ == Kind::empirical || kind_ == Kind::uniform) {
    for (const Bin& b : bins_)
      if (x >= b.lower && x < b.upper) return b.weight / (b.upper - b.lower);
    return 0.0;
  }
  return law_->pdf(x) / mass_;
}

// E[Y^k; min <= X <= max] / mass for the standardised variable Y = (X - location)/scale of
// the family, from its closed-form partial moments (continuous_law.hpp).
double Distribution::standard_partial_moment(int k) const {
  if (k == 0) return 1.0;
  const double location = law_->location(), scale = law_->scale();
  const double lo = (min_ - location) / scale, hi = (max_ - location) / scale;
  return law_->standard_partial_moment(k, lo, hi, mass_);
}

double Distribution::mean() const {
  if (kind_ == Kind::fixed) {
    double s = 0.0;
    for (double v : values_) s += v;
    return s / static_cast<double>(values_.size());
  }
  if (kind_ == Kind::empirical || kind_ == Kind::uniform) {
    double s = 0.0;
    for (const Bin& b : bins_) s += b.weight * 0.5 * (b.lower + b.upper);
    return s;
  }
  const double m1 = standard_partial_moment(1);
  return law_->location() + law_->scale() * m1;
}

double Distribution::variance() const { return central_moment(2); }

double Distribution::central_moment(int k) const {
  if (k < 2 || k > 4) throw Error("Distribution::central_moment: k = " + std::to_string(k) + " is not 2, 3 or 4");
  const double m = mean();
  double sum = 0.0;
  if (kind_ == Kind::fixed) {
    for (double v : values_) sum += std::pow(v - m, k);
    return sum / static_cast<double>(values_.size());
  }
  if (kind_ == Kind::empirical || kind_ == Kind::uniform) {
    // Uniform on [l, u): E[(X − m)^k] = ((u − m)^{k+1} − (l − m)^{k+1}) / ((k + 1)(u − l)).
    for (const Bin& b : bins_)
      sum += b.weight * (std::pow(b.upper - m, k + 1) - std::pow(b.lower - m, k + 1)) / ((k + 1) * (b.upper - b.lower));
    return sum;
  }
  // Binomial expansion about the standardised mean; Y is O(1), so the cancellation costs
  // about (mean/std)^k relative — negligible for the spreads of asperity populations.
  const double scale = law_->scale();
  const double mu = standard_partial_moment(1);
  for (int j = 0; j <= k; ++j) sum += binomial(k, j) * standard_partial_moment(j) * std::pow(-mu, k - j);
  return std::pow(scale, k) * sum;
}

}  // namespace stengmc
