#include "core/progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

namespace stengmc {

namespace {

constexpr int MAX_BAR_WIDTH = 30;
constexpr int MIN_COLUMNS = 20;  // narrower than this, the bar is left out and the text cut

//! The terminal's width: the tty's, else $COLUMNS, else 80.
int terminal_columns(int fd) {
  winsize size{};
  if (::ioctl(fd, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) {
    const long value = std::strtol(columns, nullptr, 10);
    if (value > 0 && value < 10000) return static_cast<int>(value);
  }
  return 80;
}

//! `text` cut to `width` characters (UTF-8: never inside a character).
std::string fit(std::string text, std::size_t width) {
  std::size_t characters = 0, at = 0;
  for (; at < text.size(); ++at) {
    if ((static_cast<unsigned char>(text[at]) & 0xC0) == 0x80) continue;  // a continuation byte
    if (characters == width) break;
    ++characters;
  }
  text.resize(at);
  return text;
}

}  // namespace

std::string format_duration(double seconds) {
  char text[32];
  if (seconds < 120.0) std::snprintf(text, sizeof text, "%.1f s", seconds);
  else if (seconds < 7200.0) std::snprintf(text, sizeof text, "%.1f min", seconds / 60.0);
  else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  return text;
}

ProgressOutput ProgressOutput::for_stderr() {
  ProgressOutput output;
  output.terminal = ::isatty(::fileno(stderr)) == 1;
  if (output.terminal) output.columns = terminal_columns(::fileno(stderr));
  return output;
}

void Progress::set_job_share(std::chrono::steady_clock::time_point job_start, double before, double share) {
  job_start_ = job_start;
  job_before_ = before;
  job_share_ = share;
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
  const auto now = std::chrono::steady_clock::now();
  const double fraction = std::min(1.0, static_cast<double>(done_) / static_cast<double>(total_));
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::string times = "elapsed " + format_duration(elapsed) + "  ETA " + format_duration(eta);
  if (job_start_) {
    const double job_fraction = std::min(1.0, job_before_ + job_share_ * fraction);
    const double job_elapsed = std::chrono::duration<double>(now - *job_start_).count();
    if (job_fraction > 0) times += " (whole job " + format_duration(job_elapsed * (1.0 - job_fraction) / job_fraction) + ")";
  }
  const std::string status = status_.empty() ? "" : "  " + status_;
  char numbers[64];
  if (output_.terminal) {
    std::snprintf(numbers, sizeof numbers, "%5.1f%%", 100.0 * fraction);
    // The bar takes what the text leaves, up to MAX_BAR_WIDTH; the line is then cut one
    // short of the width, so the terminal never wraps it (a wrapped \r redraw is a new line).
    const int columns = std::max(output_.columns, MIN_COLUMNS);
    const std::string text = std::string(numbers) + "  " + times;
    const int room = columns - 1 - static_cast<int>(label_.size() + text.size()) - 4;
    const int bar_width = std::min(MAX_BAR_WIDTH, room);
    std::string line = label_ + " ";
    if (bar_width >= 5) {
      const int filled = static_cast<int>(fraction * bar_width);
      // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, its bug 105329) on
      // "literal" + std::string temporaries.
      line.append("[").append(static_cast<std::size_t>(filled), '#').append(static_cast<std::size_t>(bar_width - filled), ' ').append("] ");
    }
    line += text + status;
    // \033[K clears what a longer previous line left behind.
    std::fprintf(output_.stream, "\r%s\033[K", fit(line, static_cast<std::size_t>(columns - 1)).c_str());
    if (final) std::fputc('\n', output_.stream);
  } else {
    std::fprintf(output_.stream, "%s: %zu/%zu (%.1f%%)  %s%s\n", label_.c_str(), std::min(done_, total_), total_,
                 100.0 * fraction, times.c_str(), status.c_str());
  }
  std::fflush(output_.stream);
}

}  // namespace stengmc
