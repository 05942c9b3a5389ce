#pragma once
//! How far one atom's ln k error comes from trading with the other atoms.

#include <cstddef>

#include <Eigen/Dense>

namespace stengmc {

//! The ln k standard error of the atom whose parameters start at `first` (its `own` entries,
//! ln k first) over what it would be were every other atom's parameters known exactly, its own
//! block and the `shared` parameters (the last rows of `curvature`) still free. `curvature` is
//! the posterior's (J^T J / sigma^2 plus the prior's curvatures); the conditional variance is
//! the (0, 0) entry of the inverse of its sub-block (the Schur complement); the joint one,
//! `joint_variance`, is the caller's (its covariance's diagonal, already computed). >= 1; 1
//! when the record holds the line on its own. A pair of parameters of correlation r has
//! 1/sqrt(1 - r^2).
double se_inflation(const Eigen::MatrixXd& curvature, Eigen::Index first, std::size_t own, std::size_t shared,
                    double joint_variance);

}  // namespace stengmc
