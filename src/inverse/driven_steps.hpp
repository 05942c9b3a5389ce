#pragma once
//! Stiffness steps of an excited track (docs/tracking.md, events): the driven line's centre
//! jumps. Found by binary segmentation of the track's span with the Whittle likelihood of one
//! stationary Lorentzian line per piece (line_centre_fit.hpp; piecewise-stationary segmentation
//! by likelihood as in Davis, Lee & Rodriguez-Yam, J. Am. Stat. Assoc. 101 (2006)): the split
//! that maximises the likelihood of two lines over one, kept when the line jumps there by at
//! least `z_threshold` of the jump's standard error (a Wald test on pieces of 4 tau either side,
//! fitted with a level each and a common slope: wear drifts the line, and a drift is no step),
//! each side at least 4 tau long.
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"
#include "inverse/track_linking.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

//! Sets `track.steps` (replacing any): each step's time is the best split, its interval the
//! splits whose log-likelihood lies within 1.35 (half the chi-square(1) 90 % point) of the
//! best, widened to at least +- one hop; `sighting` the first sighting after it.
//! `neighbours_hz`: other tracks' lines heard at the same time (fitted with the line where in its band).
void find_driven_steps(const KnownDevice& device, Track& track, const std::vector<TrackWindow>& windows, const RecordGrid& grid,
                       std::span<const double> voltage_v, std::span<const double> neighbours_hz, double z_threshold = 5.0);

}  // namespace stengmc
