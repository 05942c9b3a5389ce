#include <boost/math/distributions/normal.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/standard_normal.hpp"
#include "surface/continuous_law.hpp"

namespace stengmc {

namespace {

namespace bm = boost::math;

//! N(mean, std^2).
class NormalLaw final : public ContinuousLaw {
 public:
  NormalLaw(double mean, double std) : mean_(mean), std_(std) {}
  double cdf(double x) const override { return bm::cdf(bm::normal(mean_, std_), x); }
  double sf(double x) const override { return bm::cdf(bm::complement(bm::normal(mean_, std_), x)); }
  double pdf(double x) const override { return bm::pdf(bm::normal(mean_, std_), x); }
  double quantile(double p) const override { return bm::quantile(bm::normal(mean_, std_), p); }
  double quantile_complement(double q) const override { return bm::quantile(bm::complement(bm::normal(mean_, std_), q)); }
  double sample(RandomEngine& engine) const override { return boost::random::normal_distribution<double>(mean_, std_)(engine); }
  double location() const override { return mean_; }
  double scale() const override { return std_; }
  // M_k = (k-1) M_{k-2} + a^{k-1} phi(a) - b^{k-1} phi(b) (integration by parts), M_0 = mass.
  double standard_partial_moment(int k, double lo, double hi, double mass) const override {
    auto term = [](double z, int power) { return std::isinf(z) ? 0.0 : std::pow(z, power) * phi_pdf(z); };
    double m_prev = mass, m = phi_pdf(lo) - phi_pdf(hi);  // M_0, M_1 (unnormalised)
    for (int j = 2; j <= k; ++j) {
      const double next = (j - 1) * m_prev + term(lo, j - 1) - term(hi, j - 1);
      m_prev = m;
      m = next;
    }
    return m / mass;
  }

 private:
  double mean_, std_;
};

std::shared_ptr<const ContinuousLaw> make(double mean, double std) {
  if (!(std > 0.0)) throw InputError("normal distribution: std = " + format_number(std) + " must be > 0");
  return std::make_shared<NormalLaw>(mean, std);
}

}  // namespace

ContinuousFamily normal_family() { return {"normal", "mean", "std", true, -INFINITY, make}; }

}  // namespace stengmc
