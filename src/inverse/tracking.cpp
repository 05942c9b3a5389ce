#include "inverse/tracking.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/progress.hpp"
#include "core/standard_normal.hpp"
#include "inverse/driven_steps.hpp"
#include "inverse/naive_count.hpp"
#include "inverse/noise_level.hpp"
#include "inverse/start_plateau.hpp"
#include "inverse/track_births.hpp"
#include "inverse/track_lines.hpp"
#include "inverse/track_peaks.hpp"
#include "inverse/track_steps.hpp"
#include "inverse/track_wear.hpp"

namespace stengmc {

namespace {

constexpr double NOT_HERE = std::numeric_limits<double>::quiet_NaN();
//! Median of a chi-square variable of one degree of freedom.
constexpr double CHI2_1_MEDIAN = 0.45493642311957;

//! The scatter of a track's frequencies between windows that do not overlap, over what their
//! Cramer-Rao errors predict: an excited line is a random narrow-band process, not the
//! deterministic damped line the bound assumes, and wanders more. The factor (>= 1) is
//! sqrt(median(df^2 / (se_a^2 + se_b^2)) / median of chi2_1), over pairs within one stiffness
//! (no step between them); 1 with fewer than 3 pairs.
double error_inflation(const Track& track, std::size_t lag) {
  std::vector<double> ratios;
  std::size_t segment_start = 0;
  std::vector<std::size_t> boundaries = track.step_sightings;
  if (track.released) boundaries.push_back(track.release_sighting);
  std::sort(boundaries.begin(), boundaries.end());
  boundaries.push_back(track.sightings.size());
  for (std::size_t end : boundaries) {
    for (std::size_t i = segment_start; i < end; ++i)
      for (std::size_t j = i + 1; j < end; ++j) {
        const std::size_t gap = track.sightings[j].window - track.sightings[i].window;
        if (gap < lag) continue;
        if (gap == lag || j == i + 1) {
          const WindowLine& a = track.sightings[i].line;
          const WindowLine& b = track.sightings[j].line;
          const double df = a.frequency_hz - b.frequency_hz;
          ratios.push_back(df * df / (a.frequency_se_hz * a.frequency_se_hz + b.frequency_se_hz * b.frequency_se_hz));
        }
        break;
      }
    segment_start = end;
  }
  if (ratios.size() < 3) return 1.0;
  auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), middle, ratios.end());
  return std::max(1.0, std::sqrt(*middle / CHI2_1_MEDIAN));
}

//! Pooled robust standard deviation of a line's frequency between windows `lag` apart, over
//! every track: 1.4826 MAD / sqrt(2) of their differences [Hz] (0 with fewer than 8).
double frequency_wander(const std::vector<Track>& tracks, std::size_t lag) {
  std::vector<double> d;
  for (const Track& t : tracks)
    if (t.sightings.size() >= 4 * lag)  // long tracks only: short ones are often noise linked by chance
    for (std::size_t i = 0; i + lag < t.sightings.size(); ++i)
      if (t.sightings[i + lag].window - t.sightings[i].window == lag)
        d.push_back(std::abs(t.sightings[i + lag].line.frequency_hz - t.sightings[i].line.frequency_hz));
  if (d.size() < 8) return 0.0;
  auto middle = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), middle, d.end());
  return 1.4826 * *middle / std::numbers::sqrt2;
}

void set_interval(const KnownDevice& device, WindowLine& line, double inflation) {
  line.frequency_se_hz *= inflation;
  line.stiffness_low = stiffness_at(device, std::max(0.0, line.frequency_hz - Z90 * line.frequency_se_hz));
  line.stiffness_high = stiffness_at(device, line.frequency_hz + Z90 * line.frequency_se_hz);
}

//! Windows and lines, in parallel (each window on its own; the naive counter owns an FFT plan).
template <class Detector>
std::vector<WindowLines> detect_all(const Detector& detector, const RecordGrid& grid, std::span<const double> v,
                                    const std::vector<TrackWindow>& windows, const TrackingSettings& settings,
                                    std::size_t length, std::vector<double>& naive, Progress* progress) {
  std::vector<WindowLines> lines(windows.size());
  naive.assign(windows.size(), 0.0);
  std::mutex mutex;
  std::exception_ptr failure;
  const auto count = static_cast<std::int64_t>(windows.size());
  const double thresholds[] = {settings.naive_threshold};
#pragma omp parallel num_threads(std::max(1, settings.threads))
  {
    NaiveCounter counter(length, grid.sample_rate_hz(), detector.settings().band_low_hz, detector.settings().band_high_hz);
#pragma omp for schedule(dynamic, 4)
    for (std::int64_t i = 0; i < count; ++i) {
      try {
        const auto w = static_cast<std::size_t>(i);
        const std::span<const double> segment = v.subspan(windows[w].start, length);
        lines[w] = detector.detect(segment);
        naive[w] = counter.count(segment, thresholds).front();
        if (progress) {
          std::lock_guard lock(mutex);
          progress->advance();
        }
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  return lines;
}

//! Stiffness of each track between its events: the inverse-variance mean of its windows'
//! frequencies, the windows beside a step left out. Overlapping windows share samples, so the
//! mean's error is scaled by sqrt(length / hop).
void add_segments(const KnownDevice& device, const Track& track, std::size_t t, const std::vector<TrackWindow>& windows,
                  double overlap, std::vector<TrackSegment>& segments) {
  const std::size_t last = track.released ? track.release_sighting : track.sightings.size();
  std::vector<std::size_t> boundaries;
  for (const StepMark& m : track.steps) boundaries.push_back(m.sighting);
  boundaries.push_back(last);
  auto straddles = [&](const TrackWindow& w) {
    return std::any_of(track.steps.begin(), track.steps.end(),
                       [&](const StepMark& m) { return w.end_s > m.low_s && w.start_s < m.high_s; });
  };
  std::size_t start = 0;
  for (std::size_t end : boundaries) {
    double sum_w = 0.0, sum_wf = 0.0;
    std::size_t used = 0;
    for (std::size_t i = start; i < end; ++i) {
      if (straddles(windows[track.sightings[i].window])) continue;
      const WindowLine& l = track.sightings[i].line;
      const double w = 1.0 / (l.frequency_se_hz * l.frequency_se_hz);
      sum_w += w;
      sum_wf += w * l.frequency_hz;
      ++used;
    }
    if (used > 0) {
      TrackSegment s;
      s.track = t;
      s.start_s = windows[track.sightings[start].window].centre_s;
      s.end_s = windows[track.sightings[end - 1].window].centre_s;
      s.windows = used;
      s.frequency_hz = sum_wf / sum_w;
      const double se = std::sqrt(overlap / sum_w);
      s.frequency_se_hz = se;
      s.stiffness_n_per_m = stiffness_at(device, s.frequency_hz);
      s.stiffness_low = stiffness_at(device, std::max(0.0, s.frequency_hz - Z90 * se));
      s.stiffness_high = stiffness_at(device, s.frequency_hz + Z90 * se);
      segments.push_back(s);
    }
    start = end;
    if (start >= last) break;
  }
}

//! The median line of every other track heard at the same time as track `t` [Hz]: a segment's
//! fit band stops half-way to them.
std::vector<double> concurrent_lines(const std::vector<Track>& tracks, std::size_t t) {
  std::vector<double> lines;
  const std::size_t first = tracks[t].sightings.front().window, last = tracks[t].sightings.back().window;
  for (std::size_t o = 0; o < tracks.size(); ++o) {
    if (o == t || tracks[o].sightings.back().window < first || tracks[o].sightings.front().window > last) continue;
    std::vector<double> f;
    for (const TrackSighting& s : tracks[o].sightings) f.push_back(s.line.frequency_hz);
    std::nth_element(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(f.size() / 2), f.end());
    lines.push_back(f[f.size() / 2]);
  }
  return lines;
}

}  // namespace

std::pair<std::size_t, std::size_t> poisson_binomial_interval(std::span<const double> p) {
  std::vector<double> pmf{1.0};
  for (double q : p) {
    std::vector<double> next(pmf.size() + 1, 0.0);
    for (std::size_t k = 0; k < pmf.size(); ++k) {
      next[k] += pmf[k] * (1.0 - q);
      next[k + 1] += pmf[k] * q;
    }
    pmf = std::move(next);
  }
  std::size_t low = 0, high = pmf.size() - 1;
  double cdf = 0.0;
  bool low_set = false;
  for (std::size_t k = 0; k < pmf.size(); ++k) {
    cdf += pmf[k];
    if (!low_set && cdf >= 0.05) low = k, low_set = true;
    if (cdf >= 0.95) {
      high = k;
      break;
    }
  }
  return {low, high};
}

TrackingResult track_record(const KnownDevice& device, std::pair<double, double> band_hz, const RecordGrid& grid,
                            std::span<const double> v, const TrackingSettings& settings, Progress* progress) {
  const auto started = std::chrono::steady_clock::now();
  TrackingResult r;
  r.windowing = track_windowing(device, grid, settings.window_s, settings.hop_s);
  r.windows = track_windows(grid, r.windowing);
  r.band_low_hz = band_hz.first;
  r.band_high_hz = band_hz.second;
  r.excited = device.model.counterface.friction_modulation_rms > 0.0;
  const double fs = grid.sample_rate_hz();

  // Noise from the whole record above the highest plausible line (inverse/noise_level.hpp).
  NoiseEstimator noise(grid.samples, fs, 1.25 * band_hz.second);
  const NoiseLevel level = noise.estimate(v);
  if (level.bins == 0 || !(level.sigma_v > 0.0))
    throw InputError("the record's sample rate (" + format_number(fs) + " Hz) leaves too little spectrum above 1.25 x the " +
                     "device's highest plausible line (" + format_number(band_hz.second) + " Hz) to measure its noise");
  r.noise_sigma_v = level.sigma_v;

  LineDetectorSettings detection;
  detection.band_low_hz = band_hz.first;
  detection.band_high_hz = band_hz.second;
  detection.noise_sigma_v = level.sigma_v;
  detection.sample_rate_hz = fs;
  detection.threshold_snr = settings.threshold_snr;
  const double window_length_s = static_cast<double>(r.windowing.length) * grid.step_s;
  detection.cluster_hz = r.excited ? 2.0 / window_length_s : 0.0;
  detection.dynamic_range = 0.0;  // (excited: the peaks' tail rule replaces it, track_peaks.cpp)
  // Unexcited, lines are free ringings: ESPRIT's damped sinusoids. Excited, they are random
  // narrow-band processes: periodogram peaks (inverse/track_peaks.hpp).
  const std::vector<WindowLines> lines =
      r.excited ? detect_all(PeakLineDetector(device, detection), grid, v, r.windows, settings, r.windowing.length, r.naive_count, progress)
                : detect_all(LineDetector(device, detection), grid, v, r.windows, settings, r.windowing.length, r.naive_count, progress);
  for (const WindowLines& w : lines) r.window_mean_v.push_back(w.mean_v);

  const double hop_s = static_cast<double>(r.windowing.hop) * grid.step_s;
  const std::size_t lag = (r.windowing.length + r.windowing.hop - 1) / r.windowing.hop;
  LinkSettings link;
  // (Excited, each window's peak error already holds the line's random wander: track_peaks.hpp.)
  link.gate_floor_hz = 0.0;
  link.drift_per_window = 0.5 * settings.max_wear_per_ms * hop_s / 1e-3;
  // Excited, a driven line fades for tens of us at a time (its envelope is random): a track
  // outlives two window lengths unheard (80 us: a fade of a 40 us window of the line is rare).
  // Its release is timed by its ring-down, not by this.
  link.max_missed = r.excited ? std::max(settings.max_missed, 2 * lag) : settings.max_missed;
  link.reference_sightings = r.excited ? lag : 0;
  link.hold_silent = !r.excited;
  // A track must outlast a window: overlapping windows share samples, so one random feature
  // (the off-resonance response an excited asperity adds, which ESPRIT also fits; a noise
  // excursion) shows in `lag` consecutive windows. A real event rings for 20 us and more.
  link.min_sightings = lag + 2;
  link.free_damping_per_s = device.damping_rate_per_s();
  link.step_overlap_windows = r.excited ? lag : 0;
  // Unexcited, the loudest a step rings is the belt's limit (inverse/event_ringing.hpp): a
  // louder line near a held track is no step of it.
  if (!r.excited) link.max_step_ringing_v = RINGING_TOLERANCE * std::abs(device.voltage_scale_v());
  r.tracks = link_tracks(lines, link);
  // Unexcited, each release burst and each new track's first line is judged by how strongly it
  // rings: an onset, a release, a held track re-heard or stepped, or an asperity there before
  // the record (inverse/track_births.hpp).
  if (!r.excited) {
    confirm_releases(device, r.tracks, r.windows, lag);
    classify_track_births(device, r.tracks, r.windows, link, settings.max_wear_per_ms, settings.threshold_snr, lag);
  }
  if (r.excited) {
    // An excited line wanders between windows by more than its Cramer-Rao error (and, near
    // stick, more than its Lorentzian width): the gate is set from how much the first pass's
    // tracks wander, and the lines linked again.
    const double wander = frequency_wander(r.tracks, lag);
    if (wander > link.gate_floor_hz / std::numbers::sqrt2) {
      link.gate_floor_hz = std::numbers::sqrt2 * wander;
      r.tracks = link_tracks(lines, link);
    }
  }

  for (Track& track : r.tracks) {
    const double inflation = error_inflation(track, lag);
    r.error_inflation.push_back(inflation);
    for (TrackSighting& s : track.sightings) set_interval(device, s.line, inflation);
  }
  // Tracks in parallel: each search and fit reads the record and its own track only.
  std::vector<std::vector<double>> neighbours;
  for (std::size_t t = 0; t < r.tracks.size(); ++t) neighbours.push_back(concurrent_lines(r.tracks, t));
  const auto track_count = static_cast<std::int64_t>(r.tracks.size());
#pragma omp parallel for num_threads(std::max(1, settings.threads)) schedule(dynamic, 1)
  for (std::int64_t i = 0; i < track_count; ++i) {
    const auto t = static_cast<std::size_t>(i);
    if (r.excited) find_driven_steps(device, r.tracks[t], r.windows, grid, v, neighbours[t]);
    else find_steps(r.tracks[t], r.windows, lag, r.excited);
  }
  r.events = track_events(r.tracks, r.windows, r.excited);
  const double overlap = static_cast<double>(r.windowing.length) / static_cast<double>(r.windowing.hop);
  if (r.excited) {
    std::vector<std::vector<TrackSegment>> fitted(r.tracks.size());
    std::vector<std::optional<TrackWear>> wear(r.tracks.size());
#pragma omp parallel for num_threads(std::max(1, settings.threads)) schedule(dynamic, 1)
    for (std::int64_t i = 0; i < track_count; ++i) {
      const auto t = static_cast<std::size_t>(i);
      fitted[t] = fit_driven_segments(device, r.tracks[t], t, r.windows, grid, v, neighbours[t]);
      wear[t] = fit_track_wear(device, r.tracks[t], t, fitted[t], grid, v, neighbours[t], r.windows);
    }
    for (const std::vector<TrackSegment>& f : fitted) r.segments.insert(r.segments.end(), f.begin(), f.end());
    for (const std::optional<TrackWear>& w : wear)
      if (w) r.wear.push_back(*w);
  } else {
    for (std::size_t t = 0; t < r.tracks.size(); ++t) add_segments(device, r.tracks[t], t, r.windows, std::max(1.0, overlap), r.segments);
  }

  // k(t), f(t) and n(t). A track's asperity is in contact from its first window to its release;
  // where its line is not heard, k is held at its last value and its interval widens by the
  // prior's largest wear over the time since (wear only lowers k).
  const std::size_t nw = r.windows.size(), nt = r.tracks.size();
  auto table = [&] { return std::vector<std::vector<double>>(nt, std::vector<double>(nw, NOT_HERE)); };
  r.stiffness = table(), r.stiffness_low = table(), r.stiffness_high = table();
  r.frequency = table(), r.frequency_low = table(), r.frequency_high = table();
  r.count.assign(nw, 0.0);
  std::vector<std::vector<double>> uncertain(nw);
  std::vector<std::set<double>> linked(nw);
  // Unexcited: the asperities in contact at the record's start, counted by its plateau
  // (inverse/start_plateau.hpp) before the stiffest plausible asperity (the band's top line)
  // breaks away. (0: not read.)
  const std::optional<StartPlateau> plateau =
      r.excited || nw == 0 ? std::nullopt : asperities_at_start(device, stiffness_at(device, band_hz.second), level.sigma_v, grid, v);
  const std::size_t at_start = plateau ? plateau->count : 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const Track& track = r.tracks[t];
    // A line no event explains is an asperity already in contact heard again: with the start's
    // count known it is among those, else it is counted while it is heard.
    const bool counted = !(at_start > 0 && track.birth == TrackBirth::unexplained);
    double release_s = std::numeric_limits<double>::infinity();
    for (const TrackEvent& e : r.events)
      if (e.track == t && e.kind == TrackEventKind::release) release_s = e.time_s;
    double best_snr = 0.0;
    for (const TrackSighting& s : track.sightings) {
      best_snr = std::max(best_snr, s.line.snr);
      linked[s.window].insert(s.line.frequency_hz);
    }
    const double p = phi_cdf(best_snr - settings.threshold_snr);  // a track near threshold may be noise
    std::size_t next = 0;
    const WindowLine* last = nullptr;
    double last_time = 0.0;
    const std::size_t heard_until = track.released ? track.release_sighting : track.sightings.size();
    // In contact from its onset; from the record's start when it was there before (unexcited);
    // a line no event explains only while it is heard (it is not held: track_births.hpp).
    const std::size_t first_window = track.birth == TrackBirth::before_record ? 0 : track.sightings.front().window;
    const std::size_t last_window = track.birth == TrackBirth::unexplained ? track.sightings.back().window : nw - 1;
    for (std::size_t w = first_window; w <= last_window; ++w) {
      const double centre = r.windows[w].centre_s;
      if (centre > release_s && w > first_window) break;
      if (next < heard_until && track.sightings[next].window == w) {
        const WindowLine& seen = track.sightings[next].line;
        // Held afterwards: the last clear sighting (a fading ringing's last ones are the least
        // precise), or any after a step (the old stiffness is gone).
        const bool stepped = std::any_of(track.steps.begin(), track.steps.end(), [&](const StepMark& m) { return m.sighting == next; });
        if (!last || stepped || seen.snr >= 10.0 || last->snr < 10.0) {
          last = &seen;
          last_time = centre;
        }
        ++next;
        r.frequency[t][w] = seen.frequency_hz;
        r.frequency_low[t][w] = seen.frequency_hz - Z90 * seen.frequency_se_hz;
        r.frequency_high[t][w] = seen.frequency_hz + Z90 * seen.frequency_se_hz;
        r.stiffness[t][w] = seen.stiffness_n_per_m;
        r.stiffness_low[t][w] = seen.stiffness_low;
        r.stiffness_high[t][w] = seen.stiffness_high;
      } else if (last) {
        const double wear = settings.max_wear_per_ms * (centre - last_time) / 1e-3;
        r.stiffness[t][w] = last->stiffness_n_per_m * (1.0 - 0.5 * std::min(1.0, wear));
        r.stiffness_low[t][w] = last->stiffness_low * std::max(0.0, 1.0 - wear);
        r.stiffness_high[t][w] = last->stiffness_high;
      }
      if (!counted) continue;
      if (p >= 0.95) r.count[w] += 1.0;
      else uncertain[w].push_back(p);
    }
  }
  // Excited, k(t) where a segment was fitted is the segment's line centre (with the track's
  // fitted wear about the segment's middle): a window's peak wanders by ~1/T about it
  // (track_peaks.hpp). Its variance: the segment's plus the slope's over the time from its middle.
  if (r.excited)
    for (const TrackSegment& g : r.segments) {
      double slope = 0.0, slope_se = 0.0;
      for (const TrackWear& w : r.wear)
        if (w.track == g.track) slope = w.slope_per_s, slope_se = w.slope_se_per_s;
      const double middle = 0.5 * (g.start_s + g.end_s);
      const double se = (g.stiffness_high - g.stiffness_low) / (2.0 * Z90);
      for (std::size_t w = 0; w < nw; ++w) {
        const double c = r.windows[w].centre_s;
        if (c < g.start_s || c > g.end_s || std::isnan(r.stiffness[g.track][w])) continue;
        const double k = g.stiffness_n_per_m * (1.0 + slope * (c - middle));
        const double spread = Z90 * std::hypot(se, g.stiffness_n_per_m * slope_se * (c - middle));
        r.stiffness[g.track][w] = k;
        r.stiffness_low[g.track][w] = std::max(0.0, k - spread);
        r.stiffness_high[g.track][w] = k + spread;
      }
    }
  // The count: tracks in contact (a track whose best line is near the threshold counted when
  // it is more likely real than not). Its interval: the Poisson-binomial 5-95 % range of the
  // uncertain tracks and of the lines heard in no track near the threshold (p = Phi(z - z_th):
  // the chance the line's true SNR clears the threshold, its estimate having unit error).
  r.count_low.resize(nw);
  r.count_high.resize(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    const double certain = r.count[w];
    r.count[w] += static_cast<double>(std::count_if(uncertain[w].begin(), uncertain[w].end(), [](double q) { return q >= 0.5; }));
    for (const WindowLine& l : lines[w].lines)
      if (!linked[w].contains(l.frequency_hz)) uncertain[w].push_back(phi_cdf(l.snr - settings.threshold_snr));
    const auto [low, high] = poisson_binomial_interval(uncertain[w]);
    r.count_low[w] = std::min(r.count[w], certain + static_cast<double>(low));
    r.count_high[w] = std::max(r.count[w], certain + static_cast<double>(high));
  }
  // Unexcited: the asperities in contact at the record's start are counted by its plateau
  // (inverse/start_plateau.hpp); those no track accounts for at the first window were never
  // heard (the crowded start rings them all at once) and are in contact throughout, as far as
  // the record tells (a release heard later starts a track of its own, counted from the start).
  // A plateau far from its integer (a gain error, the baseline's noise) may be off by one:
  // the band is widened by one throughout.
  if (at_start > 0) {
    r.asperities_at_start = at_start;
    r.start_level = plateau->level;
    const double unheard = std::max(0.0, static_cast<double>(at_start) - r.count[0]);
    const double widen = plateau->uncertain() ? 1.0 : 0.0;
    for (std::size_t w = 0; w < nw; ++w) {
      r.count[w] += unheard;
      r.count_low[w] = std::max(0.0, r.count_low[w] + unheard - widen);
      r.count_high[w] += unheard + widen;
    }
  }
  r.window_lines = lines;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace stengmc
