#pragma once
//! The output of `stengmc track` (docs/output-files.md, tracking file), file_type
//! "stengmc-tracking". W windows, T tracks, E events, S segments, L lines in all:
//!   root attributes   provenance (the --known study's file and text), record (its path),
//!                     regime ("excited"/"unexcited"), window_s, hop_s, noise_sigma_v,
//!                     band_low_hz, band_high_hz, max_wear_per_ms, max_missed, threshold_snr,
//!                     naive_threshold, seconds
//!   /tracking/        window_time, window_start, window_mean, noise_floor, count, count_low,
//!                     count_high, naive_count (W); track, error_inflation (T);
//!                     stiffness_n_per_m, stiffness_low, stiffness_high, frequency_hz,
//!                     frequency_low, frequency_high (T x W, NaN where absent)
//!   /tracking/events/ kind, time_s, time_low_s, time_high_s, track (E)
//!   /tracking/segments/ track, start_s, end_s, windows, stiffness_n_per_m, stiffness_low,
//!                     stiffness_high, frequency_hz (S)
//!   /tracking/wear/   track, wear_rate_per_ms, wear_rate_low, wear_rate_high, pieces (excited:
//!                     the tracks whose wear was fitted)
//!   /tracking/lines/  window, frequency_hz, frequency_se_hz, amplitude_v, snr, detected (L)
//!   /tracking/record/ time, voltage: the record tracked (the figure's spectrogram)
#include <span>
#include <string>

#include "inverse/tracking.hpp"

namespace stengmc {

struct TrackingFileContext {
  std::string known_file, known_text;  //!< the --known study
  std::string record;                  //!< the record's name (path)
  double max_wear_per_ms = 0.0;
  std::size_t max_missed = 0;
  double threshold_snr = 0.0;
  double naive_threshold = 0.0;
  std::span<const double> times_s;     //!< the record
  std::span<const double> voltage_v;
};

void write_tracking_file(const std::string& path, const TrackingFileContext& context, const TrackingResult& result);

}  // namespace stengmc
