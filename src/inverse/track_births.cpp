#include "inverse/track_births.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "inverse/event_ringing.hpp"
#include "inverse/track_events.hpp"
#include "inverse/track_lines.hpp"

namespace stengmc {

namespace {

//! The amplitude at burst `e` (its estimate) of the ringing of `t`, extrapolated back along
//! e^{-gamma t} from its lines in windows that start after the burst's latest time (earlier
//! ones may straddle it and under-read it): the median over the first four such lines (~20 us).
//! A free ringing decays exactly so, and each window gives the same initial amplitude but for
//! a neighbour's beat, which in a crowded band moves a window's amplitude by up to 2x [V].
std::optional<double> amplitude_at(const Track& t, const std::vector<TrackWindow>& windows, const TrackEvent& e, double gamma) {
  constexpr std::size_t LINES = 4;
  std::vector<double> a;
  for (const TrackSighting& s : t.sightings) {
    const double start = windows[s.window].start_s;
    if (start >= e.time_high_s) a.push_back(s.line.amplitude_v * std::exp(gamma * (start - e.time_s)));
    if (a.size() == LINES) break;
  }
  if (a.empty()) return std::nullopt;
  std::sort(a.begin(), a.end());
  return a.size() % 2 == 1 ? a[a.size() / 2] : 0.5 * (a[a.size() / 2 - 1] + a[a.size() / 2]);
}

//! Whether `t`, born by a burst of matched-filter SNR `snr` at `birth_s`, is heard about as long
//! as a free ringing stays above the detection threshold `threshold`: ln(snr / threshold) / gamma
//! (~90 us from z = 500). At least half of that (a neighbour's line may take its last
//! windows): a line heard only in the windows that straddle someone's onset is the fit's
//! artefact of a partial ringing, not a ringing of its own. The record may end sooner: then
//! it must be heard to the record's end (an onset in its last ~45 us is no artefact for that).
bool heard_as_long_as_it_rings(const Track& t, const std::vector<TrackWindow>& windows, double birth_s, double gamma,
                               double threshold) {
  double snr = 0.0;
  for (const TrackSighting& s : t.sightings) snr = std::max(snr, s.line.snr);
  // (Undamped, c = 0: a free ringing never fades, and is heard to the record's end.)
  const double rings_s = gamma > 0.0 ? std::log(std::max(1.0, snr / threshold)) / gamma : std::numeric_limits<double>::infinity();
  const double left_s = windows.back().end_s - birth_s;
  return windows[t.sightings.back().window].end_s - birth_s >= std::min(0.5 * rings_s, left_s);
}

//! Median frequency of the first three sightings [Hz].
double first_frequency(const Track& t) {
  std::vector<double> f;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, t.sightings.size()); ++i) f.push_back(t.sightings[i].line.frequency_hz);
  std::sort(f.begin(), f.end());
  return f[f.size() / 2];
}

bool within(double measured, double predicted) {
  return measured >= predicted / RINGING_TOLERANCE && measured <= predicted * RINGING_TOLERANCE;
}

//! Appends `born`'s sightings to `held` (which went silent before `born` began) and empties it.
//! What `born` had found in itself (its release, its steps) is carried over. Returns the index
//! of its first sighting in `held`.
std::size_t absorb(Track& held, Track& born) {
  const std::size_t first = held.sightings.size();
  held.sightings.insert(held.sightings.end(), born.sightings.begin(), born.sightings.end());
  for (const std::size_t s : born.step_sightings) held.step_sightings.push_back(first + s);
  if (born.released) held.released = true, held.release_sighting = first + born.release_sighting;
  born.sightings.clear();
  return first;
}

//! The number of `t`'s sightings before the `lag` windows that precede `first_window` (those
//! share samples with the event there, if it is one, and straddle it).
std::size_t clear_of(const Track& t, std::size_t first_window, std::size_t lag) {
  std::size_t n = t.sightings.size();
  while (n > 0 && t.sightings[n - 1].window + lag > first_window) --n;
  return n;
}

//! Drops `t`'s sightings from `i` on (and the steps marked there).
void drop_from(Track& t, std::size_t i) {
  t.sightings.resize(i);
  std::erase_if(t.step_sightings, [&](std::size_t s) { return s >= i; });
}

//! Marks `t` released at sighting `i`: a released asperity's line is its frozen stiffness, so
//! no step of it is heard afterwards (a linker's step there was the ringing-down's wander).
void release_at(Track& t, std::size_t i) {
  t.released = true;
  t.release_sighting = i;
  std::erase_if(t.step_sightings, [&](std::size_t s) { return s >= i; });
}

}  // namespace

void confirm_releases(const KnownDevice& device, std::vector<Track>& tracks, const std::vector<TrackWindow>& windows,
                      std::size_t lag) {
  const double gamma = device.damping_rate_per_s();
  const std::size_t count = tracks.size();
  for (std::size_t t = 0; t < count; ++t) {
    if (!tracks[t].released || tracks[t].release_sighting == 0) continue;
    const std::size_t r = tracks[t].release_sighting;
    const TrackEvent burst = burst_event(TrackEventKind::release, tracks[t].sightings[r].window, windows, t);
    Track after;
    after.sightings.assign(tracks[t].sightings.begin() + static_cast<std::ptrdiff_t>(r), tracks[t].sightings.end());
    // (A burst heard in no window clear of its start is no release: a released asperity rings
    // from its full deflection for ~100 us.)
    const double heard = amplitude_at(after, windows, burst, gamma).value_or(0.0);
    const double k = stiffness_at(device, first_frequency(after));
    const double onset_v = onset_ringing_v(device, k), release_v = release_ringing_v(device, k);
    if (heard >= release_v / RINGING_TOLERANCE && heard >= std::sqrt(onset_v * release_v)) continue;  // a release
    Track& track = tracks[t];
    track.released = false;
    track.release_sighting = 0;
    if (within(heard, onset_v)) {
      // As loud as an onset: a new asperity on the held one's line. Its own track, from the burst
      // and the windows just before it that straddle its start (the linker gave them to the
      // held track as its line re-heard, not yet loud enough for a burst).
      std::size_t from = r;
      while (from > 0 && r - from < lag && tracks[t].sightings[from].window - tracks[t].sightings[from - 1].window == 1) --from;
      if (from > 0 && tracks[t].sightings[from].window - tracks[t].sightings[from - 1].window == 1) from = r;  // heard all along: no straddle
      after.sightings.assign(tracks[t].sightings.begin() + static_cast<std::ptrdiff_t>(from), tracks[t].sightings.end());
      after.onset_level = 0.0;
      for (std::size_t i = 0; i < std::min<std::size_t>(3, after.sightings.size()); ++i)
        after.onset_level = std::max(after.onset_level, after.sightings[i].line.snr);
      for (const std::size_t s : track.step_sightings)
        if (s > from) after.step_sightings.push_back(s - from);
      std::erase_if(track.step_sightings, [&](std::size_t s) { return s >= from; });
      track.sightings.resize(from);
      tracks.push_back(std::move(after));
    }
    // (Weaker: the held line re-heard, which the linker took for a burst.)
  }
}

void classify_track_births(const KnownDevice& device, std::vector<Track>& tracks, const std::vector<TrackWindow>& windows,
                           const LinkSettings& link, double max_wear_per_ms, double threshold_snr, std::size_t lag) {
  const double gamma = device.damping_rate_per_s();
  const double record_start_s = windows.front().start_s;
  // Births in time order: a track merged into a held one may itself take a later birth.
  std::vector<std::size_t> order(tracks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return tracks[a].sightings.front().window < tracks[b].sightings.front().window;
  });
  for (const std::size_t b : order) {
    Track& born = tracks[b];
    if (born.sightings.empty() || born.sightings.front().window == 0) continue;
    const std::size_t first_window = born.sightings.front().window;
    const TrackEvent birth = burst_event(TrackEventKind::onset, first_window, windows, b);
    const double birth_s = birth.time_s;
    const std::optional<double> heard = amplitude_at(born, windows, birth, gamma);
    if (!heard) continue;
    const double f = first_frequency(born);
    // The error of its clearest first line (the first may straddle the birth and be poor).
    double born_se_hz = born.sightings.front().line.frequency_se_hz, born_snr = 0.0;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, born.sightings.size()); ++i)
      if (born.sightings[i].line.snr > born_snr) born_snr = born.sightings[i].line.snr, born_se_hz = born.sightings[i].line.frequency_se_hz;
    const double k = stiffness_at(device, f);
    const double onset_v = onset_ringing_v(device, k), release_v = release_ringing_v(device, k);
    const double a = *heard;
    const bool release_like = a >= release_v / RINGING_TOLERANCE && a >= std::sqrt(onset_v * release_v);
    const bool weak = a < onset_v / RINGING_TOLERANCE;
    if (!release_like && !weak) {
      // An onset (or louder than one, not a release: left as before), when it rings as long as one.
      if (!heard_as_long_as_it_rings(born, windows, birth_s, gamma, threshold_snr)) born.birth = TrackBirth::unexplained;
      continue;
    }

    // The held tracks this line may belong to: silent since before it began. Their sightings in
    // the `lag` windows before it straddle the event (a release's window reads the line a few
    // % off, and the linker or an earlier birth may have given it to the held track): they are
    // left out of the comparison, and dropped when it is absorbed. Within the gate: the same
    // line (its wear since moves it by at most half w_max per ms); within a step's reach: a
    // step of it, when the ringing fits the jump.
    std::optional<std::size_t> same, stepped, just_silent;
    double same_d = 0.0, step_d = 0.0, silent_d = 0.0;
    for (std::size_t h = 0; h < tracks.size(); ++h) {
      const Track& held = tracks[h];
      if (h == b || held.sightings.empty() || held.released || held.sightings.size() < link.min_sightings ||
          held.sightings.back().window >= first_window)
        continue;
      const std::size_t before = clear_of(held, first_window, lag);
      if (before == 0) continue;
      const auto straddling = held.sightings.begin() + static_cast<std::ptrdiff_t>(before);
      // Its last clear line (z >= reacquire_snr): a fading ringing's last lines have wide errors,
      // which would open the gate to a neighbour's line.
      const auto clear = std::find_if(std::make_reverse_iterator(straddling), held.sightings.rend(),
                                      [&](const TrackSighting& x) { return x.line.snr >= link.reacquire_snr; });
      const TrackSighting& last_seen = held.sightings[before - 1];
      const WindowLine& last = clear == held.sightings.rend() ? last_seen.line : clear->line;
      const double elapsed = static_cast<double>(first_window - last_seen.window);
      const double drift = link.drift_per_window * elapsed;
      const double d = std::abs(f - last.frequency_hz) / last.frequency_hz;
      const double gate = link.gate_z * std::hypot(last.frequency_se_hz, born_se_hz) / last.frequency_hz;
      if (d <= gate + drift) {
        if (!same || d < same_d) same = h, same_d = d;
        continue;
      }
      if (d > link.step_fraction + drift) continue;
      // Heard until less than `lag` windows before a release-loud line within a step's reach:
      // its release read off-line by the windows that straddle it (never an asperity unheard).
      if (before < held.sightings.size() && (!just_silent || d < silent_d)) just_silent = h, silent_d = d;
      if (release_like) continue;
      // The stiffness before the step: the last heard, lowered since by at most w_max per ms.
      const double k_last = last.stiffness_n_per_m;
      const double dt_s = windows[first_window].start_s - windows[last_seen.window].start_s;
      const double k_worn = k_last * std::max(0.0, 1.0 - max_wear_per_ms * dt_s / 1e-3);
      const double ring_a = step_ringing_v(device, k_last, k), ring_b = step_ringing_v(device, k_worn, k);
      const bool straddles = (k_worn - k) * (k_last - k) <= 0.0;  // the step's size may be ~0
      const double low = straddles ? 0.0 : std::min(ring_a, ring_b), high = std::max(ring_a, ring_b);
      if (a >= low / RINGING_TOLERANCE && a <= high * RINGING_TOLERANCE && (!stepped || d < step_d)) stepped = h, step_d = d;
    }
    if (release_like && !same) same = just_silent;

    if (release_like) {
      if (same) {
        Track& held = tracks[*same];
        drop_from(held, clear_of(held, first_window, lag));
        release_at(held, absorb(held, born));
      } else {
        // The release of an asperity in contact since before the record, never heard so far.
        born.birth = TrackBirth::before_record;
        release_at(born, 0);
      }
    } else if (same) {
      absorb(tracks[*same], born);
    } else if (stepped) {
      Track& held = tracks[*stepped];
      drop_from(held, clear_of(held, first_window, lag));
      held.step_sightings.push_back(absorb(held, born));
    } else if (within(a * std::exp(gamma * (birth_s - record_start_s)), onset_ringing_v(device, k))) {
      born.birth = TrackBirth::before_record;  // its onset's ringing at the record's start, heard late
    } else {
      born.birth = TrackBirth::unexplained;
    }
  }
  std::erase_if(tracks, [](const Track& t) { return t.sightings.empty(); });
}

}  // namespace stengmc
