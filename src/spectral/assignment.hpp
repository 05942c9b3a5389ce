#pragma once
//! Optimal one-to-one assignment (Kuhn 1955, Munkres 1957: the Hungarian method).
#include <Eigen/Dense>
#include <vector>

namespace stengmc {

//! Minimum-cost assignment of rows to columns of a rectangular cost matrix; entries that
//! are +infinity are forbidden pairs. Returns, per row, the assigned column or -1.
std::vector<int> hungarian_assignment(const Eigen::MatrixXd& cost);

}  // namespace stengmc
