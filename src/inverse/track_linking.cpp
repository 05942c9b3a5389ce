#include "inverse/track_linking.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "spectral/assignment.hpp"

namespace stengmc {

namespace {

constexpr double FORBIDDEN = std::numeric_limits<double>::infinity();

struct LiveTrack {
  Track track;
  std::size_t missed = 0;  //!< consecutive windows without a sighting
  bool closed = false;
};

const WindowLine& last_line(const LiveTrack& t) { return t.track.sightings.back().line; }

//! Where the gate is centred: the last line, or the median of the last `count` lines [Hz].
double reference_frequency(const Track& t, std::size_t count) {
  if (count <= 1) return t.sightings.back().line.frequency_hz;
  std::vector<double> f;
  for (std::size_t i = t.sightings.size() > count ? t.sightings.size() - count : 0; i < t.sightings.size(); ++i)
    f.push_back(t.sightings[i].line.frequency_hz);
  std::nth_element(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(f.size() / 2), f.end());
  return f[f.size() / 2];
}

//! Median snr of the track's last few sightings: its steady level.
double recent_level(const Track& t) {
  std::vector<double> levels;
  for (std::size_t i = t.sightings.size() >= 4 ? t.sightings.size() - 4 : 0; i < t.sightings.size(); ++i)
    levels.push_back(t.sightings[i].line.snr);
  std::nth_element(levels.begin(), levels.begin() + static_cast<std::ptrdiff_t>(levels.size() / 2), levels.end());
  return levels[levels.size() / 2];
}

//! Unexcited, a step rings the asperity freely at its new stiffness: its line decays at c/2m.
//! A window where an onset or step starts part-way holds lines that are no ringing (the
//! plateau's jump, mixtures), with dampings far from it.
bool free_ringing(const WindowLine& l, const LinkSettings& s) {
  return std::abs(l.damping_per_s - s.free_damping_per_s) <= 0.6 * s.free_damping_per_s;
}

//! Unexcited: a step rings no louder than the belt lets it (max_step_ringing_v; 0: no check).
bool within_step_ringing(const WindowLine& l, const LinkSettings& s) {
  return s.max_step_ringing_v <= 0.0 || l.amplitude_v <= s.max_step_ringing_v;
}

void add_sighting(LiveTrack& t, std::size_t window, const WindowLine& line) {
  t.track.sightings.push_back({window, line});
  if (t.track.sightings.size() <= 3) t.track.onset_level = std::max(t.track.onset_level, line.snr);
  t.missed = 0;
}

//! Unexcited: a track born where a silent, held track's line would be after a step (its first
//! clear line within step_fraction of the held one's last) continues that track with a step.
//! The window that straddles a step can hold a line between the two, which starts the new
//! track before the clear line would have been linked as a step.
void merge_steps_of_silent_tracks(std::vector<LiveTrack>& tracks, const LinkSettings& s) {
  for (std::size_t b = 0; b < tracks.size(); ++b) {
    Track& born = tracks[b].track;
    if (born.sightings.size() < s.min_sightings || born.sightings.front().window == 0) continue;
    const auto clear = std::find_if(born.sightings.begin(), born.sightings.end(),
                                    [&](const TrackSighting& x) { return x.line.snr >= s.reacquire_snr && free_ringing(x.line, s); });
    if (clear != born.sightings.end() && !within_step_ringing(clear->line, s)) continue;
    if (clear == born.sightings.end()) continue;
    const std::size_t start = born.sightings.front().window;
    std::size_t best = tracks.size();
    double best_rel = s.step_fraction;
    for (std::size_t a = 0; a < tracks.size(); ++a) {
      const Track& held = tracks[a].track;
      if (a == b || held.released || held.sightings.size() < s.min_sightings || held.sightings.back().window + 2 > start) continue;
      const double f0 = held.sightings.back().line.frequency_hz;
      const double rel = std::abs(clear->line.frequency_hz - f0) / f0;
      if (rel <= best_rel) best = a, best_rel = rel;
    }
    if (best == tracks.size()) continue;
    Track& held = tracks[best].track;
    held.step_sightings.push_back(held.sightings.size());
    held.sightings.insert(held.sightings.end(), born.sightings.begin(), born.sightings.end());
    born.sightings.clear();
  }
}

//! Median frequency of the sightings of `t` in windows [first, last] [Hz] (0 when none).
double median_frequency(const Track& t, std::size_t first, std::size_t last) {
  std::vector<double> f;
  for (const TrackSighting& x : t.sightings)
    if (x.window >= first && x.window <= last) f.push_back(x.line.frequency_hz);
  if (f.empty()) return 0.0;
  std::nth_element(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(f.size() / 2), f.end());
  return f[f.size() / 2];
}

//! Excited: one driven line often ends up as two tracks taking turns (a side feature starts a
//! track beside the line, which then takes the line whenever the first track's gate misses it),
//! and a stiffness step moves the line out of the gate at once. Two tracks within a step's reach
//! (step_fraction) of each other where they meet, not both heard in most of the windows they
//! share (min_duty: two driven asperities would be), and the second born before the first has
//! been silent for max_missed windows, are one asperity: merged (where both are heard, the
//! stronger line kept). A step between them is found afterwards in the merged track
//! (track_steps.hpp).
void merge_interleaved_tracks(std::vector<LiveTrack>& tracks, const LinkSettings& s) {
  const std::size_t reach = std::max<std::size_t>(1, s.step_overlap_windows);
  // The relative distance of two tracks' lines where they meet when they may be one asperity
  // (below), else nothing.
  auto candidate = [&](const Track& first, const Track& second) -> std::optional<double> {
    const std::size_t a0 = first.sightings.front().window, a1 = first.sightings.back().window;
    const std::size_t b0 = second.sightings.front().window, b1 = second.sightings.back().window;
    if (b0 > a1 + s.max_missed || a0 > b1 + s.max_missed) return std::nullopt;
    // Where they meet: the shared windows, or the ends that face each other.
    const std::size_t lo = std::max(a0, b0), hi = std::min(a1, b1);
    double fa = 0.0, fb = 0.0;
    if (lo <= hi) {
      fa = median_frequency(first, lo > reach ? lo - reach : 0, hi + reach);
      fb = median_frequency(second, lo > reach ? lo - reach : 0, hi + reach);
    } else if (a1 < b0) {
      fa = median_frequency(first, a1 > reach ? a1 - reach : 0, a1);
      fb = median_frequency(second, b0, b0 + reach);
    } else {
      fa = median_frequency(first, a0, a0 + reach);
      fb = median_frequency(second, b1 > reach ? b1 - reach : 0, b1);
    }
    if (!(fa > 0.0 && fb > 0.0) || std::abs(fa - fb) > s.step_fraction * fa) return std::nullopt;
    // Two asperities are both heard in most of the windows they share (min_duty), past the
    // windows that straddle where the second began; unless their lines lie within twice a
    // window's peak error of each other: two random peaks of one line (a window of two
    // coherence times often shows the line as two bumps), which the windows cannot tell
    // from two asperities anyway.
    const double window_se = std::max(first.sightings.back().line.frequency_se_hz, second.sightings.front().line.frequency_se_hz);
    if (lo + reach <= hi && std::abs(fa - fb) > 2.0 * window_se) {
      const auto duty = [&](const Track& t) {
        const auto heard = std::count_if(t.sightings.begin(), t.sightings.end(),
                                         [&](const TrackSighting& x) { return x.window >= lo + reach && x.window <= hi; });
        return static_cast<double>(heard) / static_cast<double>(hi - lo - reach + 1);
      };
      if (duty(first) >= s.min_duty && duty(second) >= s.min_duty) return std::nullopt;
    }
    return std::abs(fa - fb) / fa;
  };
  // The closest pair first: a piece of a line belongs to the track nearest it, not to one
  // that merely ended there (a released asperity's track must not take a neighbour's line).
  for (;;) {
    std::size_t best_a = tracks.size(), best_b = tracks.size();
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < tracks.size(); ++a) {
      if (tracks[a].track.sightings.empty()) continue;
      for (std::size_t b = a + 1; b < tracks.size(); ++b) {
        if (tracks[b].track.sightings.empty()) continue;
        const std::optional<double> d = candidate(tracks[a].track, tracks[b].track);
        if (d && *d < best) best = *d, best_a = a, best_b = b;
      }
    }
    if (best_a == tracks.size()) break;
    Track& first = tracks[best_a].track;
    Track& second = tracks[best_b].track;
    const std::size_t a1 = first.sightings.back().window;
    std::vector<TrackSighting> all = first.sightings;
    all.insert(all.end(), second.sightings.begin(), second.sightings.end());
    std::stable_sort(all.begin(), all.end(), [](const TrackSighting& x, const TrackSighting& y) { return x.window < y.window; });
    std::vector<TrackSighting> kept;
    for (const TrackSighting& x : all)
      if (!kept.empty() && kept.back().window == x.window) {
        if (x.line.snr > kept.back().line.snr) kept.back() = x;
      } else {
        kept.push_back(x);
      }
    first.sightings = std::move(kept);
    first.onset_level = 0.0;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, first.sightings.size()); ++i)
      first.onset_level = std::max(first.onset_level, first.sightings[i].line.snr);
    first.ended = first.sightings.back().window == a1 ? first.ended : second.ended;
    second.sightings.clear();
  }
}

//! Excited, an asperity in contact is driven and heard in most windows: a track heard in
//! fewer than min_duty of the windows it spans is random lines the wide gate strung together.
bool heard_enough(const Track& t, const LinkSettings& s) {
  if (s.hold_silent) return true;
  const double span = static_cast<double>(t.sightings.back().window - t.sightings.front().window + 1);
  return static_cast<double>(t.sightings.size()) >= s.min_duty * span;
}

}  // namespace

std::vector<Track> link_tracks(const std::vector<WindowLines>& windows, const LinkSettings& s) {
  std::vector<LiveTrack> tracks;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    std::vector<const WindowLine*> lines;
    for (const WindowLine& l : windows[w].lines)
      if (l.detected) lines.push_back(&l);
    std::vector<std::size_t> live;
    for (std::size_t t = 0; t < tracks.size(); ++t)
      if (!tracks[t].closed) live.push_back(t);

    // 1. Gated nearest-neighbour assignment of lines to live tracks. The gate widens with
    // the windows since the track was last heard (wear may have moved its line).
    Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(live.size()),
                                                     static_cast<Eigen::Index>(lines.size()), FORBIDDEN);
    for (std::size_t r = 0; r < live.size(); ++r) {
      const LiveTrack& t = tracks[live[r]];
      const WindowLine& last = last_line(t);
      const double reference_hz = reference_frequency(t.track, s.reference_sightings);
      const double elapsed = static_cast<double>(w - t.track.sightings.back().window);
      for (std::size_t c = 0; c < lines.size(); ++c) {
        const double df = std::abs(lines[c]->frequency_hz - reference_hz);
        // (The median of the last lag lines, about two independent ones, halves their variance.)
        const double track_se = s.reference_sightings > 1 ? last.frequency_se_hz / std::numbers::sqrt2 : last.frequency_se_hz;
        const double sigma = std::sqrt(lines[c]->frequency_se_hz * lines[c]->frequency_se_hz + track_se * track_se +
                                       s.gate_floor_hz * s.gate_floor_hz);
        const double drift = s.drift_per_window * elapsed * last.frequency_hz;
        // A track silent for a while is heard again only by a clear line: a weak one then is
        // more likely noise than the asperity ringing again.
        const bool clear = t.missed < 2 || lines[c]->snr >= s.reacquire_snr;
        if (clear && df <= s.gate_z * sigma + drift)
          cost(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = std::pow(df / (sigma + drift), 2);
      }
    }
    std::vector<int> assigned = live.empty() || lines.empty() ? std::vector<int>(live.size(), -1) : hungarian_assignment(cost);
    std::vector<bool> line_used(lines.size(), false);
    std::vector<bool> track_seen(live.size(), false);
    for (std::size_t r = 0; r < live.size(); ++r) {
      if (assigned[r] < 0) continue;
      const auto c = static_cast<std::size_t>(assigned[r]);
      LiveTrack& t = tracks[live[r]];
      // A burst on a known track: a held track heard again, or an excited one jumping well above
      // its steady level. As strong as its onset: the release (full deflection rings out).
      const bool was_silent = t.missed >= 2;
      const bool burst = was_silent || lines[c]->snr >= s.burst_ratio * recent_level(t.track);
      // (After its first three sightings: the onset's own rise is no release.)
      // Unexcited only: an excited line's level wanders by x3 and more; its release is found
      // afterwards from the free ring-down (find_free_ringdown).
      const bool release = s.hold_silent && burst && !t.track.released && t.track.sightings.size() >= 3 &&
                           lines[c]->snr >= s.release_level_fraction * t.track.onset_level;
      add_sighting(t, w, *lines[c]);
      if (release) {
        t.track.released = true;
        t.track.release_sighting = t.track.sightings.size() - 1;
      }
      line_used[c] = true;
      track_seen[r] = true;
    }

    // 2. Lines left over: a stiffness step of a track that lost its line (the step's ringing is
    // weaker than an onset's), else a new asperity.
    std::vector<std::size_t> free_lines, step_tracks;
    for (std::size_t c = 0; c < lines.size(); ++c)
      if (!line_used[c]) free_lines.push_back(c);
    for (std::size_t r = 0; r < live.size(); ++r)
      if (!track_seen[r] && !tracks[live[r]].track.released && tracks[live[r]].track.sightings.size() >= s.min_sightings)
        step_tracks.push_back(live[r]);
    // (Unexcited only: a driven line is followed through a step by the gate, which its wander
    // widens, and the step found inside the track: track_steps.hpp.)
    if (s.hold_silent && !free_lines.empty() && !step_tracks.empty()) {
      Eigen::MatrixXd step_cost = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(step_tracks.size()),
                                                            static_cast<Eigen::Index>(free_lines.size()), FORBIDDEN);
      for (std::size_t r = 0; r < step_tracks.size(); ++r) {
        const LiveTrack& t = tracks[step_tracks[r]];
        const double f0 = last_line(t).frequency_hz;
        const double elapsed = static_cast<double>(w - t.track.sightings.back().window);
        for (std::size_t c = 0; c < free_lines.size(); ++c) {
          const WindowLine& l = *lines[free_lines[c]];
          const double rel = std::abs(l.frequency_hz - f0) / f0;
          if (l.snr >= s.reacquire_snr && (!s.hold_silent || (free_ringing(l, s) && within_step_ringing(l, s))) &&
              rel <= s.step_fraction + s.drift_per_window * elapsed)
            step_cost(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rel;
        }
      }
      const std::vector<int> steps = hungarian_assignment(step_cost);
      for (std::size_t r = 0; r < step_tracks.size(); ++r) {
        if (steps[r] < 0) continue;
        LiveTrack& t = tracks[step_tracks[r]];
        const std::size_t c = free_lines[static_cast<std::size_t>(steps[r])];
        add_sighting(t, w, *lines[c]);
        t.track.step_sightings.push_back(t.track.sightings.size() - 1);
        line_used[c] = true;
        for (std::size_t q = 0; q < live.size(); ++q)
          if (live[q] == step_tracks[r]) track_seen[q] = true;
      }
    }

    // 3. Misses and deaths; births.
    for (std::size_t r = 0; r < live.size(); ++r) {
      if (track_seen[r]) continue;
      LiveTrack& t = tracks[live[r]];
      ++t.missed;
      const bool holds = s.hold_silent && !t.track.released && t.track.sightings.size() >= s.min_sightings;
      if (!holds && t.missed > s.max_missed) {
        t.closed = true;
        t.track.ended = true;
      }
    }
    for (std::size_t c = 0; c < lines.size(); ++c) {
      if (line_used[c]) continue;
      LiveTrack t;
      add_sighting(t, w, *lines[c]);
      tracks.push_back(std::move(t));
    }
  }
  if (s.hold_silent) merge_steps_of_silent_tracks(tracks, s);
  else if (s.step_overlap_windows > 0) merge_interleaved_tracks(tracks, s);
  std::vector<Track> out;
  for (LiveTrack& t : tracks)
    if (t.track.sightings.size() >= s.min_sightings && heard_enough(t.track, s)) {
      if (!s.hold_silent) find_free_ringdown(t.track, s.free_damping_per_s);  // at the record's end too
      out.push_back(std::move(t.track));
    }
  return out;
}

void find_free_ringdown(Track& track, double gamma) {
  constexpr std::size_t MIN_RINGDOWN = 3;
  const std::vector<TrackSighting>& s = track.sightings;
  // The last sightings, where the ringing fades into the noise, have unreliable dampings: the
  // ring-down is judged on those still well above the noise (twice the weakest detectable).
  // Released, nothing drives the asperity: its line is a free ringing, decaying at c/2m
  // across the window. (The band's floor falling back to the white noise, 5-20 x lower than
  // in contact, would tell too, but only for a lone asperity: others driven keep it up.)
  auto free = [&](const WindowLine& l) { return l.damping_per_s >= 0.6 * gamma && l.damping_per_s <= 1.6 * gamma; };
  std::size_t end = s.size();
  while (end > 0 && s[end - 1].line.snr < 10.0) --end;
  // Excited, the last windows of a fading line also hold its neighbours' leakage, which the
  // halves' damping picks up: up to 3 trailing sightings that do not look free are passed over.
  for (std::size_t skipped = 0; skipped < 3 && end > 0 && !free(s[end - 1].line); ++skipped) --end;
  std::size_t first = end;
  while (first > 0) {
    const WindowLine& l = s[first - 1].line;
    const bool falls = first == end || l.snr >= 0.8 * s[first].line.snr;
    if (!free(l) || !falls) break;
    --first;
  }
  if (end - first < MIN_RINGDOWN || first == 0) return;  // from its birth: an onset's ringing, not a release
  track.released = true;
  track.release_sighting = first;
}

}  // namespace stengmc
