#include "inverse/track_wear.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "inverse/line_centre_fit.hpp"
#include "inverse/track_lines.hpp"

namespace stengmc {

namespace {

struct Piece {
  std::size_t segment = 0;
  double time_s = 0.0;      //!< its middle [s]
  double stiffness = 0.0;   //!< [N/m]
  double se = 0.0;          //!< [N/m]
};

}  // namespace

std::optional<TrackWear> fit_track_wear(const KnownDevice& device, const Track& track, std::size_t index,
                                        std::span<const TrackSegment> segments, const RecordGrid& grid,
                                        std::span<const double> v, std::span<const double> neighbours_hz,
                                        const std::vector<TrackWindow>& windows) {
  const double gamma = device.damping_rate_per_s();
  const double half_width_hz = gamma / (2.0 * std::numbers::pi);
  const double piece_s = 4.0 / gamma;  // 4 tau: the shortest span a centre is fitted over
  std::vector<Piece> pieces;
  std::size_t longest = 0;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const TrackSegment& g = segments[s];
    const auto count = static_cast<std::size_t>(std::floor((g.end_s - g.start_s) / piece_s));
    longest = std::max(longest, count);
    if (count == 0) continue;
    const double length = (g.end_s - g.start_s) / static_cast<double>(count);
    // 12 half-widths each side, at least 8 ordinates (8 / length); other tracks' lines in it
    // fitted with this one.
    const double reach = std::max(12.0 * half_width_hz, 8.0 / length);
    const double least = std::max(3.0 * half_width_hz, 8.0 / length);
    for (std::size_t i = 0; i < count; ++i) {
      const double a = g.start_s + static_cast<double>(i) * length, b = a + length;
      // Started at the median of its windows' lines (wear moves the line along the segment).
      std::vector<double> f;
      for (const TrackSighting& x : track.sightings) {
        const double c = windows[x.window].centre_s;
        if (c >= a && c < b) f.push_back(x.line.frequency_hz);
      }
      double guess = g.frequency_hz;
      if (!f.empty()) {
        std::nth_element(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(f.size() / 2), f.end());
        guess = f[f.size() / 2];
      }
      const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil((a - grid.start_s) / grid.step_s)));
      const auto last = std::min(grid.samples, static_cast<std::size_t>(std::max(0.0, std::ceil((b - grid.start_s) / grid.step_s))));
      if (last <= first + 16) continue;
      const FitBand fb = fit_band(guess, guess, reach, neighbours_hz, least);
      const LocalPeriodogram p = local_periodogram(v.subspan(first, last - first), grid.sample_rate_hz(), fb.low_hz, fb.high_hz);
      const LorentzianFit fit = fit_lorentzian(p, guess, half_width_hz, false, fb.neighbours_hz);
      if (!fit.valid) continue;
      const double k = stiffness_at(device, fit.centre_hz);
      // k = m (omega^2 + gamma^2): dk/df = 2 m omega 2 pi ~ 2 k / f.
      pieces.push_back({s, 0.5 * (a + b), k, 2.0 * k * fit.centre_se_hz / fit.centre_hz});
    }
  }
  if (pieces.size() < 3 || longest < 2) return std::nullopt;

  // Relative stiffnesses y = k_i / level_s with one level c_s per segment and a common slope.
  const std::size_t nseg = segments.size();
  std::vector<double> level(nseg, 0.0), weight(nseg, 0.0), middle(nseg, 0.0);
  for (const Piece& p : pieces) {
    const double w = 1.0 / (p.se * p.se);
    level[p.segment] += w * p.stiffness;
    middle[p.segment] += w * p.time_s;
    weight[p.segment] += w;
  }
  for (std::size_t s = 0; s < nseg; ++s)
    if (weight[s] > 0.0) level[s] /= weight[s], middle[s] /= weight[s];
  const auto n = static_cast<Eigen::Index>(pieces.size()), columns = static_cast<Eigen::Index>(nseg + 1);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, columns);
  Eigen::VectorXd y(n), w(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Piece& p = pieces[static_cast<std::size_t>(i)];
    x(i, static_cast<Eigen::Index>(p.segment)) = 1.0;
    x(i, columns - 1) = p.time_s - middle[p.segment];
    y(i) = p.stiffness / level[p.segment];
    const double sigma = p.se / level[p.segment];
    w(i) = 1.0 / (sigma * sigma);
  }
  // Segments without pieces have empty columns: a unit diagonal keeps the system solvable.
  Eigen::MatrixXd normal = x.transpose() * w.asDiagonal() * x;
  for (std::size_t s = 0; s < nseg; ++s)
    if (weight[s] == 0.0) normal(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(s)) = 1.0;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::VectorXd beta = ldlt.solve(x.transpose() * w.asDiagonal() * y);
  const Eigen::MatrixXd covariance = ldlt.solve(Eigen::MatrixXd::Identity(columns, columns));
  std::size_t used_segments = 0;
  for (double q : weight) used_segments += q > 0.0 ? 1 : 0;
  const double dof = static_cast<double>(pieces.size()) - static_cast<double>(used_segments) - 1.0;
  const Eigen::VectorXd residual = y - x * beta;
  const double chi2 = residual.dot(w.asDiagonal() * residual);
  const double birge = dof >= 1.0 ? std::max(1.0, std::sqrt(chi2 / dof)) : 1.0;

  TrackWear wear;
  wear.track = index;
  wear.pieces = pieces.size();
  wear.slope_per_s = beta(columns - 1);
  wear.slope_se_per_s = birge * std::sqrt(covariance(columns - 1, columns - 1));
  // Relative to the stiffness at the track's first sighting: the first segment with pieces, its
  // level extrapolated back to the segment's start.
  std::size_t s0 = 0;
  while (s0 < nseg && weight[s0] == 0.0) ++s0;
  const double lead_s = segments[s0].start_s - middle[s0];
  const double c0 = beta(static_cast<Eigen::Index>(s0));
  auto rate = [&](double rho) { return -rho * 1e-3 / (c0 + rho * lead_s); };
  wear.rate_per_ms = rate(wear.slope_per_s);
  // rate() falls as rho rises (lead_s <= 0): the interval's ends swap.
  wear.rate_low = rate(wear.slope_per_s + Z90 * wear.slope_se_per_s);
  wear.rate_high = rate(wear.slope_per_s - Z90 * wear.slope_se_per_s);
  if (!std::isfinite(wear.rate_per_ms) || !std::isfinite(wear.rate_low) || !std::isfinite(wear.rate_high)) return std::nullopt;
  return wear;
}

}  // namespace stengmc
