#pragma once
#include <chrono>
#include <cstddef>
#include <string>

namespace stengmc {

//! A progress bar with ETA on stderr. It stays silent for the first second, so
//! quick runs print nothing, and redraws at most ten times a second.
class Progress {
 public:
  //! @param label  what is being done ("tribology", "circuit")
  //! @param total  number of work units
  Progress(std::string label, std::size_t total);
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
  std::size_t done_ = 0;
  std::string status_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace stengmc
