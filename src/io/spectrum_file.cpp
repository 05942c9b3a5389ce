#include "io/spectrum_file.hpp"

#include "core/column.hpp"

#include <cstdint>
#include <string>

namespace stengmc {

namespace {


void write_identifiability(Hdf5Writer& file, const std::string& group, const Identifiability& id) {
  std::vector<std::int64_t> identified, matched;
  for (bool b : id.identified) identified.push_back(b ? 1 : 0);
  for (int m : id.matched_line) matched.push_back(m);
  file.write(group + "/identified", identified);
  file.write(group + "/matched_line", matched);
  file.write(group + "/frequency_error", id.frequency_error_hz);
  file.write(group + "/amplitude", id.amplitude);
  file.attribute(group, "n_sliding", static_cast<std::int64_t>(id.n_sliding));
  file.attribute(group, "n_detected", static_cast<std::int64_t>(id.n_detected));
  file.attribute(group, "n_identifiable", static_cast<std::int64_t>(id.n_identifiable));
  file.attribute(group, "ratio", id.ratio);
}

}  // namespace

void write_spectra(Hdf5Writer& file, const SpectralResult& result, const SpectrumSettings& settings) {
  file.write("/spectrum/frequency", result.voltage.frequency_hz);
  file.write("/spectrum/voltage", result.voltage.amplitude);
  if (!result.current_amplitude.empty()) file.write("/spectrum/current", result.current_amplitude);
  file.attribute("/spectrum", "window", window_name(settings.window));
  file.attribute("/spectrum", "start_s", settings.start_s);
  file.attribute("/spectrum", "end_s", settings.end_s);
  file.attribute("/spectrum", "first_sample", static_cast<std::int64_t>(result.first_sample));
  file.attribute("/spectrum", "samples", static_cast<std::int64_t>(result.samples));
  file.attribute("/spectrum", "zero_pad_factor", static_cast<std::int64_t>(settings.zero_pad_factor));
  file.attribute("/spectrum", "resolution_hz", result.voltage.resolution_hz);
  file.attribute("/spectrum", "noise_floor_v", result.noise_floor_v);
  file.attribute("/spectrum", "prominence_over_floor", settings.peaks.prominence_over_floor);
  file.attribute("/spectrum", "identification_tolerance", settings.identifiability.relative_tolerance);
  file.attribute("/spectrum", "dynamic_range_db", settings.dynamic_range_db);
  file.attribute("/spectrum", "start_time_s", result.start_time_s);
  file.attribute("/spectrum", "mean_v", result.mean_v);
  file.write("/spectrum/expected_frequency", result.expected_frequency_hz);
  std::vector<std::int64_t> sliding;
  for (bool b : result.sliding) sliding.push_back(b ? 1 : 0);
  file.write("/spectrum/sliding", sliding);

  file.write("/spectrum/peaks/frequency", column(result.peaks, [](const Peak& p) { return p.frequency_hz; }));
  file.write("/spectrum/peaks/amplitude", column(result.peaks, [](const Peak& p) { return p.amplitude; }));
  file.write("/spectrum/peaks/prominence", column(result.peaks, [](const Peak& p) { return p.prominence; }));
  write_identifiability(file, "/spectrum/identifiability/fft", result.fft);

  if (result.high_resolution) {
    file.write("/spectrum/lines/frequency", column(result.lines, [](const Line& l) { return l.frequency_hz; }));
    file.write("/spectrum/lines/amplitude", column(result.lines, [](const Line& l) { return l.amplitude; }));
    file.write("/spectrum/lines/damping", column(result.lines, [](const Line& l) { return l.damping_per_s; }));
    file.write("/spectrum/lines/phase", column(result.lines, [](const Line& l) { return l.phase_rad; }));
    file.attribute("/spectrum/lines", "order_criterion", order_criterion_name(settings.esprit.criterion));
    file.attribute("/spectrum/lines", "samples_used",
                   static_cast<std::int64_t>(std::min(result.samples, settings.esprit.max_samples)));
    write_identifiability(file, "/spectrum/identifiability/high_resolution", *result.high_resolution);
  }
  if (result.spectrogram) {
    const Spectrogram& s = *result.spectrogram;
    file.write("/spectrogram/window_time", s.time_s);  // not "time": that would shadow the root's /time
    file.write("/spectrogram/frequency", s.frequency_hz);
    file.write("/spectrogram/voltage", s.amplitude);
    file.attribute("/spectrogram", "window", window_name(settings.spectrogram->window));
    file.attribute("/spectrogram", "window_samples", static_cast<std::int64_t>(settings.spectrogram->window_samples));
    file.attribute("/spectrogram", "hop_samples", static_cast<std::int64_t>(settings.spectrogram->hop_samples));
  }
}

}  // namespace stengmc
