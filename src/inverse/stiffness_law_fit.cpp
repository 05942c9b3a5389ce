#include "inverse/stiffness_law_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/weibull.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/trigamma.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <numeric>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "inverse/sample_statistics.hpp"

namespace stengmc {

namespace {

constexpr double Z90 = 1.6448536269514722;  // two-sided 90 %

//! ln of the family's density at x, in closed form. Not ln(boost::math::pdf): the density of
//! a narrow law underflows to 0 a few widths out (ln 0 = -inf in the AIC), and Boost's gamma
//! density gives up (its tgamma series) beyond a shape of ~1e11.
double log_density(double x, StiffnessFamily family, double p1, double p2) {
  switch (family) {
    case StiffnessFamily::lognormal: {
      const double z = (std::log(x) - std::log(p1)) / p2;
      return -std::log(x) - std::log(p2) - 0.5 * std::log(2.0 * PI) - 0.5 * z * z;
    }
    case StiffnessFamily::gamma:  // shape p1, scale p2
      return (p1 - 1.0) * std::log(x) - x / p2 - p1 * std::log(p2) - std::lgamma(p1);
    case StiffnessFamily::weibull: {  // shape p1, scale p2
      const double u = std::log(x / p2);
      return std::log(p1 / p2) + (p1 - 1.0) * u - std::exp(p1 * u);
    }
  }
  throw Error("unknown stiffness family");
}

double log_likelihood(std::span<const double> k, StiffnessFamily family, double p1, double p2) {
  double sum = 0.0;
  for (double x : k) sum += log_density(x, family, p1, p2);
  return sum;
}

//! The Weibull shape's profile equation sum w ln k / sum w - 1/c - mean(ln k) = 0, w = k^c
//! (increasing in c), bracketed from the data: below, -1/c wins; above, the weights pile
//! on the largest k and the left side tends to ln max(k) - mean(ln k) > 0 (has_spread holds).
//! Its root is ~1 / sd(ln k) for a sample normal in ln k, more for a skewed one: the bracket
//! that stopped at 1.6e4 failed for merged lines; doubling from 1 reaches any root.
double weibull_shape(std::span<const double> k, double mean_log) {
  const double largest = *std::max_element(k.begin(), k.end());
  auto profile = [&](double c) {
    double num = 0.0, den = 0.0;
    for (double x : k) {
      const double u = std::log(x / largest);  // <= 0: w <= 1, no overflow of k^c
      const double w = std::exp(c * u);
      num += w * u;
      den += w;
    }
    return num / den + std::log(largest) - 1.0 / c - mean_log;
  };
  double low = 1.0, high = 1.0;
  while (profile(low) > 0.0) low /= 2.0;
  while (profile(high) < 0.0) high *= 2.0;
  boost::uintmax_t iterations = 200;
  const auto root = boost::math::tools::toms748_solve(profile, low, high, boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (root.first + root.second);
}

//! MLE parameters of the family.
std::array<double, 2> maximum_likelihood(std::span<const double> k, StiffnessFamily family) {
  const double n = static_cast<double>(k.size());
  double mean_log = 0.0, mean = 0.0;
  for (double x : k) mean_log += std::log(x) / n, mean += x / n;
  switch (family) {
    case StiffnessFamily::lognormal: {
      double var = 0.0;
      for (double x : k) var += (std::log(x) - mean_log) * (std::log(x) - mean_log) / n;
      return {std::exp(mean_log), std::sqrt(var)};
    }
    case StiffnessFamily::gamma: {
      const double s = std::log(mean) - mean_log;  // > 0 unless all equal
      double a = (3.0 - s + std::sqrt((s - 3.0) * (s - 3.0) + 24.0 * s)) / (12.0 * s);
      for (int i = 0; i < 100; ++i) {
        const double f = std::log(a) - boost::math::digamma(a) - s;
        const double df = 1.0 / a - boost::math::trigamma(a);
        const double next = a - f / df;
        const double updated = next > 0.0 ? next : a / 2.0;
        if (std::abs(updated - a) < 1e-14 * a) {
          a = updated;
          break;
        }
        a = updated;
      }
      return {a, mean / a};
    }
    case StiffnessFamily::weibull: {
      const double c = weibull_shape(k, mean_log);
      // scale = (mean k^c)^(1/c), taken relative to the largest k against overflow of k^c.
      const double largest = *std::max_element(k.begin(), k.end());
      double sum = 0.0;
      for (double x : k) sum += std::exp(c * std::log(x / largest));
      return {c, largest * std::exp(std::log(sum / n) / c)};
    }
  }
  throw Error("unknown stiffness family");
}

}  // namespace

bool has_spread(std::span<const double> k) {
  return sample_sd_log(std::vector<double>(k.begin(), k.end())) >= MIN_LAW_SD_LOG;
}

LawFit fit_stiffness_law(std::span<const double> k, StiffnessFamily family) {
  LawFit fit;
  fit.family = family;
  std::vector<double> sorted(k.begin(), k.end());
  std::sort(sorted.begin(), sorted.end());
  const auto distinct = static_cast<std::size_t>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  if (distinct < 3) return fit;
  for (double x : k)
    if (!(x > 0.0) || !std::isfinite(x)) throw Error("fit_stiffness_law: stiffnesses must be finite and > 0");
  if (!has_spread(k)) return fit;
  fit.parameters = maximum_likelihood(k, family);
  fit.log_likelihood = log_likelihood(k, family, fit.parameters[0], fit.parameters[1]);
  fit.aic = 4.0 - 2.0 * fit.log_likelihood;
  // Observed information in (ln p1, ln p2) by central differences of ln L (step 1e-4: the
  // curvature's relative error ~1e-8, far below the interval's own approximation).
  const double h = 1e-4;
  const double u0 = std::log(fit.parameters[0]), v0 = std::log(fit.parameters[1]);
  auto ll = [&](double u, double v) { return log_likelihood(k, family, std::exp(u), std::exp(v)); };
  Eigen::Matrix2d info;
  const double f0 = fit.log_likelihood;
  info(0, 0) = -(ll(u0 + h, v0) - 2.0 * f0 + ll(u0 - h, v0)) / (h * h);
  info(1, 1) = -(ll(u0, v0 + h) - 2.0 * f0 + ll(u0, v0 - h)) / (h * h);
  info(0, 1) = info(1, 0) = -(ll(u0 + h, v0 + h) - ll(u0 + h, v0 - h) - ll(u0 - h, v0 + h) + ll(u0 - h, v0 - h)) / (4.0 * h * h);
  const Eigen::Matrix2d covariance = info.inverse();
  for (int p = 0; p < 2; ++p) {
    const double half = Z90 * std::sqrt(std::max(0.0, covariance(p, p)));
    const double centre = p == 0 ? u0 : v0;
    fit.interval[static_cast<std::size_t>(p)] = {std::exp(centre - half), std::exp(centre + half)};
  }
  // Median and sd of ln k of the fitted law.
  switch (family) {
    case StiffnessFamily::lognormal:
      fit.median = fit.parameters[0];
      fit.sd_log = fit.parameters[1];
      break;
    case StiffnessFamily::gamma:
      fit.median = boost::math::median(boost::math::gamma_distribution<>(fit.parameters[0], fit.parameters[1]));
      fit.sd_log = std::sqrt(boost::math::trigamma(fit.parameters[0]));  // Var ln X = psi'(a)
      break;
    case StiffnessFamily::weibull:
      fit.median = boost::math::median(boost::math::weibull(fit.parameters[0], fit.parameters[1]));
      // ln X = ln scale + G / c with G standard Gumbel-min: Var = (pi^2 / 6) / c^2.
      fit.sd_log = 3.14159265358979323846 / std::sqrt(6.0) / fit.parameters[0];
      break;
  }
  fit.fitted = true;
  return fit;
}

std::vector<LawFit> compare_stiffness_laws(std::span<const double> k) {
  std::vector<LawFit> fits;
  for (StiffnessFamily f : {StiffnessFamily::lognormal, StiffnessFamily::gamma, StiffnessFamily::weibull})
    fits.push_back(fit_stiffness_law(k, f));
  std::stable_sort(fits.begin(), fits.end(), [](const LawFit& a, const LawFit& b) {
    if (a.fitted != b.fitted) return a.fitted;
    return a.aic < b.aic;
  });
  return fits;
}

}  // namespace stengmc
