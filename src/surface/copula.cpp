#include "surface/copula.hpp"

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace stengmc {

GaussianCopula::GaussianCopula(double rho) : rho_(rho) {
  if (!(rho > -1.0 && rho < 1.0)) {
    std::ostringstream out;
    out << "Gaussian copula: rho = " << rho << " must lie in (-1, 1)";
    throw InputError(out.str());
  }
}

GaussianCopula GaussianCopula::from_toml(TomlTable& table) {
  const double rho = table.required_number("rho");
  // |rho| = 1 is a degenerate (comonotone) copula: no density, and the surface is better
  // described by deriving one quantity from the other.
  if (!(rho > -1.0 && rho < 1.0)) {
    std::ostringstream out;
    out << "= " << rho << " must lie in the open interval (-1, 1)";
    table.fail("rho", out.str());
  }
  return GaussianCopula(rho);
}

std::pair<double, double> GaussianCopula::sample(const Distribution& first, const Distribution& second,
                                                 RandomEngine& engine1, RandomEngine& engine2) const {
  boost::random::normal_distribution<double> standard(0.0, 1.0);
  const double z1 = standard(engine1);
  const double e = standard(engine2);
  const double z2 = rho_ * z1 + std::sqrt(1.0 - rho_ * rho_) * e;
  return {first.quantile_of_normal_score(z1), second.quantile_of_normal_score(z2)};
}

double GaussianCopula::spearman() const { return 6.0 / M_PI * std::asin(rho_ / 2.0); }

}  // namespace stengmc
