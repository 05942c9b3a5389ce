#include "inverse/track_steps.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

namespace {

double median(std::vector<double> v) {
  auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

}  // namespace

void find_steps(Track& track, const std::vector<TrackWindow>& windows, std::size_t lag, bool excited, double threshold) {
  track.steps.clear();
  const std::vector<TrackSighting>& s = track.sightings;
  // The linker's steps: the old line in the window before the new one's first; excited, both
  // heard throughout, so the step lies between their centres; unexcited, the step's ringing
  // is heard from its window's end at the latest.
  for (std::size_t i : track.step_sightings) {
    const std::size_t b = s[i].window;
    StepMark m{i, 0.0, windows[b > 0 ? b - 1 : 0].centre_s, excited ? windows[b].centre_s : windows[b].end_s};
    m.time_s = 0.5 * (m.low_s + m.high_s);
    track.steps.push_back(m);
  }
  // Steps inside the track, in the sightings heard before its release and between the linker's steps.
  // (Up to its release, and only while its line is clear: a fading ringing's last estimates
  // scatter by more than the track's usual wander.)
  std::size_t heard = track.released ? track.release_sighting : s.size();
  while (heard > 0 && s[heard - 1].line.snr < 10.0) --heard;
  const std::size_t half = std::max<std::size_t>(3, 2 * lag);
  if (heard < 2 * half) return;
  std::vector<double> differences;
  for (std::size_t i = 0; i + lag < heard; ++i)
    if (s[i + lag].window - s[i].window == lag) differences.push_back(s[i + lag].line.frequency_hz - s[i].line.frequency_hz);
  if (differences.size() < 4) return;
  const double center = median(differences);
  for (double& d : differences) d = std::abs(d - center);
  const double sigma = 1.4826 * median(differences) / std::sqrt(2.0);
  if (!(sigma > 0.0)) return;
  // Each window's estimate varies by its own (inflated) Cramer-Rao error and the track's
  // wander; overlapping windows share samples, so a mean of `half` of them counts as half/lag.
  std::vector<double> variance(heard);
  for (std::size_t i = 0; i < heard; ++i)
    variance[i] = s[i].line.frequency_se_hz * s[i].line.frequency_se_hz + sigma * sigma;
  std::vector<double> statistic(heard, 0.0);
  const double correlation = static_cast<double>(lag) / static_cast<double>(half);
  for (std::size_t i = half; i + half <= heard; ++i) {
    double before = 0.0, after = 0.0, v_before = 0.0, v_after = 0.0;
    for (std::size_t j = 0; j < half; ++j) {
      before += s[i - half + j].line.frequency_hz;
      after += s[i + j].line.frequency_hz;
      v_before += variance[i - half + j];
      v_after += variance[i + j];
    }
    const double n = static_cast<double>(half);
    statistic[i] = std::abs(after - before) / n / std::sqrt(correlation * (v_before + v_after) / n);
  }
  // A long track (excited: a driven line wanders slowly, over more windows than its windows
  // overlap) is also judged against itself: the boundary's difference must stand out of all its
  // boundaries' differences (robust z: the median and 1.4826 MAD of them), so a wander that
  // is the track's habit makes no step.
  if (heard >= 6 * half) {
    std::vector<double> signed_differences;
    for (std::size_t i = half; i + half <= heard; i += half) {
      double before = 0.0, after = 0.0;
      for (std::size_t j = 0; j < half; ++j) {
        before += s[i - half + j].line.frequency_hz;
        after += s[i + j].line.frequency_hz;
      }
      signed_differences.push_back((after - before) / static_cast<double>(half));
    }
    const double centre = median(signed_differences);
    std::vector<double> deviations;
    for (double d : signed_differences) deviations.push_back(std::abs(d - centre));
    const double spread = 1.4826 * median(deviations);
    if (spread > 0.0)
      for (std::size_t i = half; i + half <= heard; ++i) {
        double before = 0.0, after = 0.0;
        for (std::size_t j = 0; j < half; ++j) {
          before += s[i - half + j].line.frequency_hz;
          after += s[i + j].line.frequency_hz;
        }
        const double robust = std::abs((after - before) / static_cast<double>(half) - centre) / spread;
        statistic[i] = std::min(statistic[i], robust);
      }
  }
  auto near_known = [&](std::size_t i) {
    return std::any_of(track.steps.begin(), track.steps.end(), [&](const StepMark& m) {
      return (m.sighting > i ? m.sighting - i : i - m.sighting) < half;
    });
  };
  for (;;) {
    std::size_t best = 0;
    for (std::size_t i = half; i + half <= heard; ++i)
      if (statistic[i] > statistic[best] && !near_known(i)) best = i;
    if (statistic[best] < threshold) break;
    // The crossing: the estimates move from one level to the other over the windows that
    // straddle the step; the step is where they pass the middle of the two levels.
    double before = 0.0, after = 0.0;
    for (std::size_t j = 0; j < half; ++j) {
      before += s[best - half + j].line.frequency_hz / static_cast<double>(half);
      after += s[best + j].line.frequency_hz / static_cast<double>(half);
    }
    const double middle = 0.5 * (before + after);
    std::size_t cross = best;
    for (std::size_t i = best - half + 1; i < best + half; ++i)
      if ((s[i - 1].line.frequency_hz - middle) * (after - before) < 0.0 && (s[i].line.frequency_hz - middle) * (after - before) >= 0.0) {
        cross = i;
        if (i >= best) break;
      }
    const double length = windows[s[cross].window].end_s - windows[s[cross].window].start_s;
    const double t = 0.5 * (windows[s[cross - 1].window].centre_s + windows[s[cross].window].centre_s);
    track.steps.push_back({best, t, t - 0.5 * length, t + 0.5 * length});
    for (std::size_t i = best - half + 1; i < best + half; ++i) statistic[i] = 0.0;
  }
  std::sort(track.steps.begin(), track.steps.end(), [](const StepMark& a, const StepMark& b) { return a.sighting < b.sighting; });
}

}  // namespace stengmc
