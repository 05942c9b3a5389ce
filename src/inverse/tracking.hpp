#pragma once
//! `stengmc track`: a long record of a known device followed window by window (docs/tracking.md):
//! lines detected per window, linked into tracks, events read off them, the count n(t) and
//! each track's stiffness k(t) with 90 % intervals.
#include <cstddef>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"
#include "inverse/track_events.hpp"
#include "inverse/track_linking.hpp"
#include "inverse/track_segments.hpp"
#include "inverse/track_wear.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

class Progress;

struct TrackingSettings {
  double window_s = 0.0;           //!< window length [s]; 0: the device's (track_windowing)
  double hop_s = 0.0;              //!< hop [s]; 0: half the window
  double max_wear_per_ms = 0.30;   //!< the prior's largest wear rate w_max [1/ms]: gates and held intervals
  std::size_t max_missed = 2;      //!< G (excited: at least two window overlaps are allowed)
  double threshold_snr = 5.0;      //!< detection threshold (LineDetectorSettings::threshold_snr)
  //! Prominence over the local floor of the naive per-window FFT count (the `spectrum`
  //! peak search's, at half its default of 10: the windows are short).
  double naive_threshold = 5.0;
  int threads = 1;
};

struct TrackingResult {
  TrackWindowing windowing;
  std::vector<TrackWindow> windows;
  double noise_sigma_v = 0.0;               //!< white noise estimated above the band [V]
  double band_low_hz = 0.0, band_high_hz = 0.0;
  bool excited = false;                     //!< the device's counterface keeps lines alive
  std::vector<double> window_mean_v;        //!< per window
  std::vector<double> count, count_low, count_high, naive_count;  //!< per window
  //! [track][window], NaN where the track's asperity is not in contact.
  std::vector<std::vector<double>> stiffness, stiffness_low, stiffness_high;
  //! [track][window], NaN where the track's line was not heard (or after its release).
  std::vector<std::vector<double>> frequency, frequency_low, frequency_high;
  //! Unexcited: asperities in contact at the record's start, from its plateau (0: not read;
  //! inverse/start_plateau.hpp). Those no track accounts for are in the count throughout.
  std::size_t asperities_at_start = 0;
  //! The plateau over R sigma w v_b before rounding (NaN: not read); more than
  //! PLATEAU_CERTAIN_OFFSET from asperities_at_start widens the count's band by one.
  double start_level = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> error_inflation;      //!< per track: the factor its frequency errors were scaled by
  std::vector<WindowLines> window_lines;    //!< every window's lines, detected and grey
  std::vector<Track> tracks;
  std::vector<TrackEvent> events;
  std::vector<TrackSegment> segments;
  std::vector<TrackWear> wear;              //!< excited: each track's fitted wear (tracks with enough pieces)
  double seconds = 0.0;                     //!< computing time
};

//! Tracks `voltage_v` on `grid` of `device`, whose lines lie in `band_hz`.
//! @throws InputError when the record leaves no band above the lines to measure its noise.
TrackingResult track_record(const KnownDevice& device, std::pair<double, double> band_hz, const RecordGrid& grid,
                            std::span<const double> voltage_v, const TrackingSettings& settings, Progress* progress = nullptr);

//! 5 % and 95 % quantiles of a sum of independent Bernoulli(p_i) (Poisson-binomial), exact by
//! convolution.
std::pair<std::size_t, std::size_t> poisson_binomial_interval(std::span<const double> p);

}  // namespace stengmc
