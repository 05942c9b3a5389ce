#pragma once
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace stengmc {

//! Where and how a Progress reports.
struct ProgressOutput {
  std::FILE* stream = stderr;
  //! A terminal gets one bar redrawn in place (carriage return); anything else (a log
  //! file, CI, a Slurm output file) gets a plain line every `line_period`, so the log
  //! stays readable and small.
  bool terminal = false;
  std::chrono::milliseconds silent_period{1000};  //!< nothing is shown before this
  std::chrono::milliseconds redraw_period{100};   //!< a terminal's bar: at most this often
  std::chrono::milliseconds line_period{5000};    //!< elsewhere: one line this often

  //! stderr, a terminal when isatty says so.
  static ProgressOutput for_stderr();
};

//! A progress report with ETA. It stays silent for the first second, so quick runs print
//! nothing; on a terminal it is a bar redrawn at most ten times a second, elsewhere a line
//! every few seconds (ProgressOutput).
class Progress {
 public:
  //! @param label  what is being done ("tribology", "circuit")
  //! @param total  number of work units
  Progress(std::string label, std::size_t total, ProgressOutput output = ProgressOutput::for_stderr());
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  //! Marks `units` more work units as done.
  void advance(std::size_t units = 1);
  //! A short live line shown after the ETA (e.g. the running statistics); "" for none.
  void set_status(std::string status) { status_ = std::move(status); }

 private:
  void draw(bool final);

  std::string label_;
  std::size_t total_;
  ProgressOutput output_;
  std::size_t done_ = 0;
  std::string status_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace stengmc
