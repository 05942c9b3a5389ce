#pragma once
//! The windows `stengmc track` cuts a long record into (docs/tracking.md, windows): each
//! short enough that a line's stiffness and count are constant across it, long enough to
//! resolve the device's lines.
#include <cstddef>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! Window length and hop in samples.
struct TrackWindowing {
  std::size_t length = 0;  //!< samples per window
  std::size_t hop = 0;     //!< samples between window starts
};

//! One window: its first sample and centre time.
struct TrackWindow {
  std::size_t start = 0;   //!< index of its first sample in the record
  double start_s = 0.0;    //!< time of that sample [s]
  double end_s = 0.0;      //!< time of its last sample [s]
  double centre_s = 0.0;   //!< time of its centre [s]
};

//! The device's windows. Unexcited (lines are free ringings): length m/c = tau/2 (10 us with
//! Table 1 values: a ringing decays by e^-1/2 across it, so a damped line is still one line),
//! hop half of it. Excited (lines are random narrow-band processes of width c/(2 pi m)): length
//! 2 tau = 4m/c (40 us), two coherence times, so a window's periodogram peak is the line's and
//! not one of its random bumps, and a fade (tens of us) seldom empties a whole window; hop
//! tau/4, the same 5 us as unexcited. A value given in seconds
//! (> 0) wins. @throws InputError when a window would be shorter than
//! 64 samples or longer than the record, or the hop is 0 or longer than the window.
TrackWindowing track_windowing(const KnownDevice& device, const RecordGrid& grid, double window_s = 0.0,
                               double hop_s = 0.0);

//! Every whole window of `grid` (the last samples, fewer than a hop, are not analysed alone).
std::vector<TrackWindow> track_windows(const RecordGrid& grid, const TrackWindowing& windowing);

}  // namespace stengmc
