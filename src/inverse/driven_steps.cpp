#include "inverse/driven_steps.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "inverse/line_centre_fit.hpp"
#include "inverse/track_segments.hpp"

namespace stengmc {

namespace {

struct PieceFit {
  double log_likelihood = 0.0;
  double centre_hz = 0.0, centre_se_hz = 0.0;
  bool valid = false;
};

class StepSearch {
 public:
  StepSearch(const KnownDevice& device, const Track& track, const std::vector<TrackWindow>& windows, const RecordGrid& grid,
             std::span<const double> v, double low_hz, double high_hz, std::span<const double> neighbours_hz)
      : track_(track), windows_(windows), grid_(grid), v_(v), neighbours_hz_(neighbours_hz), low_hz_(low_hz), high_hz_(high_hz),
        half_width_hz_(device.damping_rate_per_s() / (2.0 * std::numbers::pi)) {}

  //! The median line of the sightings whose window centre lies in [start_s, end_s) [Hz] (0: none).
  double median_line(double start_s, double end_s) const {
    std::vector<double> f;
    for (const TrackSighting& s : track_.sightings) {
      const double c = windows_[s.window].centre_s;
      if (c >= start_s && c < end_s) f.push_back(s.line.frequency_hz);
    }
    if (f.empty()) return 0.0;
    std::nth_element(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(f.size() / 2), f.end());
    return f[f.size() / 2];
  }

  //! The line fitted over [start_s, end_s), started at the median of the sightings whose window centre lies in it.
  PieceFit fit(double start_s, double end_s) const {
    PieceFit out;
    const double guess = median_line(start_s, end_s);
    if (!(guess > 0.0)) return out;
    const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil((start_s - grid_.start_s) / grid_.step_s)));
    const auto last = std::min(grid_.samples, static_cast<std::size_t>(std::max(0.0, std::ceil((end_s - grid_.start_s) / grid_.step_s))));
    if (last <= first + 16) return out;
    const LocalPeriodogram p = local_periodogram(v_.subspan(first, last - first), grid_.sample_rate_hz(), low_hz_, high_hz_);
    const LorentzianFit lf = fit_lorentzian(p, guess, half_width_hz_, false, neighbours_hz_);
    out.valid = lf.valid;
    out.log_likelihood = lf.log_likelihood;
    out.centre_hz = lf.centre_hz;
    out.centre_se_hz = lf.centre_se_hz;
    return out;
  }

  //! The line's jump at `split_s` over its standard error: pieces of about `piece_s` on either
  //! side fitted (independent, each with its Whittle error), and their centres by weighted least
  //! squares with a level on each side and one common slope (wear drifts the line: a drift is
  //! no step, and a two-level model with no slope would take it for one). The error is scaled by
  //! the Birge ratio sqrt(chi^2 / dof) when the pieces scatter more than their errors say.
  double jump_z(double start_s, double split_s, double end_s, double piece_s) const {
    struct Centre {
      int side;
      double time_s, centre_hz, se_hz;
    };
    std::vector<Centre> centres;
    for (int side = 0; side < 2; ++side) {
      const double a = side == 0 ? start_s : split_s, b = side == 0 ? split_s : end_s;
      const auto count = std::max<std::size_t>(1, static_cast<std::size_t>(std::floor((b - a) / piece_s)));
      const double length = (b - a) / static_cast<double>(count);
      for (std::size_t i = 0; i < count; ++i) {
        const double p0 = a + static_cast<double>(i) * length;
        const PieceFit f = fit(p0, p0 + length);
        if (f.valid) centres.push_back({side, p0 + 0.5 * length - split_s, f.centre_hz, f.centre_se_hz});
      }
    }
    const bool both = std::any_of(centres.begin(), centres.end(), [](const Centre& c) { return c.side == 0; }) &&
                      std::any_of(centres.begin(), centres.end(), [](const Centre& c) { return c.side == 1; });
    if (!both || centres.size() < 3) return 0.0;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d right = Eigen::Vector3d::Zero();
    for (const Centre& c : centres) {
      const Eigen::Vector3d x(c.side == 0 ? 1.0 : 0.0, c.side == 1 ? 1.0 : 0.0, c.time_s);
      const double w = 1.0 / (c.se_hz * c.se_hz);
      normal += w * x * x.transpose();
      right += w * c.centre_hz * x;
    }
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(normal);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return 0.0;
    const Eigen::Vector3d beta = ldlt.solve(right);
    const Eigen::Matrix3d covariance = ldlt.solve(Eigen::Matrix3d::Identity());
    double chi2 = 0.0;
    for (const Centre& c : centres) {
      const double r = (c.centre_hz - beta(c.side) - beta(2) * c.time_s) / c.se_hz;
      chi2 += r * r;
    }
    const double dof = static_cast<double>(centres.size()) - 3.0;
    const double birge = dof >= 1.0 ? std::max(1.0, std::sqrt(chi2 / dof)) : 1.0;
    const double variance = covariance(0, 0) + covariance(1, 1) - 2.0 * covariance(0, 1);
    if (!(variance > 0.0)) return 0.0;
    return std::abs(beta(1) - beta(0)) / (birge * std::sqrt(variance));
  }

  //! Splits of [start_s, end_s) into pieces of at least `shortest_s`, recursively.
  void split(double start_s, double end_s, double shortest_s, double hop_s, double z_threshold, std::vector<StepMark>& steps) const {
    if (end_s - start_s < 2.0 * shortest_s) return;
    // Locating the split: the pieces' periodograms on the whole span's Fourier grid, from
    // running DTFT sums at every hop (one pass over the samples, then O(ordinates) a split).
    // A piece of length T_p sees those ordinates oversampled T / T_p times: its Whittle
    // log-likelihood is weighted by T_p / T. The split found, the two pieces are fitted on
    // their own grids for the test.
    const double fs = grid_.sample_rate_hz();
    const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil((start_s - grid_.start_s) / grid_.step_s)));
    const auto last = std::min(grid_.samples, static_cast<std::size_t>(std::max(0.0, std::ceil((end_s - grid_.start_s) / grid_.step_s))));
    const auto hop = static_cast<std::size_t>(std::max(1.0, std::round(hop_s / grid_.step_s)));
    const auto shortest = static_cast<std::size_t>(std::round(shortest_s / grid_.step_s));
    if (last <= first + 2 * shortest) return;
    const std::size_t n = last - first;
    const double bin = fs / static_cast<double>(n);
    std::vector<double> frequencies;
    for (auto j = static_cast<std::size_t>(std::ceil(low_hz_ / bin)); static_cast<double>(j) * bin <= high_hz_; ++j)
      frequencies.push_back(static_cast<double>(j) * bin);
    if (frequencies.size() < 8) return;
    const std::size_t marks = n / hop + 1;
    std::vector<std::complex<double>> running(frequencies.size() * (marks + 1));  // [mark][frequency]
    std::vector<std::size_t> at(marks + 1);
    {
      std::vector<std::complex<double>> sum(frequencies.size()), phasor(frequencies.size(), 1.0), rotation;
      for (double f : frequencies) rotation.push_back(std::polar(1.0, -2.0 * std::numbers::pi * f / fs));
      std::size_t mark = 0;
      for (std::size_t i = 0; i <= n; ++i) {
        if (i % hop == 0 || i == n) {
          std::copy(sum.begin(), sum.end(), running.begin() + static_cast<std::ptrdiff_t>(mark * frequencies.size()));
          at[mark++] = i;
          if (i == n) break;
        }
        const double y = v_[first + i];
        for (std::size_t j = 0; j < frequencies.size(); ++j) {
          sum[j] += y * phasor[j];
          phasor[j] *= rotation[j];
        }
        if ((i & 1023u) == 1023u)
          for (std::complex<double>& p : phasor) p /= std::abs(p);
      }
      at.resize(mark);
    }
    const std::size_t total_marks = at.size();
    auto piece = [&](std::size_t m0, std::size_t m1) {
      LocalPeriodogram p;
      p.frequency_hz = frequencies;
      const double samples = static_cast<double>(at[m1] - at[m0]);
      p.span_s = samples / fs;
      for (std::size_t j = 0; j < frequencies.size(); ++j)
        p.power.push_back(std::norm(running[m1 * frequencies.size() + j] - running[m0 * frequencies.size() + j]) / samples);
      const double start = start_s + static_cast<double>(at[m0]) / fs, end = start_s + static_cast<double>(at[m1]) / fs;
      // (Locating only: without the neighbours, whose two parameters each would multiply the
      // cost of the many candidate fits; the jump test below fits them.)
      const LorentzianFit lf = fit_lorentzian(p, median_line(start, end), half_width_hz_);
      return std::pair<double, bool>{lf.log_likelihood * samples / static_cast<double>(n), lf.valid};
    };
    double best_l = -std::numeric_limits<double>::infinity();
    std::size_t best = 0;
    std::vector<double> profile(total_marks, -std::numeric_limits<double>::infinity());
    for (std::size_t m = 1; m + 1 < total_marks; ++m) {
      if (at[m] < shortest || n - at[m] < shortest) continue;
      const auto [la, oka] = piece(0, m);
      const auto [lb, okb] = piece(m, total_marks - 1);
      if (!oka || !okb) continue;
      profile[m] = la + lb;
      if (profile[m] > best_l) best_l = profile[m], best = m;
    }
    if (!std::isfinite(best_l)) return;
    const double best_t = start_s + static_cast<double>(at[best]) / fs;
    if (!(jump_z(start_s, best_t, end_s, shortest_s) >= z_threshold)) return;
    StepMark m;
    m.time_s = best_t;
    m.low_s = best_t - hop_s;
    m.high_s = best_t + hop_s;
    for (std::size_t k = 0; k < total_marks; ++k)
      if (profile[k] >= best_l - 1.35) {
        const double t = start_s + static_cast<double>(at[k]) / fs;
        m.low_s = std::min(m.low_s, t - hop_s);
        m.high_s = std::max(m.high_s, t + hop_s);
      }
    steps.push_back(m);
    split(start_s, m.low_s, shortest_s, hop_s, z_threshold, steps);
    split(m.high_s, end_s, shortest_s, hop_s, z_threshold, steps);
  }

 private:
  const Track& track_;
  const std::vector<TrackWindow>& windows_;
  const RecordGrid& grid_;
  std::span<const double> v_;
  std::span<const double> neighbours_hz_;
  double low_hz_, high_hz_, half_width_hz_;
};

}  // namespace

void find_driven_steps(const KnownDevice& device, Track& track, const std::vector<TrackWindow>& windows, const RecordGrid& grid,
                       std::span<const double> v, std::span<const double> neighbours_hz, double z_threshold) {
  track.steps.clear();
  track.step_sightings.clear();
  const double gamma = device.damping_rate_per_s();
  const double half_width_hz = gamma / (2.0 * std::numbers::pi);
  const std::vector<SegmentSpan> spans = segment_spans(track, windows);
  if (spans.empty() || windows.size() < 2) return;
  const SegmentSpan& all = spans.front();  // no steps yet: one span
  std::vector<double> f;
  for (std::size_t i = all.first; i < all.last; ++i) f.push_back(track.sightings[i].line.frequency_hz);
  if (f.size() < 4) return;
  std::sort(f.begin(), f.end());
  const double f_low = f[f.size() / 10], f_high = f[f.size() - 1 - f.size() / 10];
  const FitBand fb = fit_band(f_low, f_high, 12.0 * half_width_hz, neighbours_hz, 3.0 * half_width_hz);
  const StepSearch search(device, track, windows, grid, v, fb.low_hz, fb.high_hz, fb.neighbours_hz);
  const double hop_s = windows[1].start_s - windows[0].start_s;
  std::vector<StepMark> steps;
  search.split(all.start_s, all.end_s, 4.0 / gamma, hop_s, z_threshold, steps);
  std::sort(steps.begin(), steps.end(), [](const StepMark& a, const StepMark& b) { return a.time_s < b.time_s; });
  for (StepMark& m : steps) {
    m.sighting = track.sightings.size();
    for (std::size_t i = 0; i < track.sightings.size(); ++i)
      if (windows[track.sightings[i].window].centre_s >= m.time_s) {
        m.sighting = i;
        break;
      }
    if (m.sighting > 0 && m.sighting < all.last) track.steps.push_back(m);
  }
}

}  // namespace stengmc
