#include "inverse/se_inflation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace stengmc {

double se_inflation(const Eigen::MatrixXd& curvature, Eigen::Index first, std::size_t own, std::size_t shared,
                    double joint_variance) {
  std::vector<Eigen::Index> index;
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(own); ++j) index.push_back(first + j);
  for (Eigen::Index j = curvature.rows() - static_cast<Eigen::Index>(shared); j < curvature.rows(); ++j) index.push_back(j);
  const auto m = static_cast<Eigen::Index>(index.size());
  Eigen::MatrixXd block(m, m);
  for (Eigen::Index a = 0; a < m; ++a)
    for (Eigen::Index b = 0; b < m; ++b) block(a, b) = curvature(index[static_cast<std::size_t>(a)], index[static_cast<std::size_t>(b)]);
  const double alone = block.inverse()(0, 0);
  // A curvature that is not positive definite has no such ratio: say "no trade" rather than
  // write a NaN (its errors are refused upstream).
  if (!(alone > 0.0) || !(joint_variance > 0.0) || !std::isfinite(alone) || !std::isfinite(joint_variance)) return 1.0;
  return std::max(1.0, std::sqrt(joint_variance / alone));
}

}  // namespace stengmc
