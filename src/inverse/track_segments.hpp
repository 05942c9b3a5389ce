#pragma once
//! A track's stiffness between two of its events (docs/tracking.md, k(t)): its segments.
//! Unexcited, the inverse-variance mean of the windows' ringing lines (in tracking.cpp);
//! excited, the centre of the driven line fitted over the segment's whole span
//! (fit_driven_segments).
#include <cstddef>
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"
#include "inverse/track_linking.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

struct TrackSegment {
  std::size_t track = 0;
  double start_s = 0.0, end_s = 0.0;  //!< the span it covers [s] (unexcited: first and last window centre)
  std::size_t windows = 0;            //!< windows whose lines it holds
  double frequency_hz = 0.0;
  double frequency_se_hz = 0.0;       //!< standard error of frequency_hz [Hz]
  double stiffness_n_per_m = 0.0;
  double stiffness_low = 0.0;         //!< 90 % interval [N/m]
  double stiffness_high = 0.0;
};

//! Excited: each segment of `track` (between its onset, steps and release) fitted as one
//! stationary Lorentzian line (line_centre_fit.hpp) over the samples from the first sighting's
//! window centre to the last's (the windows that straddle a step, [low_s, high_s] of its mark,
//! left out), in a band of 12 half-widths (c / 4 pi m) beyond the segment's window lines, any
//! other track's line heard at the same time (`neighbours_hz`) in it fitted with this one. Its 90 % interval is the centre +- 1.645 x the Whittle curvature's error.
//! The error is scaled by the Birge ratio of the segment's windows about the centre (at least
//! 1: a track that mixes lines or drifts is less sure than a stationary line's bound).
//! A segment shorter than 4 tau = 8 m / c is not fitted (too few ordinates).
std::vector<TrackSegment> fit_driven_segments(const KnownDevice& device, const Track& track, std::size_t index,
                                              const std::vector<TrackWindow>& windows, const RecordGrid& grid,
                                              std::span<const double> voltage_v, std::span<const double> neighbours_hz);

//! The segments' spans of `track` [s]: from the first sighting's window centre (or a step's
//! high_s) to the last heard sighting's window centre (or a step's low_s, or its release
//! sighting's window start), with the sightings each holds.
struct SegmentSpan {
  double start_s = 0.0, end_s = 0.0;
  std::size_t first = 0, last = 0;  //!< sightings [first, last)
};
std::vector<SegmentSpan> segment_spans(const Track& track, const std::vector<TrackWindow>& windows);

}  // namespace stengmc
