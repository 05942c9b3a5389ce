#include "pipeline/spectral_summary.hpp"

#include <algorithm>
#include <cstdio>

namespace stengmc {

namespace {

//! "+0.0123 %" when identified, else why not.
std::string verdict(const Identifiability& id, std::size_t i, double expected_hz) {
  if (id.identified.at(i)) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.4f %%", 100.0 * id.frequency_error_hz[i] / expected_hz);
    return text;
  }
  return id.matched_line.at(i) < 0 ? "not found" : "ambiguous";
}

//! A table of found items (FFT peaks or ESPRIT lines), by frequency: at most 20, the
//! strongest, the rest counted (every one is in the output file at `dataset`). `third`
//! names the last column and `value` reads it.
template <class Item, class Third>
std::string format_found(std::vector<Item> items, const char* what, const char* third, Third value,
                         const char* dataset) {
  constexpr std::size_t MAX_LISTED = 20;
  const std::size_t found = items.size();
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.amplitude > b.amplitude; });
  if (items.size() > MAX_LISTED) items.resize(MAX_LISTED);
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.frequency_hz < b.frequency_hz; });
  char line[160];
  std::snprintf(line, sizeof line, "%-4s %14s %14s %16s\n", "#", what, "amplitude [V]", third);
  std::string out = line;
  for (std::size_t i = 0; i < items.size(); ++i) {
    std::snprintf(line, sizeof line, "%-4zu %14.5f %14.4g %16.4g\n", i + 1, items[i].frequency_hz * 1e-6,
                  items[i].amplitude, value(items[i]));
    out += line;
  }
  if (found > items.size()) out += "     ... and " + std::to_string(found - items.size()) + " weaker (" + dataset + ")\n";
  return out;
}

//! What a record's spectrum holds when there are no asperities to compare with.
std::string format_found_lines(const SpectralResult& result) {
  std::string out = format_found(result.peaks, "FFT peak [MHz]", "prominence [V]",
                                 [](const Peak& p) { return p.prominence; }, "/spectrum/peaks");
  if (result.peaks.empty()) out += "     (no peak stands above the noise floor)\n";
  if (result.high_resolution)
    out += format_found(result.lines, "ESPRIT [MHz]", "damping [1/s]", [](const Line& l) { return l.damping_per_s; },
                        "/spectrum/lines");
  return out;
}

}  // namespace

std::string format_spectral_summary(const SpectralResult& result) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line,
                "spectrum: %zu samples from t = %.4g s, resolution %.4g Hz, noise floor %.3g V, %zu FFT peaks",
                result.samples, result.start_time_s,
                result.voltage.resolution_hz, result.noise_floor_v, result.peaks.size());
  out += line;
  if (result.high_resolution) out += ", " + std::to_string(result.lines.size()) + " ESPRIT lines";
  out += "\n";
  if (result.expected_frequency_hz.empty()) {
    // A measured record: no asperities to compare with, so what was found is the answer.
    out += format_found_lines(result);
  } else {
    std::snprintf(line, sizeof line, "%-4s %12s %8s %18s %18s\n", "#", "f_i [MHz]", "slides", "FFT line error",
                  "ESPRIT line error");
    out += line;
    for (std::size_t i = 0; i < result.expected_frequency_hz.size(); ++i) {
      const double f = result.expected_frequency_hz[i];
      const bool slides = result.sliding.at(i);
      std::snprintf(line, sizeof line, "%-4zu %12.5f %8s %18s %18s\n", i + 1, f * 1e-6, slides ? "yes" : "no",
                    slides ? verdict(result.fft, i, f).c_str() : "",
                    slides && result.high_resolution ? verdict(*result.high_resolution, i, f).c_str() : "");
      out += line;
    }
    std::snprintf(line, sizeof line, "identifiable: FFT %zu of %zu sliding (ratio %.3f)", result.fft.n_identifiable,
                  result.fft.n_sliding, result.fft.ratio);
    out += line;
    if (result.high_resolution) {
      std::snprintf(line, sizeof line, "; ESPRIT %zu of %zu (ratio %.3f)", result.high_resolution->n_identifiable,
                    result.high_resolution->n_sliding, result.high_resolution->ratio);
      out += line;
    }
    out += "\n";
  }
  for (const std::string& note : result.notes) out += "NOTE: " + note + "\n";
  return out;
}

}  // namespace stengmc
