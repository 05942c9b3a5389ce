#include "inverse/track_segments.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "inverse/line_centre_fit.hpp"
#include "inverse/track_lines.hpp"

namespace stengmc {

std::vector<SegmentSpan> segment_spans(const Track& track, const std::vector<TrackWindow>& windows) {
  std::vector<SegmentSpan> spans;
  const std::vector<TrackSighting>& s = track.sightings;
  const std::size_t heard = track.released ? track.release_sighting : s.size();
  if (heard == 0) return spans;
  double start_s = windows[s.front().window].centre_s;
  std::size_t first = 0;
  for (const StepMark& m : track.steps) {
    if (m.sighting >= heard || m.sighting <= first) continue;
    spans.push_back({start_s, m.low_s, first, m.sighting});
    start_s = m.high_s;
    first = m.sighting;
  }
  const double end_s = track.released ? windows[s[track.release_sighting].window].start_s : windows[s[heard - 1].window].centre_s;
  spans.push_back({start_s, end_s, first, heard});
  return spans;
}

std::vector<TrackSegment> fit_driven_segments(const KnownDevice& device, const Track& track, std::size_t index,
                                              const std::vector<TrackWindow>& windows, const RecordGrid& grid,
                                              std::span<const double> v, std::span<const double> neighbours_hz) {
  std::vector<TrackSegment> segments;
  const double gamma = device.damping_rate_per_s();
  const double half_width_hz = gamma / (2.0 * std::numbers::pi);
  const double shortest_s = 4.0 / gamma;  // 4 tau (tau = 2m/c = 1/gamma)
  for (const SegmentSpan& span : segment_spans(track, windows)) {
    if (span.end_s - span.start_s < shortest_s || span.last <= span.first) continue;
    std::vector<double> f;
    for (std::size_t i = span.first; i < span.last; ++i) f.push_back(track.sightings[i].line.frequency_hz);
    std::sort(f.begin(), f.end());
    const double guess = f[f.size() / 2];
    // The band holds the windows' lines (10-90 %: a wearing line drifts across the segment)
    // and 12 half-widths beyond; other tracks' lines in it are fitted with this one.
    const double f_low = f[f.size() / 10], f_high = f[f.size() - 1 - f.size() / 10];
    const FitBand fb = fit_band(f_low, f_high, 12.0 * half_width_hz, neighbours_hz, 3.0 * half_width_hz);
    const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil((span.start_s - grid.start_s) / grid.step_s)));
    const auto last = std::min(grid.samples, static_cast<std::size_t>(std::floor((span.end_s - grid.start_s) / grid.step_s)) + 1);
    if (last <= first + 16) continue;
    const LocalPeriodogram p = local_periodogram(v.subspan(first, last - first), grid.sample_rate_hz(), fb.low_hz, fb.high_hz);
    // A stationary line's window peaks spread over ~2.6 x their error (10-90 %); a line that
    // drifts (wear) further is smeared over the span: its width is fitted too (the centre is
    // then the span's middle, its error that of the wider line).
    const double window_se = track.sightings[span.first].line.frequency_se_hz;
    const bool drifting = f_high - f_low > 4.0 * window_se;
    const LorentzianFit fit = fit_lorentzian(p, guess, drifting ? 0.5 * (f_high - f_low) : half_width_hz, drifting, fb.neighbours_hz);
    if (!fit.valid) continue;
    // The model's adequacy: the windows' peaks about the fitted centre against their own
    // error (the line's wander in a window: track_peaks.hpp). A stationary line gives a mean
    // square of ~1; a track that mixes two asperities' lines, or drifts, more: the centre's
    // error is scaled by that Birge ratio sqrt(mean r^2) (never below 1).
    double sum_r2 = 0.0;
    for (std::size_t i = span.first; i < span.last; ++i) {
      const WindowLine& l = track.sightings[i].line;
      const double r = (l.frequency_hz - fit.centre_hz) / l.frequency_se_hz;
      sum_r2 += r * r;
    }
    const double birge = std::max(1.0, std::sqrt(sum_r2 / static_cast<double>(span.last - span.first)));
    const double se_hz = birge * fit.centre_se_hz;
    TrackSegment g;
    g.track = index;
    g.start_s = span.start_s;
    g.end_s = span.end_s;
    g.windows = span.last - span.first;
    g.frequency_hz = fit.centre_hz;
    g.frequency_se_hz = se_hz;
    g.stiffness_n_per_m = stiffness_at(device, fit.centre_hz);
    g.stiffness_low = stiffness_at(device, std::max(0.0, fit.centre_hz - Z90 * se_hz));
    g.stiffness_high = stiffness_at(device, fit.centre_hz + Z90 * se_hz);
    segments.push_back(g);
  }
  return segments;
}

}  // namespace stengmc
