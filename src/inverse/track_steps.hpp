#pragma once
//! Stiffness steps of a track (docs/tracking.md, events): those the linker made (a line gone and
//! a new one within a step's reach) timed from their windows, and those inside a track, where
//! its frequency moves from one level to another by more than its scatter allows.
#include <cstddef>
#include <vector>

#include "inverse/track_linking.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

//! Times the linker's steps and finds the track's other steps. A step inside a track: the
//! boundary i where |mean(f[i, i+M)) - mean(f[i-M, i))| over its standard error
//! sigma sqrt(2 lag / M) is a local maximum above `threshold` (a two-sample change-point test,
//! e.g. Basseville & Nikiforov, "Detection of Abrupt Changes", 1993, sec. 2.2); sigma is the
//! robust scatter (MAD) of the frequency between windows `lag` apart (windows that share no
//! sample), lag/M the correlation of overlapping windows' estimates; M = 2 lag (at least 3).
//! Its time is where the windows' estimates cross from one level to the other, +- half a window.
void find_steps(Track& track, const std::vector<TrackWindow>& windows, std::size_t lag, bool excited, double threshold = 6.0);

}  // namespace stengmc
