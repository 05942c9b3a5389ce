#include <boost/math/distributions/gamma.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/random/gamma_distribution.hpp>
#include <cmath>

#include "surface/continuous_law.hpp"
#include "surface/shape_scale_law.hpp"

namespace stengmc {

namespace {

namespace bm = boost::math;

//! pdf proportional to x^(shape-1) exp(-x/scale).
class GammaLaw final : public ContinuousLaw {
 public:
  GammaLaw(double shape, double scale) : shape_(shape), scale_(scale) {}
  double cdf(double x) const override { return x <= 0.0 ? 0.0 : bm::cdf(law(), x); }
  double sf(double x) const override { return x <= 0.0 ? 1.0 : bm::cdf(bm::complement(law(), x)); }
  double pdf(double x) const override { return x <= 0.0 ? 0.0 : bm::pdf(law(), x); }
  double quantile(double p) const override { return bm::quantile(law(), p); }
  double quantile_complement(double q) const override { return bm::quantile(bm::complement(law(), q)); }
  double sample(RandomEngine& engine) const override { return boost::random::gamma_distribution<double>(shape_, scale_)(engine); }
  double scale() const override { return scale_; }
  // Y = X / scale: E[Y^k; a <= Y <= b] = Gamma(shape+k)/Gamma(shape) [P(shape+k, b) - P(shape+k, a)].
  double standard_partial_moment(int k, double lo, double hi, double mass) const override {
    const double order = shape_ + k;
    auto p = [&](double y) { return std::isinf(y) ? 1.0 : bm::gamma_p(order, y); };
    return bm::tgamma_ratio(shape_ + k, shape_) * (p(hi) - p(lo)) / mass;
  }

 private:
  bm::gamma_distribution<> law() const { return bm::gamma_distribution<>(shape_, scale_); }
  double shape_, scale_;
};

std::shared_ptr<const ContinuousLaw> make(double shape, double scale) {
  check_shape_and_scale("gamma", shape, scale);
  return std::make_shared<GammaLaw>(shape, scale);
}

}  // namespace

ContinuousFamily gamma_family() { return {"gamma", "shape", "scale", false, 0.0, make}; }

}  // namespace stengmc
