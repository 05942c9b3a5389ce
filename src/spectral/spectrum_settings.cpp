#include "spectral/spectrum_settings.hpp"

#include <string>

namespace stengmc {

SpectrumSettings read_spectrum_settings(TomlTable& table) {
  SpectrumSettings s;
  s.window = parse_window(table.choice("window", "hann", {"rectangular", "hann", "blackman_harris"}), "[spectrum] window");
  s.start_s = table.non_negative("start_s", s.start_s);
  s.end_s = table.non_negative("end_s", s.end_s);
  if (s.end_s > 0.0 && s.end_s <= s.start_s)
    table.fail("end_s", "= " + std::to_string(s.end_s) + " must be > start_s = " + std::to_string(s.start_s) + " (or 0 for the end of the run)");
  s.zero_pad_factor = static_cast<std::size_t>(table.integer("zero_pad_factor", 1, 1));
  if (s.zero_pad_factor > 64) table.fail("zero_pad_factor", "must be <= 64");
  s.element_currents = table.boolean("element_currents", s.element_currents);
  s.peaks.prominence_over_floor = table.positive("prominence_over_floor", s.peaks.prominence_over_floor);
  s.peaks.min_separation_hz = table.non_negative("min_separation_hz", s.peaks.min_separation_hz);
  s.peaks.min_frequency_hz = table.non_negative("min_frequency_hz", s.peaks.min_frequency_hz);
  s.peaks.leakage_margin = table.non_negative("leakage_margin", s.peaks.leakage_margin);
  s.peaks.max_peaks = static_cast<std::size_t>(table.integer("max_peaks", static_cast<long long>(s.peaks.max_peaks), 1));
  s.peaks.max_frequency_hz = table.non_negative("max_frequency_hz", s.peaks.max_frequency_hz);
  if (s.peaks.max_frequency_hz > 0.0 && s.peaks.max_frequency_hz <= s.peaks.min_frequency_hz)
    table.fail("max_frequency_hz", "must be > min_frequency_hz (or 0 for up to Nyquist)");
  s.peaks.floor_window_hz = table.non_negative("floor_window_hz", s.peaks.floor_window_hz);
  s.esprit.min_frequency_hz = s.peaks.min_frequency_hz;
  s.high_resolution = table.boolean("high_resolution", s.high_resolution);
  s.esprit.max_lines = static_cast<std::size_t>(table.integer("max_lines", static_cast<long long>(s.esprit.max_lines), 1));
  if (s.esprit.max_lines > 64) table.fail("max_lines", "must be <= 64");
  s.esprit.criterion = parse_order_criterion(table.choice("order_criterion", "mdl", {"mdl", "aic", "ester"}),
                                             "[spectrum] order_criterion");
  s.esprit.fixed_lines = static_cast<std::size_t>(table.integer("fixed_lines", 0, 0));
  s.esprit.max_samples = static_cast<std::size_t>(table.integer("max_esprit_samples", static_cast<long long>(s.esprit.max_samples), 16));
  s.identifiability.relative_tolerance = table.positive("identification_tolerance", s.identifiability.relative_tolerance);
  if (s.identifiability.relative_tolerance >= 0.5)
    table.fail("identification_tolerance", "must be < 0.5 (a relative frequency tolerance)");
  s.dynamic_range_db = table.positive("dynamic_range_db", s.dynamic_range_db);
  s.min_slip_fraction = table.non_negative("min_slip_fraction", s.min_slip_fraction);
  if (s.min_slip_fraction > 1.0) table.fail("min_slip_fraction", "must be <= 1");
  if (auto spectrogram = table.table("spectrogram")) {
    SpectrogramOptions o;
    o.window_samples = static_cast<std::size_t>(spectrogram->integer("window_samples", static_cast<long long>(o.window_samples), 4));
    o.hop_samples = static_cast<std::size_t>(spectrogram->integer("hop_samples", static_cast<long long>(o.hop_samples), 1));
    o.window = parse_window(spectrogram->choice("window", "hann", {"rectangular", "hann", "blackman_harris"}),
                            "[spectrum.spectrogram] window");
    s.spectrogram = o;
  }
  return s;
}

SpectrumSettings read_spectrum_table(TomlDocument& document, std::string_view when_missing) {
  TomlTable root = document.root();
  auto table = root.table("spectrum");
  if (!table) {
    std::string what = "is missing";
    what.append(when_missing);
    root.fail("spectrum", what);
  }
  SpectrumSettings settings = read_spectrum_settings(*table);
  // Only [spectrum] is read here; whatever else the document holds is its owner's business.
  document.reject_unknown_keys("spectrum");
  return settings;
}

}  // namespace stengmc
