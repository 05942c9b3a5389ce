#include "inverse/track_events.hpp"

#include <algorithm>

namespace stengmc {

std::string_view track_event_name(TrackEventKind kind) {
  switch (kind) {
    case TrackEventKind::onset: return "onset";
    case TrackEventKind::release: return "release";
    case TrackEventKind::step: return "step";
  }
  return "onset";
}

TrackEvent burst_event(TrackEventKind kind, std::size_t first, const std::vector<TrackWindow>& windows, std::size_t track) {
  const TrackWindow& w = windows[first];
  const double length = w.end_s - w.start_s;
  TrackEvent e{kind, 0.0, windows.front().start_s, w.end_s, track};
  if (first > 0) e.time_low_s = std::max(windows.front().start_s, windows[first - 1].end_s - 0.3 * length);
  e.time_s = 0.5 * (e.time_low_s + e.time_high_s);
  return e;
}

std::vector<TrackEvent> track_events(const std::vector<Track>& tracks, const std::vector<TrackWindow>& windows, bool excited) {
  std::vector<TrackEvent> events;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const Track& track = tracks[t];
    // (Unexcited: an asperity in contact from before the record has its onset at its start; a
    // line no event explains has none: inverse/track_births.hpp.)
    if (track.birth == TrackBirth::before_record) events.push_back(burst_event(TrackEventKind::onset, 0, windows, t));
    else if (track.birth == TrackBirth::onset) events.push_back(burst_event(TrackEventKind::onset, track.sightings.front().window, windows, t));
    for (const StepMark& m : track.steps) events.push_back({TrackEventKind::step, m.time_s, m.low_s, m.high_s, t});
    if (track.released && excited) {
      // Its free ring-down: the first window after the release is the first of it, or one
      // whose start is still driven for a share of it that the halves' damping does not see
      // (up to 0.3 of the window, as an onset's share; 0.12 seen on a 40 us window).
      const std::size_t b = track.sightings[track.release_sighting].window;
      const double length = windows[b].end_s - windows[b].start_s;
      TrackEvent e{TrackEventKind::release, 0.0, windows[b > 0 ? b - 1 : 0].start_s, windows[b].start_s + 0.3 * length, t};
      e.time_s = 0.5 * (e.time_low_s + e.time_high_s);
      events.push_back(e);
    } else if (track.released) {
      events.push_back(burst_event(TrackEventKind::release, track.sightings[track.release_sighting].window, windows, t));
    } else if (track.ended && excited) {
      // No burst heard: the line stopped between the last window it was seen in and the next.
      const std::size_t a = track.sightings.back().window;
      const std::size_t next = std::min(a + 1, windows.size() - 1);
      TrackEvent e{TrackEventKind::release, 0.0, windows[a].centre_s, windows[next].end_s, t};
      e.time_s = 0.5 * (e.time_low_s + e.time_high_s);
      events.push_back(e);
    }
  }
  std::sort(events.begin(), events.end(), [](const TrackEvent& a, const TrackEvent& b) { return a.time_s < b.time_s; });
  return events;
}

}  // namespace stengmc
