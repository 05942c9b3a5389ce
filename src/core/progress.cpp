#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>

namespace stengmc {

namespace {
constexpr int BAR_WIDTH = 30;
}  // namespace

ProgressOutput ProgressOutput::for_stderr() {
  ProgressOutput output;
  output.terminal = ::isatty(::fileno(stderr)) == 1;
  return output;
}

Progress::Progress(std::string label, std::size_t total, ProgressOutput output)
    : label_(std::move(label)), total_(total == 0 ? 1 : total), output_(output),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::~Progress() {
  if (shown_) draw(true);
}

void Progress::advance(std::size_t units) {
  done_ += units;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < output_.silent_period) return;
  const auto period = output_.terminal ? output_.redraw_period : output_.line_period;
  if (shown_ && now - last_draw_ < period && done_ < total_) return;
  if (!output_.terminal && shown_ && done_ >= total_) return;  // the destructor writes the last line
  last_draw_ = now;
  draw(false);
}

void Progress::draw(bool final) {
  shown_ = true;
  const double fraction = std::min(1.0, static_cast<double>(done_) / static_cast<double>(total_));
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  const char* separator = status_.empty() ? "" : "  ";
  if (output_.terminal) {
    const int filled = static_cast<int>(fraction * BAR_WIDTH);
    // \033[K clears what a longer previous line left behind.
    std::fprintf(output_.stream, "\r%-10s [%.*s%*s] %5.1f%%  elapsed %6.1f s  ETA %6.1f s%s%s\033[K", label_.c_str(),
                 filled, "##############################", BAR_WIDTH - filled, "", 100.0 * fraction, elapsed, eta,
                 separator, status_.c_str());
    if (final) std::fputc('\n', output_.stream);
  } else {
    std::fprintf(output_.stream, "%s: %zu/%zu (%.1f%%)  elapsed %.1f s  ETA %.1f s%s%s\n", label_.c_str(),
                 std::min(done_, total_), total_, 100.0 * fraction, elapsed, eta, separator, status_.c_str());
  }
  std::fflush(output_.stream);
}

}  // namespace stengmc
