#include <boost/math/distributions/lognormal.hpp>
#include <boost/random/lognormal_distribution.hpp>
#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/standard_normal.hpp"
#include "surface/continuous_law.hpp"

namespace stengmc {

namespace {

namespace bm = boost::math;

//! ln X ~ N(ln median, sigma_log^2).
class LognormalLaw final : public ContinuousLaw {
 public:
  LognormalLaw(double median, double sigma_log) : median_(median), sigma_log_(sigma_log) {}
  double cdf(double x) const override { return x <= 0.0 ? 0.0 : bm::cdf(law(), x); }
  double sf(double x) const override { return x <= 0.0 ? 1.0 : bm::cdf(bm::complement(law(), x)); }
  double pdf(double x) const override { return x <= 0.0 ? 0.0 : bm::pdf(law(), x); }
  double quantile(double p) const override { return bm::quantile(law(), p); }
  double quantile_complement(double q) const override { return bm::quantile(bm::complement(law(), q)); }
  double sample(RandomEngine& engine) const override {
    return boost::random::lognormal_distribution<double>(std::log(median_), sigma_log_)(engine);
  }
  double scale() const override { return median_; }
  // Y = X / median: E[Y^k; a <= Y <= b] = e^{k^2 s^2 / 2} [Phi((ln b - k s^2)/s) - Phi((ln a - k s^2)/s)].
  double standard_partial_moment(int k, double lo, double hi, double mass) const override {
    const double s = sigma_log_, shift = k * s * s;
    auto z = [&](double y) { return y <= 0.0 ? -INFINITY : (std::log(y) - shift) / s; };
    return std::exp(0.5 * k * k * s * s) * (phi_cdf(z(hi)) - phi_cdf(z(lo))) / mass;
  }

 private:
  bm::lognormal law() const { return bm::lognormal(std::log(median_), sigma_log_); }
  double median_, sigma_log_;
};

std::shared_ptr<const ContinuousLaw> make(double median, double sigma_log) {
  if (!(median > 0.0)) throw InputError("lognormal distribution: median = " + format_number(median) + " must be > 0");
  if (!(sigma_log > 0.0)) throw InputError("lognormal distribution: sigma_log = " + format_number(sigma_log) + " must be > 0");
  return std::make_shared<LognormalLaw>(median, sigma_log);
}

}  // namespace

ContinuousFamily lognormal_family() { return {"lognormal", "median", "sigma_log", false, 0.0, make}; }

}  // namespace stengmc
