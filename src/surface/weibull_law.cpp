#include <boost/math/distributions/weibull.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/random/weibull_distribution.hpp>
#include <cmath>

#include "surface/continuous_law.hpp"
#include "surface/shape_scale_law.hpp"

namespace stengmc {

namespace {

namespace bm = boost::math;

//! cdf 1 - exp(-(x/scale)^shape).
class WeibullLaw final : public ContinuousLaw {
 public:
  WeibullLaw(double shape, double scale) : shape_(shape), scale_(scale) {}
  double cdf(double x) const override { return x <= 0.0 ? 0.0 : bm::cdf(law(), x); }
  double sf(double x) const override { return x <= 0.0 ? 1.0 : bm::cdf(bm::complement(law(), x)); }
  double pdf(double x) const override { return x <= 0.0 ? 0.0 : bm::pdf(law(), x); }
  double quantile(double p) const override { return bm::quantile(law(), p); }
  double quantile_complement(double q) const override { return bm::quantile(bm::complement(law(), q)); }
  double sample(RandomEngine& engine) const override { return boost::random::weibull_distribution<double>(shape_, scale_)(engine); }
  double scale() const override { return scale_; }
  // Y = X / scale: E[Y^k; a <= Y <= b] = Gamma(1+k/shape) [P(1+k/shape, b^shape) - P(1+k/shape, a^shape)].
  double standard_partial_moment(int k, double lo, double hi, double mass) const override {
    const double order = 1.0 + k / shape_;
    auto p = [&](double y) { return std::isinf(y) ? 1.0 : bm::gamma_p(order, std::pow(y, shape_)); };
    return bm::tgamma(order) * (p(hi) - p(lo)) / mass;
  }

 private:
  bm::weibull law() const { return bm::weibull(shape_, scale_); }
  double shape_, scale_;
};

std::shared_ptr<const ContinuousLaw> make(double shape, double scale) {
  check_shape_and_scale("weibull", shape, scale);
  return std::make_shared<WeibullLaw>(shape, scale);
}

}  // namespace

ContinuousFamily weibull_family() { return {"weibull", "shape", "scale", false, 0.0, make}; }

}  // namespace stengmc
