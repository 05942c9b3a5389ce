#pragma once
//! The continuous families of surface laws (normal, lognormal, gamma, weibull, ...): each
//! gives its untruncated cdf, survival function, density, quantiles, Boost.Random sampler
//! and closed-form partial moments; Distribution (distribution.hpp) adds the truncation and
//! the moments of the truncated law around it. A new family is one file defining its
//! ContinuousFamily and one line in continuous_families.cpp.
#include <memory>
#include <string_view>
#include <vector>

#include "core/random_stream.hpp"

namespace stengmc {

//! One member of a family: the untruncated law at given parameters.
class ContinuousLaw {
 public:
  virtual ~ContinuousLaw() = default;
  [[nodiscard]] virtual double cdf(double x) const = 0;
  [[nodiscard]] virtual double sf(double x) const = 0;  //!< 1 - cdf, accurate in the upper tail
  [[nodiscard]] virtual double pdf(double x) const = 0;
  [[nodiscard]] virtual double quantile(double p) const = 0;
  [[nodiscard]] virtual double quantile_complement(double q) const = 0;  //!< the x with sf(x) = q
  //! One untruncated draw with the Boost.Random distribution of the family (fixed
  //! algorithms, portable).
  [[nodiscard]] virtual double sample(RandomEngine& engine) const = 0;
  //! The partial moments are those of Y = (X - location) / scale.
  [[nodiscard]] virtual double location() const { return 0.0; }
  [[nodiscard]] virtual double scale() const = 0;
  //! E[Y^k; y_lo <= Y <= y_hi] / mass for k >= 1, where mass = P(y_lo <= Y <= y_hi).
  [[nodiscard]] virtual double standard_partial_moment(int k, double y_lo, double y_hi, double mass) const = 0;
};

//! A family as surface files name it.
struct ContinuousFamily {
  std::string_view name;        //!< `kind = "..."`
  std::string_view first_key;   //!< its two parameters' keys, in the quantity's unit unless
  std::string_view second_key;  //!< they are shapes or log-scales (dimensionless)
  bool first_may_be_negative;   //!< a location (normal's mean); every other parameter must be > 0
  double support_lower;         //!< -inf, or 0 for laws of positive quantities
  //! The law; parameters out of range throw InputError naming the family and the key.
  std::shared_ptr<const ContinuousLaw> (*make)(double first, double second);
};

//! Every family, in the order error messages list them.
const std::vector<ContinuousFamily>& continuous_families();
//! The family named `name`, or nullptr.
const ContinuousFamily* find_continuous_family(std::string_view name);

}  // namespace stengmc
