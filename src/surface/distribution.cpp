#include "core/format.hpp"
#include "surface/distribution.hpp"

#include <algorithm>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/weibull.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/random/gamma_distribution.hpp>
#include <boost/random/lognormal_distribution.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_int_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <boost/random/weibull_distribution.hpp>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace stengmc {

namespace bm = boost::math;

namespace {

constexpr double MIN_MASS = 1e-12;  // truncations keeping less than this are rejected

// Uniform on the open interval (0, 1) from the top 53 bits: (k + 1/2) 2^-53, so that
// quantiles of unbounded laws stay finite. A fixed algorithm, like Boost's.
double open_uniform(RandomEngine& engine) { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; }

// Standard normal cdf and density, safe at ±infinity.
double phi_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
double phi_pdf(double z) { return std::isinf(z) ? 0.0 : std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI); }

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

}  // namespace

// ---------------------------------------------------------------- construction

Distribution::Distribution(Kind kind, double a, double b, double min, double max)
    : kind_(kind), a_(a), b_(b), min_(min), max_(max) {}

Distribution Distribution::normal(double mean, double std, double min, double max) {
  if (!(std > 0.0)) throw InputError("normal distribution: std = " + format_number(std) + " must be > 0");
  Distribution d(Kind::normal, mean, std, -INFINITY, INFINITY);
  d.set_truncation(min, max);
  return d;
}

Distribution Distribution::lognormal(double median, double sigma_log, double min, double max) {
  if (!(median > 0.0)) throw InputError("lognormal distribution: median = " + format_number(median) + " must be > 0");
  if (!(sigma_log > 0.0)) throw InputError("lognormal distribution: sigma_log = " + format_number(sigma_log) + " must be > 0");
  Distribution d(Kind::lognormal, median, sigma_log, 0.0, INFINITY);
  d.set_truncation(std::max(min, 0.0), max);
  return d;
}

namespace {
//! Gamma and Weibull share their parameters (shape, scale > 0) and support [0, inf).
void check_shape_and_scale(const char* name, double shape, double scale) {
  if (!(shape > 0.0)) throw InputError(std::string(name) + " distribution: shape = " + format_number(shape) + " must be > 0");
  if (!(scale > 0.0)) throw InputError(std::string(name) + " distribution: scale = " + format_number(scale) + " must be > 0");
}
}  // namespace

Distribution Distribution::shape_scale(Kind kind, double shape, double scale, double min, double max) {
  check_shape_and_scale(kind == Kind::gamma ? "gamma" : "weibull", shape, scale);
  Distribution d(kind, shape, scale, 0.0, INFINITY);
  d.set_truncation(std::max(min, 0.0), max);
  return d;
}

Distribution Distribution::gamma(double shape, double scale, double min, double max) {
  return shape_scale(Kind::gamma, shape, scale, min, max);
}

Distribution Distribution::weibull(double shape, double scale, double min, double max) {
  return shape_scale(Kind::weibull, shape, scale, min, max);
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
  Distribution d(Kind::fixed, 0.0, 0.0, values.front(), values.back());
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
  Distribution d(Kind::empirical, 0.0, 0.0, bins.front().lower, bins.back().upper);
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

// ---------------------------------------------------------------- the untruncated laws

double Distribution::base_cdf(double x) const {
  if (x == INFINITY) return 1.0;
  if (x == -INFINITY) return 0.0;
  switch (kind_) {
    case Kind::normal: return bm::cdf(bm::normal(a_, b_), x);
    case Kind::lognormal: return x <= 0.0 ? 0.0 : bm::cdf(bm::lognormal(std::log(a_), b_), x);
    case Kind::gamma: return x <= 0.0 ? 0.0 : bm::cdf(bm::gamma_distribution<>(a_, b_), x);
    case Kind::weibull: return x <= 0.0 ? 0.0 : bm::cdf(bm::weibull(a_, b_), x);
    default: return 0.0;  // histogram kinds do not use the base law
  }
}

double Distribution::base_sf(double x) const {
  if (x == INFINITY) return 0.0;
  if (x == -INFINITY) return 1.0;
  switch (kind_) {
    case Kind::normal: return bm::cdf(bm::complement(bm::normal(a_, b_), x));
    case Kind::lognormal: return x <= 0.0 ? 1.0 : bm::cdf(bm::complement(bm::lognormal(std::log(a_), b_), x));
    case Kind::gamma: return x <= 0.0 ? 1.0 : bm::cdf(bm::complement(bm::gamma_distribution<>(a_, b_), x));
    case Kind::weibull: return x <= 0.0 ? 1.0 : bm::cdf(bm::complement(bm::weibull(a_, b_), x));
    default: return 1.0;
  }
}

double Distribution::base_pdf(double x) const {
  switch (kind_) {
    case Kind::normal: return bm::pdf(bm::normal(a_, b_), x);
    case Kind::lognormal: return x <= 0.0 ? 0.0 : bm::pdf(bm::lognormal(std::log(a_), b_), x);
    case Kind::gamma: return x <= 0.0 ? 0.0 : bm::pdf(bm::gamma_distribution<>(a_, b_), x);
    case Kind::weibull: return x <= 0.0 ? 0.0 : bm::pdf(bm::weibull(a_, b_), x);
    default: return 0.0;
  }
}

double Distribution::base_quantile(double p) const {
  switch (kind_) {
    case Kind::normal: return bm::quantile(bm::normal(a_, b_), p);
    case Kind::lognormal: return bm::quantile(bm::lognormal(std::log(a_), b_), p);
    case Kind::gamma: return bm::quantile(bm::gamma_distribution<>(a_, b_), p);
    default: return bm::quantile(bm::weibull(a_, b_), p);
  }
}

double Distribution::base_quantile_complement(double q) const {
  switch (kind_) {
    case Kind::normal: return bm::quantile(bm::complement(bm::normal(a_, b_), q));
    case Kind::lognormal: return bm::quantile(bm::complement(bm::lognormal(std::log(a_), b_), q));
    case Kind::gamma: return bm::quantile(bm::complement(bm::gamma_distribution<>(a_, b_), q));
    default: return bm::quantile(bm::complement(bm::weibull(a_, b_), q));
  }
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
  const double x = lower_target <= 0.5 ? base_quantile(lower_target)
                                       : base_quantile_complement(std::max(sf_max_ + q * mass_, 1e-300));
  return std::clamp(x, min_, max_);
}

double Distribution::sample(RandomEngine& engine) const {
  if (!truncated_) {
    switch (kind_) {
      case Kind::normal: return boost::random::normal_distribution<double>(a_, b_)(engine);
      case Kind::lognormal: return boost::random::lognormal_distribution<double>(std::log(a_), b_)(engine);
      case Kind::gamma: return boost::random::gamma_distribution<double>(a_, b_)(engine);
      case Kind::weibull: return boost::random::weibull_distribution<double>(a_, b_)(engine);
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
  return base_pdf(x) / mass_;
}

// E[Y^k; min <= X <= max] / mass for the standardised variable Y (normal: (X − mean)/std;
// others: X/scale, X/median), from closed-form partial moments:
//   normal     M_k = (k−1) M_{k−2} + a^{k−1}φ(a) − b^{k−1}φ(b)   (integration by parts)
//   lognormal  E[Y^k; ·] = e^{k²s²/2} [Φ((ln b − k s²)/s) − Φ((ln a − k s²)/s)]
//   gamma      E[Y^k; ·] = Γ(α+k)/Γ(α) [P(α+k, b) − P(α+k, a)]
//   weibull    E[Y^k; ·] = Γ(1+k/β) [P(1+k/β, b^β) − P(1+k/β, a^β)]
// (P the regularised lower incomplete gamma function; a, b the standardised bounds.)
double Distribution::standard_partial_moment(int k) const {
  if (k == 0) return 1.0;
  if (kind_ == Kind::normal) {
    const double lo = (min_ - a_) / b_, hi = (max_ - a_) / b_;
    auto term = [](double z, int power) { return std::isinf(z) ? 0.0 : std::pow(z, power) * phi_pdf(z); };
    double m_prev = mass_, m = phi_pdf(lo) - phi_pdf(hi);  // M_0, M_1 (unnormalised)
    for (int j = 2; j <= k; ++j) {
      const double next = (j - 1) * m_prev + term(lo, j - 1) - term(hi, j - 1);
      m_prev = m;
      m = next;
    }
    return m / mass_;
  }
  const double lo = min_ / (kind_ == Kind::lognormal ? a_ : b_), hi = max_ / (kind_ == Kind::lognormal ? a_ : b_);
  if (kind_ == Kind::lognormal) {
    const double s = b_, shift = k * s * s;
    auto z = [&](double y) { return y <= 0.0 ? -INFINITY : (std::log(y) - shift) / s; };
    return std::exp(0.5 * k * k * s * s) * (phi_cdf(z(hi)) - phi_cdf(z(lo))) / mass_;
  }
  const double order = kind_ == Kind::gamma ? a_ + k : 1.0 + k / a_;
  auto arg = [&](double y) { return kind_ == Kind::gamma ? y : std::pow(y, a_); };
  auto p = [&](double y) { return std::isinf(y) ? 1.0 : bm::gamma_p(order, arg(y)); };
  const double factor = kind_ == Kind::gamma ? bm::tgamma_ratio(a_ + k, a_) : bm::tgamma(order);
  return factor * (p(hi) - p(lo)) / mass_;
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
  return kind_ == Kind::normal ? a_ + b_ * m1 : (kind_ == Kind::lognormal ? a_ : b_) * m1;
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
  const double scale = kind_ == Kind::lognormal ? a_ : b_;
  const double mu = standard_partial_moment(1);
  for (int j = 0; j <= k; ++j) sum += binomial(k, j) * standard_partial_moment(j) * std::pow(-mu, k - j);
  return std::pow(scale, k) * sum;
}

}  // namespace stengmc
