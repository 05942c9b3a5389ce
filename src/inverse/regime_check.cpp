#include "inverse/regime_check.hpp"

namespace stengmc {

double growing_line_share(const TrackingResult& r, std::size_t* count) {
  std::size_t strong = 0, growing = 0;
  for (const WindowLines& w : r.window_lines)
    for (const WindowLine& l : w.lines)
      if (l.detected && l.snr >= 10.0) {
        ++strong;
        if (l.damping_per_s < 0.0) ++growing;
      }
  if (count) *count = strong;
  return strong > 0 ? static_cast<double>(growing) / static_cast<double>(strong) : 0.0;
}

bool looks_excited(const TrackingResult& r) {
  std::size_t strong = 0;
  const double share = growing_line_share(r, &strong);
  return !r.excited && strong >= 20 && share >= 0.3;
}

}  // namespace stengmc
