#include "inverse/driven_steps.hpp"

#include <algorithm>
#include <cmath>
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
             std::span<const double> v, double low_hz, double high_hz)
      : track_(track), windows_(windows), grid_(grid), v_(v), low_hz_(low_hz), high_hz_(high_hz),
        half_width_hz_(device.damping_rate_per_s() / (2.0 * std::numbers::pi)) {}

  //! The line fitted over [start_s, end_s), started at the median of the sightings whose window centre lies in it.
  PieceFit fit(double start_s, double end_s) const {
    PieceFit out;
    std::vector<double> f;
    for (const TrackSighting& s : track_.sightings) {
      const double c = windows_[s.window].centre_s;
      if (c >= start_s && c < end_s) f.push_back(s.line.frequency_hz);
    }
    if (f.empty()) return out;
    std::nth_element(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(f.size() / 2), f.end());
    const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil((start_s - grid_.start_s) / grid_.step_s)));
    const auto last = std::min(grid_.samples, static_cast<std::size_t>(std::max(0.0, std::ceil((end_s - grid_.start_s) / grid_.step_s))));
    if (last <= first + 16) return out;
    const LocalPeriodogram p = local_periodogram(v_.subspan(first, last - first), grid_.sample_rate_hz(), low_hz_, high_hz_);
    const LorentzianFit lf = fit_lorentzian(p, f[f.size() / 2], half_width_hz_);
    out.valid = lf.valid;
    out.log_likelihood = lf.log_likelihood;
    out.centre_hz = lf.centre_hz;
    out.centre_se_hz = lf.centre_se_hz;
    return out;
  }

  //! Splits of [start_s, end_s) into pieces of at least `shortest_s`, recursively.
  void split(double start_s, double end_s, double shortest_s, double hop_s, double z_threshold, std::vector<StepMark>& steps) const {
    if (end_s - start_s < 2.0 * shortest_s) return;
    // Coarse then fine: every 4 hops, then every hop around the best.
    auto profile = [&](double t) {
      const PieceFit a = fit(start_s, t), b = fit(t, end_s);
      return std::pair<double, bool>{a.log_likelihood + b.log_likelihood, a.valid && b.valid};
    };
    double best_t = 0.0, best_l = -std::numeric_limits<double>::infinity();
    for (double t = start_s + shortest_s; t <= end_s - shortest_s; t += 4.0 * hop_s) {
      const auto [l, ok] = profile(t);
      if (ok && l > best_l) best_l = l, best_t = t;
    }
    if (!std::isfinite(best_l)) return;
    std::vector<std::pair<double, double>> fine;
    for (double t = std::max(start_s + shortest_s, best_t - 4.0 * hop_s); t <= std::min(end_s - shortest_s, best_t + 4.0 * hop_s);
         t += hop_s) {
      const auto [l, ok] = profile(t);
      if (!ok) continue;
      fine.emplace_back(t, l);
      if (l > best_l) best_l = l, best_t = t;
    }
    const PieceFit before = fit(start_s, best_t), after = fit(best_t, end_s);
    if (!before.valid || !after.valid) return;
    const double z = std::abs(after.centre_hz - before.centre_hz) / std::hypot(before.centre_se_hz, after.centre_se_hz);
    if (!(z >= z_threshold)) return;
    StepMark m;
    m.time_s = best_t;
    m.low_s = best_t - hop_s;
    m.high_s = best_t + hop_s;
    for (const auto& [t, l] : fine)
      if (l >= best_l - 1.35) m.low_s = std::min(m.low_s, t - hop_s), m.high_s = std::max(m.high_s, t + hop_s);
    steps.push_back(m);
    split(start_s, m.low_s, shortest_s, hop_s, z_threshold, steps);
    split(m.high_s, end_s, shortest_s, hop_s, z_threshold, steps);
  }

 private:
  const Track& track_;
  const std::vector<TrackWindow>& windows_;
  const RecordGrid& grid_;
  std::span<const double> v_;
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
  double below = 12.0 * half_width_hz, above = 12.0 * half_width_hz;
  for (double other : neighbours_hz) {
    if (other < f_low) below = std::min(below, std::max(3.0 * half_width_hz, 0.5 * (f_low - other)));
    if (other > f_high) above = std::min(above, std::max(3.0 * half_width_hz, 0.5 * (other - f_high)));
  }
  const StepSearch search(device, track, windows, grid, v, f_low - below, f_high + above);
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
