#include "inverse/track_windows.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"

namespace stengmc {

namespace {
//! Fewest samples per window: ESPRIT's Hankel matrix needs ~3x the lines it looks for.
constexpr std::size_t MIN_WINDOW_SAMPLES = 64;
}  // namespace

TrackWindowing track_windowing(const KnownDevice& device, const RecordGrid& grid, double window_s, double hop_s) {
  // tau = 2m/c is the free ringing's envelope time; half of it keeps a decaying line close to
  // a line of constant amplitude inside the window, and 1/(tau/2) = 100 kHz separates lines
  // ~5 % apart at 2 MHz once ESPRIT's super-resolution is counted.
  const double half_tau = device.asperity.mass_kg / device.model.damping_n_s_per_m;
  const bool excited = device.model.counterface.friction_modulation_rms > 0.0;
  if (window_s <= 0.0) window_s = excited ? 4.0 * half_tau : half_tau;
  if (hop_s <= 0.0) hop_s = std::min(0.5 * half_tau, window_s);
  TrackWindowing w;
  w.length = static_cast<std::size_t>(std::llround(window_s / grid.step_s));
  w.hop = static_cast<std::size_t>(std::llround(hop_s / grid.step_s));
  if (w.length < MIN_WINDOW_SAMPLES)
    throw InputError("--window-s = " + format_number(window_s) + " s is " + std::to_string(w.length) +
                     " samples at this record's rate; a window needs at least " + std::to_string(MIN_WINDOW_SAMPLES));
  if (w.length > grid.samples)
    throw InputError("--window-s = " + format_number(window_s) + " s is longer than the record (" +
                     format_number(grid.duration_s()) + " s)");
  if (w.hop == 0 || w.hop > w.length)
    throw InputError("--hop-s = " + format_number(hop_s) + " s must be at least one sample and at most the window (" +
                     format_number(window_s) + " s)");
  return w;
}

std::vector<TrackWindow> track_windows(const RecordGrid& grid, const TrackWindowing& windowing) {
  std::vector<TrackWindow> windows;
  for (std::size_t start = 0; start + windowing.length <= grid.samples; start += windowing.hop) {
    const double first = grid.at(start), last = grid.at(start + windowing.length - 1);
    windows.push_back({start, first, last, 0.5 * (first + last)});
  }
  return windows;
}

}  // namespace stengmc
