#pragma once
//! Events read off the tracks (docs/tracking.md, events): an onset where a track is born
//! ringing, a stiffness step where a track's line jumped, a release where its release burst
//! starts (or, when none was heard, between the window it was last seen in and the first it
//! was missed in). Each with a time and the interval the windows allow.
#include <cstddef>
#include <string_view>
#include <vector>

#include "inverse/track_linking.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

enum class TrackEventKind { onset, release, step };

std::string_view track_event_name(TrackEventKind kind);

struct TrackEvent {
  TrackEventKind kind = TrackEventKind::onset;
  double time_s = 0.0;       //!< estimate [s]
  double time_low_s = 0.0;   //!< the window boundaries it lies between [s]
  double time_high_s = 0.0;
  std::size_t track = 0;     //!< index of the track
};

//! The events of `tracks`, sorted by time. A track seen from the first window has its onset
//! at or before the record's start: that onset is reported with time_low_s = the record's start.
std::vector<TrackEvent> track_events(const std::vector<Track>& tracks, const std::vector<TrackWindow>& windows, bool excited);

//! The time an asperity starts ringing that is first heard in window `first` (burst: an onset
//! or a release) [s]: between the end of the window before, less 0.3 of a window (a strong
//! burst is heard from a 30 % share), and the end of `first`.
TrackEvent burst_event(TrackEventKind kind, std::size_t first, const std::vector<TrackWindow>& windows, std::size_t track);

}  // namespace stengmc
