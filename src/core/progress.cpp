#include "core/progress.hpp"

#include <cstdio>

namespace stengmc {

namespace {
constexpr auto SILENT_PERIOD = std::chrono::seconds(1);
constexpr auto REDRAW_PERIOD = std::chrono::milliseconds(100);
constexpr int BAR_WIDTH = 30;
}  // namespace

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total == 0 ? 1 : total),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::~Progress() {
  if (shown_) draw(true);
}

void Progress::advance(std::size_t units) {
  done_ += units;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < SILENT_PERIOD) return;
  if (shown_ && now - last_draw_ < REDRAW_PERIOD && done_ < total_) return;
  last_draw_ = now;
  draw(false);
}

void Progress::draw(bool final) {
  shown_ = true;
  const double fraction = std::min(1.0, static_cast<double>(done_) / static_cast<double>(total_));
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  const int filled = static_cast<int>(fraction * BAR_WIDTH);
  // \033[K clears what a longer previous line left behind.
  std::fprintf(stderr, "\r%-10s [%.*s%*s] %5.1f%%  elapsed %6.1f s  ETA %6.1f s%s%s\033[K", label_.c_str(), filled,
               "##############################", BAR_WIDTH - filled, "", 100.0 * fraction, elapsed, eta,
               status_.empty() ? "" : "  ", status_.c_str());
  if (final) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace stengmc
