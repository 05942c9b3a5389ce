#pragma once
//! Gaussian copula for a correlated (height, stiffness) pair (Nelsen, "An Introduction to
//! Copulas", 2nd ed. 2006, §2.3 and §5.1).
//!
//! Two independent standard normals z1, e are drawn, z2 = rho z1 + sqrt(1 − rho²) e, and
//! each is mapped to its marginal by x_i = F_i^{-1}(Φ(z_i)). The marginals are exactly the
//! given distributions; rho is the correlation of the normal scores Φ^{-1}(F_i(x_i)), NOT
//! the Pearson correlation of the x_i. Spearman's rank correlation (invariant under the
//! monotone marginal maps) is rho_S = (6/π) asin(rho/2) (Nelsen, eq. 5.1.12 with Kruskal
//! 1958); Kendall's tau is (2/π) asin(rho).
//!
//! Note: the marginals are drawn by inverse CDF here, so with rho = 0 the values differ
//! from Distribution::sample's (same law, different numbers).
#include <utility>

#include "core/random_stream.hpp"
#include "core/toml_reader.hpp"
#include "surface/distribution.hpp"

namespace stengmc {

class GaussianCopula {
 public:
  //! @param rho normal-scores correlation [-], in (−1, 1); InputError otherwise.
  explicit GaussianCopula(double rho);
  //! Reads `rho` from `table` (InputError with file:line:key unless −1 < rho < 1).
  static GaussianCopula from_toml(TomlTable& table);

  //! One pair (x1 from `first`, x2 from `second`). z1 comes from `engine1`, the independent
  //! normal e from `engine2`: pass the heights and stiffnesses streams, so that each
  //! quantity's randomness stays on its own named stream.
  [[nodiscard]] std::pair<double, double> sample(const Distribution& first, const Distribution& second,
                                                 RandomEngine& engine1, RandomEngine& engine2) const;

  //! The normal-scores correlation [-].
  [[nodiscard]] double rho() const { return rho_; }
  //! Spearman's rank correlation implied by rho [-]: (6/π) asin(rho/2).
  [[nodiscard]] double spearman() const;

 private:
  double rho_;
};

}  // namespace stengmc
