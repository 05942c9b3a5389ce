#pragma once
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <optional>
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
  //! A terminal's width in characters: the bar's line is cut to fit, so a redraw never wraps.
  int columns = 80;

  //! stderr, a terminal when isatty says so, its width from the terminal (else $COLUMNS, else 80).
  static ProgressOutput for_stderr();
};

//! Seconds as a person reads them: "42.0 s", "12.5 min", "3.2 h".
std::string format_duration(double seconds);

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
  //! This report is one part of a longer job (a sweep's grid point) that started at
  //! `job_start`: its units cover the job's fraction [before, before + share]. The report then
  //! also gives the whole job's ETA, assuming the parts left cost what the parts done did.
  void set_job_share(std::chrono::steady_clock::time_point job_start, double before, double share);

 private:
  void draw(bool final);

  std::string label_;
  std::size_t total_;
  ProgressOutput output_;
  std::size_t done_ = 0;
  std::string status_;
  std::optional<std::chrono::steady_clock::time_point> job_start_;
  double job_before_ = 0.0, job_share_ = 1.0;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace stengmc
