#include "io/tracking_file.hpp"

#include <cstdint>
#include <type_traits>

#include "core/hdf5_file.hpp"
#include "io/output_vocabulary.hpp"
#include "io/run_file.hpp"

namespace stengmc {

namespace {

//! One member of every row, as a dataset's values: a table of structs written column by column
//! (indices and counts as 64-bit integers, the files' integer type).
template <class Row, class Member>
auto column(const std::vector<Row>& rows, Member Row::*member) {
  using Value = std::conditional_t<std::is_integral_v<Member>, std::int64_t, Member>;
  std::vector<Value> values;
  values.reserve(rows.size());
  for (const Row& row : rows) values.push_back(static_cast<Value>(row.*member));
  return values;
}

}  // namespace

void write_tracking_file(const std::string& path, const TrackingFileContext& context, const TrackingResult& r) {
  Hdf5Writer f(path, describe_output);
  write_provenance(f, {.file_type = "stengmc-tracking",
                       .input_file = context.known_file,
                       .input_text = context.known_text,
                       .seed = 0,
                       .surface_file = "",
                       .surface_text = "",
                       .auxiliary_inputs = ""});
  const double step = context.times_s.size() > 1 ? context.times_s[1] - context.times_s[0] : 0.0;
  f.attribute("/", "record", context.record);
  f.attribute("/", "regime", r.excited ? "excited" : "unexcited");
  f.attribute("/", "window_s", static_cast<double>(r.windowing.length) * step);
  f.attribute("/", "hop_s", static_cast<double>(r.windowing.hop) * step);
  f.attribute("/", "noise_sigma_v", r.noise_sigma_v);
  f.attribute("/", "band_low_hz", r.band_low_hz);
  f.attribute("/", "band_high_hz", r.band_high_hz);
  f.attribute("/", "max_wear_per_ms", context.max_wear_per_ms);
  f.attribute("/", "max_missed", static_cast<std::int64_t>(context.max_missed));
  f.attribute("/", "threshold_snr", context.threshold_snr);
  f.attribute("/", "naive_threshold", context.naive_threshold);
  f.attribute("/", "seconds", r.seconds);
  // Unexcited: the asperities counted at the start from its plateau (0: not read) and, when
  // read, the plateau's level before rounding.
  f.attribute("/", "start_count", static_cast<std::int64_t>(r.asperities_at_start));
  if (r.asperities_at_start > 0) f.attribute("/", "start_level", r.start_level);

  std::vector<double> floor;
  for (const WindowLines& w : r.window_lines) floor.push_back(w.floor_v);
  f.write("/tracking/window_time", column(r.windows, &TrackWindow::centre_s));
  f.write("/tracking/window_start", column(r.windows, &TrackWindow::start_s));
  f.write("/tracking/window_mean", r.window_mean_v);
  f.write("/tracking/noise_floor", floor);
  f.write("/tracking/count", r.count);
  f.write("/tracking/count_low", r.count_low);
  f.write("/tracking/count_high", r.count_high);
  f.write("/tracking/naive_count", r.naive_count);
  std::vector<std::int64_t> tracks;
  for (std::size_t t = 0; t < r.tracks.size(); ++t) tracks.push_back(static_cast<std::int64_t>(t));
  f.write("/tracking/track", tracks);
  f.write("/tracking/error_inflation", r.error_inflation);
  const std::size_t nw = r.windows.size();
  f.write_with_gaps("/tracking/stiffness_n_per_m", r.stiffness, nw);
  f.write_with_gaps("/tracking/stiffness_low", r.stiffness_low, nw);
  f.write_with_gaps("/tracking/stiffness_high", r.stiffness_high, nw);
  f.write_with_gaps("/tracking/frequency_hz", r.frequency, nw);
  f.write_with_gaps("/tracking/frequency_low", r.frequency_low, nw);
  f.write_with_gaps("/tracking/frequency_high", r.frequency_high, nw);

  std::vector<std::string> kind;
  for (const TrackEvent& e : r.events) kind.emplace_back(track_event_name(e.kind));
  f.write("/tracking/events/kind", kind);
  f.write("/tracking/events/time_s", column(r.events, &TrackEvent::time_s));
  f.write("/tracking/events/time_low_s", column(r.events, &TrackEvent::time_low_s));
  f.write("/tracking/events/time_high_s", column(r.events, &TrackEvent::time_high_s));
  f.write("/tracking/events/track", column(r.events, &TrackEvent::track));

  f.write("/tracking/segments/track", column(r.segments, &TrackSegment::track));
  f.write("/tracking/segments/start_s", column(r.segments, &TrackSegment::start_s));
  f.write("/tracking/segments/end_s", column(r.segments, &TrackSegment::end_s));
  f.write("/tracking/segments/windows", column(r.segments, &TrackSegment::windows));
  f.write("/tracking/segments/stiffness_n_per_m", column(r.segments, &TrackSegment::stiffness_n_per_m));
  f.write("/tracking/segments/stiffness_low", column(r.segments, &TrackSegment::stiffness_low));
  f.write("/tracking/segments/stiffness_high", column(r.segments, &TrackSegment::stiffness_high));
  f.write("/tracking/segments/frequency_hz", column(r.segments, &TrackSegment::frequency_hz));

  f.write("/tracking/wear/track", column(r.wear, &TrackWear::track));
  f.write("/tracking/wear/wear_rate_per_ms", column(r.wear, &TrackWear::rate_per_ms));
  f.write("/tracking/wear/wear_rate_low", column(r.wear, &TrackWear::rate_low));
  f.write("/tracking/wear/wear_rate_high", column(r.wear, &TrackWear::rate_high));
  f.write("/tracking/wear/pieces", column(r.wear, &TrackWear::pieces));

  std::vector<std::int64_t> line_window, detected;
  std::vector<double> lf, lse, la, lz;
  for (std::size_t w = 0; w < r.window_lines.size(); ++w)
    for (const WindowLine& l : r.window_lines[w].lines) {
      line_window.push_back(static_cast<std::int64_t>(w));
      detected.push_back(l.detected ? 1 : 0);
      lf.push_back(l.frequency_hz);
      lse.push_back(l.frequency_se_hz);
      la.push_back(l.amplitude_v);
      lz.push_back(l.snr);
    }
  f.write("/tracking/lines/window", line_window);
  f.write("/tracking/lines/frequency_hz", lf);
  f.write("/tracking/lines/frequency_se_hz", lse);
  f.write("/tracking/lines/amplitude_v", la);
  f.write("/tracking/lines/snr", lz);
  f.write("/tracking/lines/detected", detected);
  f.write("/tracking/record/time", context.times_s);
  f.write("/tracking/record/voltage", context.voltage_v);
  f.commit();
}

}  // namespace stengmc
