#include "surface/load_spread.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_01.hpp>
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/standard_normal.hpp"

namespace stengmc {

namespace {

// Beyond |z| = 40 the normal density is below 1e-347: nothing left to integrate.
constexpr double GAUSSIAN_REACH = 40.0;

//! ∫_a^b (z − δ)^p φ(z) dz by adaptive 61-point Gauss–Kronrod (the integrand's only
//! non-smooth point, z = δ, is an end of the interval, where the rule does not sample).
double excess_integral(double power, double separation, double a, double b) {
  if (!(b > a)) return 0.0;
  auto f = [&](double z) { return std::pow(std::max(0.0, z - separation), power) * phi_pdf(z); };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, a, b, 15, 1e-14);
}

}  // namespace

double excess_height_moment(double power, double separation) {
  if (!(power > 0.0) || !std::isfinite(separation))
    throw Error("excess_height_moment: needs p > 0 and a finite separation");
  const double tail = phi_cdf(-separation);  // Q(δ) = P(Z > δ)
  // Split where the density peaks (z = 0) when it lies inside: each piece is then smooth
  // and unimodal, which the adaptive rule integrates to full accuracy.
  const double lower = std::max(separation, -GAUSSIAN_REACH);
  const double upper = std::max(separation, 0.0) + GAUSSIAN_REACH;
  const double middle = std::clamp(0.0, lower, upper);
  return (excess_integral(power, separation, lower, middle) + excess_integral(power, separation, middle, upper)) / tail;
}

double load_cv_at_separation(double separation) {
  const double m = excess_height_moment(1.5, separation);
  return std::sqrt(std::max(0.0, excess_height_moment(3.0, separation) / (m * m) - 1.0));
}

double separation_for_load_cv(double cv) {
  if (!(cv > 0.0 && cv <= MAX_LOAD_CV))
    throw Error("separation_for_load_cv: cv = " + format_number(cv) + " must lie in (0, " + format_number(MAX_LOAD_CV) + "]");
  // CV rises monotonically with δ: for δ → −∞ it is ~(3/2)/|δ|, so the bracket's lower
  // end sits where that is below the target.
  auto f = [&](double d) { return load_cv_at_separation(d) - cv; };
  double low = std::min(-1.0, -3.0 / cv), high = 8.0;
  boost::uintmax_t iterations = 200;
  const auto [a, b] = boost::math::tools::toms748_solve(f, low, high, boost::math::tools::eps_tolerance<double>(48), iterations);
  return 0.5 * (a + b);
}

LoadSpread::LoadSpread(double mean_load_n, double cv) : mean_load_n_(mean_load_n), cv_(cv) {
  if (!(mean_load_n > 0.0) || !std::isfinite(mean_load_n))
    throw Error("LoadSpread: mean_load_n = " + format_number(mean_load_n) + " must be > 0");
  if (!(cv >= 0.0 && cv <= MAX_LOAD_CV)) throw Error("LoadSpread: cv = " + format_number(cv) + " out of range");
  if (cv == 0.0) {
    separation_ = -INFINITY;
    return;
  }
  separation_ = separation_for_load_cv(cv);
  load_per_excess_ = mean_load_n / excess_height_moment(1.5, separation_);
}

LoadedSummit LoadSpread::draw(RandomEngine& engine) const {
  if (cv_ == 0.0) return {boost::random::normal_distribution<double>(0.0, 1.0)(engine), mean_load_n_};
  // Inverse CDF on the upper tail: Z = Q^{-1}(u Q(δ)), accurate however far δ lies out.
  // u + 2^-54 lies in (0, 1): neither end (an infinite height, a zero load) is drawn.
  const double u = boost::random::uniform_01<double>()(engine) + 0x1p-54;
  const double q = u * phi_cdf(-separation_);
  const double z = boost::math::quantile(boost::math::complement(boost::math::normal(0.0, 1.0), q));
  return {z, load_per_excess_ * std::pow(std::max(0.0, z - separation_), 1.5)};
}

double LoadSpread::load_quantile(double p) const {
  if (!(p > 0.0 && p < 1.0)) throw Error("LoadSpread::load_quantile: p = " + format_number(p) + " must lie in (0, 1)");
  if (cv_ == 0.0) return mean_load_n_;
  // The load rises with Z: its p-quantile is that of Z given Z > δ, Q^{-1}((1 - p) Q(δ)).
  const double z = boost::math::quantile(boost::math::complement(boost::math::normal(0.0, 1.0), (1.0 - p) * phi_cdf(-separation_)));
  return load_per_excess_ * std::pow(std::max(0.0, z - separation_), 1.5);
}

}  // namespace stengmc
