#pragma once
//! A one-dimensional distribution of an asperity quantity (height [m], stiffness [N/m],
//! ...), read from a TOML table (MODEL.md §4). Values are in the SI unit of the quantity
//! the enclosing table describes; the distribution itself is unit-agnostic.
//!
//! Kinds and keys (every parameter in the quantity's SI unit unless marked [-]):
//!   normal     mean, std                     (std > 0)
//!   lognormal  median, sigma_log [-]         (ln X ~ N(ln median, sigma_log²); both > 0)
//!   uniform    min, max                      (max > min)
//!   gamma      shape [-], scale              (pdf ∝ x^(shape−1) exp(−x/scale); both > 0)
//!   weibull    shape [-], scale              (cdf 1 − exp(−(x/scale)^shape); both > 0)
//!   fixed      values = [...]                (each drawn with probability 1/n, with
//!                                             replacement; a list in order is a fixed
//!                                             population, not a distribution)
//!   empirical  file = "h.csv"                (a piecewise-uniform histogram; see
//!                                             read_histogram; path relative to the
//!                                             surface file's folder)
//! normal, lognormal, gamma and weibull take an optional truncation `min` and/or `max`:
//! samples come from the exact truncated law by inverse-CDF sampling on [F(min), F(max)]
//! with Boost.Math quantiles, and cdf/pdf/moments are those of the truncated law.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/random_stream.hpp"
#include "core/toml_reader.hpp"
#include "surface/continuous_law.hpp"

namespace stengmc {

class Distribution {
 public:
  //! A continuous family (continuous_law.hpp: normal, lognormal, gamma, weibull, ...,
  //! registered by name), or one of the laws given by values.
  enum class Kind { continuous, uniform, fixed, empirical };

  //! One histogram bin: density uniform on [lower, upper), total weight `weight` (>= 0).
  struct Bin {
    double lower;
    double upper;
    double weight;
  };

  //! Reads `kind` and its keys (see the file comment) from `table`; a histogram `file`
  //! is resolved against `base_dir` (the surface file's folder). Every bad value throws
  //! InputError naming file:line and the key.
  static Distribution from_toml(TomlTable& table, const std::filesystem::path& base_dir);

  //! Reads a histogram CSV: one bin per line, `lower,upper,weight`; blank lines and lines
  //! starting with '#' are skipped, as is a first line `lower,upper,weight`. Bins must be
  //! in increasing order and not overlap (gaps are allowed: zero density there); weights
  //! are >= 0 (counts or probabilities; normalised here) with a positive sum.
  //! Throws InputError "file:line: ..." on anything else.
  static std::vector<Bin> read_histogram(const std::filesystem::path& file);

  // Direct construction (tests, programmatic surfaces). Bad arguments throw InputError
  // without a location. `min`/`max` truncate; infinities mean "not truncated".
  //! A registered continuous family by name (its parameters in the family's order).
  static Distribution continuous(std::string_view family, double first, double second, double min, double max);
  static Distribution normal(double mean, double std, double min = -INFINITY, double max = INFINITY);
  static Distribution lognormal(double median, double sigma_log, double min = 0.0, double max = INFINITY);
  static Distribution uniform(double min, double max);
  static Distribution gamma(double shape, double scale, double min = 0.0, double max = INFINITY);
  static Distribution weibull(double shape, double scale, double min = 0.0, double max = INFINITY);
  static Distribution fixed(std::vector<double> values);
  static Distribution empirical(std::vector<Bin> bins);

  //! One draw. Untruncated continuous kinds use the Boost.Random distribution of that
  //! name (fixed algorithms, portable); truncated ones, the histogram and `fixed` use
  //! inverse-CDF sampling.
  double sample(RandomEngine& engine) const;
  //! The p-quantile, 0 < p < 1.
  double quantile(double p) const;
  //! The quantile at normal score z, i.e. quantile(Φ(z)), accurate in both tails (copulas).
  double quantile_of_normal_score(double z) const;
  //! P(X <= x).
  double cdf(double x) const;
  //! Density at x; for `fixed` (no density) 0 — plot its 1/n masses instead.
  double pdf(double x) const;
  double mean() const;
  double variance() const;
  //! E[(X − mean)^k] for k = 2, 3, 4 (exact: closed-form partial moments).
  double central_moment(int k) const;

  [[nodiscard]] Kind kind() const { return kind_; }
  //! The continuous family, or nullptr for uniform, fixed and empirical laws.
  [[nodiscard]] const ContinuousFamily* family() const { return family_; }
  //! The law's `kind` as surface files write it ("normal", ..., "uniform", "fixed", "empirical").
  [[nodiscard]] std::string_view kind_name() const;
  //! The smallest / largest value that can be drawn (may be infinite).
  [[nodiscard]] double lower() const { return min_; }
  [[nodiscard]] double upper() const { return max_; }
  [[nodiscard]] bool truncated() const { return truncated_; }
  //! `fixed`: its values, sorted (each drawn with probability 1/n); empty otherwise.
  [[nodiscard]] const std::vector<double>& fixed_values() const { return values_; }
  //! The histogram file an empirical law was read from, as "<path>\n<its text>" ("" for
  //! every other law): results depend on it, so provenance and resume checks include it.
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  Distribution(Kind kind, double min, double max);
  void set_truncation(double min, double max);
  double from_probability(double p, double q) const;
  double base_cdf(double x) const;
  double base_sf(double x) const;
  double standard_partial_moment(int k) const;

  Kind kind_;
  const ContinuousFamily* family_ = nullptr;   // continuous: its family
  std::shared_ptr<const ContinuousLaw> law_;   // continuous: the untruncated law
  double min_ = -INFINITY;
  double max_ = INFINITY;
  bool truncated_ = false;
  double cdf_min_ = 0.0, sf_min_ = 1.0, cdf_max_ = 1.0, sf_max_ = 0.0;
  double mass_ = 1.0;                // probability of [min, max] under the untruncated law
  std::vector<double> values_;       // fixed: sorted values
  std::vector<Bin> bins_;            // empirical / uniform: bins with weights normalised
  std::vector<double> cumulative_;   // empirical / uniform: cdf at each bin's upper edge
  std::string source_;               // empirical from a file: "<path>\n<its text>", else empty
};

}  // namespace stengmc
