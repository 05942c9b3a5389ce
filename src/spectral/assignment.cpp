#include "spectral/assignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace stengmc {

namespace {

//! Kuhn–Munkres with row/column potentials and shortest augmenting paths (the O(n^2 m)
//! formulation of Jonker & Volgenant 1987, as written in e-maxx's "Hungarian algorithm"):
//! rows are added one at a time and each is joined to the current matching by a
//! Dijkstra-like search on reduced costs. Needs rows <= cols; returns the column of each row.
std::vector<int> assign_rows(const Eigen::MatrixXd& a) {
  const int n = static_cast<int>(a.rows());
  const int m = static_cast<int>(a.cols());
  const double inf = std::numeric_limits<double>::infinity();
  // 1-based with a virtual column 0 that holds the row being inserted.
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<bool> used(m + 1, false);
    do {
      used[j0] = true;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced = a(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < minv[j]) {
          minv[j] = reduced;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {  // flip the augmenting path
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> column(n, -1);
  for (int j = 1; j <= m; ++j)
    if (p[j] != 0) column[p[j] - 1] = j - 1;
  return column;
}

}  // namespace

std::vector<int> hungarian_assignment(const Eigen::MatrixXd& cost) {
  const Eigen::Index rows = cost.rows();
  const Eigen::Index cols = cost.cols();
  std::vector<int> result(static_cast<std::size_t>(rows), -1);
  if (rows == 0 || cols == 0) return result;

  // Forbidden pairs get a finite cost `big` so large that one forbidden pair more always
  // costs more than any rearrangement of the allowed ones: the optimum first maximises the
  // number of allowed pairs, then minimises their cost. With allowed costs shifted into
  // [0, span] (a constant shift changes every full assignment alike), r assigned pairs
  // differ by at most r x span, so big = (r + 1)(span + 1) suffices.
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) {
      const double c = cost(i, j);
      if (std::isnan(c) || c == -std::numeric_limits<double>::infinity())
        throw InputError("assignment: cost(" + std::to_string(i) + ", " + std::to_string(j) +
                         ") must be finite or +infinity (forbidden)");
      if (std::isinf(c)) continue;
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
  if (lo > hi) return result;  // every pair forbidden
  const double pairs = static_cast<double>(std::min(rows, cols));
  const double span = hi - lo;
  const double big = (pairs + 1.0) * (span + 1.0);
  if (!std::isfinite(big)) throw InputError("assignment: the cost range is too wide to represent forbidden pairs");
  // Rounding: the potentials carry values up to ~big, so allowed costs are resolved to
  // ~1e-16 x big; cost differences far below that are ties.

  const bool transposed = rows > cols;  // the search needs rows <= cols
  Eigen::MatrixXd shifted = transposed ? Eigen::MatrixXd(cost.transpose()) : cost;
  shifted = shifted.unaryExpr([&](double c) { return std::isinf(c) ? big : c - lo; });
  const std::vector<int> assigned = assign_rows(shifted);

  for (std::size_t r = 0; r < assigned.size(); ++r) {
    const int c = assigned[r];
    const auto i = static_cast<Eigen::Index>(transposed ? c : static_cast<int>(r));
    const auto j = static_cast<Eigen::Index>(transposed ? static_cast<int>(r) : c);
    if (c < 0 || std::isinf(cost(i, j))) continue;  // unassigned or only a forbidden pair was left
    result[static_cast<std::size_t>(i)] = static_cast<int>(j);
  }
  return result;
}

}  // namespace stengmc
