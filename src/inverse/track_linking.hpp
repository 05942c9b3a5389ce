#pragma once
//! Lines linked across windows into tracks (docs/tracking.md, linking): a gated
//! global-nearest-neighbour tracker (Blackman & Popoli, "Design and Analysis of Modern
//! Tracking Systems", Artech House 1999, ch. 6-7) whose per-window assignment is the
//! Hungarian method (Kuhn 1955, Munkres 1957; spectral/assignment.hpp), with birth, death
//! after G missed windows (excited) or held silent tracks (unexcited), and what the physics of
//! the contact adds: unexcited, a silent track re-heard by a free ringing within a stiffness
//! step's reach is one asperity whose stiffness stepped, and re-heard by a burst as strong as
//! its onset's is its release (a released asperity rings from its full deflection mu N / k, as
//! at onset); excited, a track that ends in a free ring-down was released there.
#include <cstddef>
#include <vector>

#include "inverse/track_lines.hpp"

namespace stengmc {

struct LinkSettings {
  //! Gate: |f_line - f_track| <= gate_z * sqrt(se_line^2 + se_track^2 + floor^2) + drift.
  double gate_z = 3.0;
  //! Frequency error floor of the gate [Hz]: 0 on the first pass; excited, the second pass
  //! sets it from how much the first pass's tracks wander (tracking.cpp).
  double gate_floor_hz = 0.0;
  //! Largest relative frequency drift per window of wear: 0.5 w_max hop / 1 ms (f ~ sqrt(k)).
  double drift_per_window = 0.0;
  //! G: a track not seen in more than this many consecutive windows dies (excited regime).
  std::size_t max_missed = 2;
  //! Unexcited regime: a silent track is held (its asperity is in contact but not heard)
  //! until its release is heard, instead of dying after G misses.
  bool hold_silent = false;
  //! Largest relative frequency change of a stiffness step: sqrt(1.15) - 1 ~ 1 - sqrt(0.85) ~ 8 %.
  //! A line appearing within it of a track that lost its line continues that track with a step
  //! (whatever its level: a step can ring as hard as an onset); a new asperity's onset that close
  //! to a silent one is taken for a step of it (docs/tracking.md, limits).
  double step_fraction = 0.08;
  //! A burst whose level (snr) reaches this fraction of the track's onset level is a release.
  double release_level_fraction = 0.5;
  //! A burst on a track: its level over the median of its last levels (or any line after silence).
  double burst_ratio = 3.0;
  //! Tracks seen in fewer windows are dropped as false alarms (a real event rings >= 20 us).
  std::size_t min_sightings = 2;
  //! Least snr of a line that takes up a track after two or more missed windows.
  double reacquire_snr = 10.0;
  //! Excited: least share of the windows a track spans in which it must be heard.
  double min_duty = 0.5;
  //! c / 2m of the device: the damping of a free ringing [1/s].
  double free_damping_per_s = 0.0;
  //! Unexcited (> 0): the loudest a stiffness step can make a line ring at the window's start,
  //! the belt's limit R sigma w v_b (inverse/event_ringing.hpp) times the amplitude tolerance
  //! (inverse/track_births.hpp) [V]. A louder line within a step's reach of a held track is no
  //! step of it (a release rings 2-12 x louder than the limit in the validation's prior).
  double max_step_ringing_v = 0.0;
  //! Excited (> 0): windows that share samples with one (lag). Tracks that take turns on one
  //! line, or meet within step_fraction of each other (a step moves a driven line out of the
  //! gate at once), are merged, their lines compared over this many windows where they meet.
  std::size_t step_overlap_windows = 0;
  //! > 0 (excited): the gate is centred on the median of the track's last this many lines
  //! instead of its last line: a short window's peak of a random narrow-band line scatters by
  //! ~1/T about the line's centre, and one stray sighting would drag a last-line gate with it.
  std::size_t reference_sightings = 0;
};

struct TrackSighting {
  std::size_t window = 0;
  WindowLine line;
};

//! A stiffness step of a track: the first sighting of the new stiffness and when it happened.
struct StepMark {
  std::size_t sighting = 0;
  double time_s = 0.0, low_s = 0.0, high_s = 0.0;  //!< estimate and interval [s]
};

//! Unexcited: what a track's first line is, judged by how strongly it rings
//! (inverse/track_births.hpp). An onset starts the track; an asperity in contact from before
//! the record (a ringing since its start first resolved now, or the release of an asperity
//! never heard) is in contact from the record's start; a line no event explains is counted
//! only while it is heard (it is not held).
enum class TrackBirth { onset, before_record, unexplained };

struct Track {
  std::vector<TrackSighting> sightings;   //!< in window order
  std::vector<std::size_t> step_sightings;  //!< sightings that start a new stiffness (a step before them)
  std::vector<StepMark> steps;            //!< the steps timed (inverse/track_steps.hpp), by sighting
  std::size_t release_sighting = 0;       //!< sighting where the release burst starts (when released)
  bool released = false;                  //!< its release was heard (burst)
  bool ended = false;                     //!< died (missed > G) before the record's end
  double onset_level = 0.0;               //!< largest snr of its first three sightings
  TrackBirth birth = TrackBirth::onset;   //!< unexcited: what its first line is (track_births.hpp)
};

//! Excited regime: a track whose last sightings (at least three) are all a free ringing
//! (damping within [0.6, 1.6] x c/2m, from the periodogram peak's two window halves; in
//! contact the random line's damping scatters by ~1e5 /s either way) whose level falls is released: the release is the first
//! of them (the counterface no longer drives the asperity, so it rings down from where it
//! was let go). Sets released and release_sighting.
void find_free_ringdown(Track& track, double free_damping_per_s);

//! Tracks of the detected lines of each window (grey candidates are not linked).
std::vector<Track> link_tracks(const std::vector<WindowLines>& windows, const LinkSettings& settings);

}  // namespace stengmc
