#pragma once
//! The wear rate of an excited track (docs/tracking.md, k(t)): the slope of its stiffness over
//! the time it is in contact. Each segment (between events) is cut into pieces of 4 tau, each
//! piece's line centre fitted (line_centre_fit.hpp: independent pieces, each with its Whittle
//! error), and the relative stiffnesses k_i / k_segment fitted by weighted least squares with
//! one level per segment and one common slope rho [1/s] (a step multiplies k; wear lowers it
//! by a share of k0 per ms: docs/model.md §1.4). The slope's error is scaled by the Birge ratio
//! sqrt(chi^2 / dof) when the pieces scatter more than their errors say.
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"
#include "inverse/track_linking.hpp"
#include "inverse/track_segments.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

struct TrackWear {
  std::size_t track = 0;
  //! w = -rho x 1 ms / (k at the track's first sighting over its segment's level): the model's
  //! wear_rate_per_ms when the track starts at the asperity's onset [1/ms].
  double rate_per_ms = 0.0;
  double rate_low = 0.0, rate_high = 0.0;  //!< 90 % interval [1/ms]
  double slope_per_s = 0.0;                //!< rho: relative stiffness change per second [1/s]
  double slope_se_per_s = 0.0;             //!< its standard error [1/s]
  std::size_t pieces = 0;                  //!< pieces fitted
};

//! The wear of `track` from its fitted `segments` (the same track's, in time order); none with
//! fewer than 3 pieces or no segment of two pieces.
std::optional<TrackWear> fit_track_wear(const KnownDevice& device, const Track& track, std::size_t index,
                                        std::span<const TrackSegment> segments, const RecordGrid& grid,
                                        std::span<const double> voltage_v, std::span<const double> neighbours_hz,
                                        const std::vector<TrackWindow>& windows);

}  // namespace stengmc
