#pragma once
//! The temporary name an output is written under before it is renamed into place, and
//! its removal on every failure path (docs/faults.md).
//!
//! The name is `<final>.<host>.<pid>.tmp`: two runs writing the same output (on one machine
//! or on several sharing a disk) never write the same temporary. The file is removed
//!  - by the destructor, when an exception unwinds the writer;
//!  - by a SIGINT, SIGTERM or SIGHUP handler (Ctrl-C, a batch system's kill), which removes
//!    every registered temporary and then dies of the signal as it would have;
//!  - after a SIGKILL or a power cut, which nothing can intercept, by the next TemporaryFile
//!    for the same final path: it removes the temporaries of that path left by processes of
//!    this host that no longer exist (another host's are never touched: its process may be
//!    alive).
#include <string>

namespace stengmc {

class TemporaryFile {
 public:
  //! Chooses the temporary name for `final_path` and removes stale temporaries of it; does
  //! not create the file.
  explicit TemporaryFile(std::string final_path);
  //! Removes the temporary file unless it was committed.
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& final_path() const { return final_path_; }

  //! Renames the temporary file onto the final path (atomic within one filesystem); throws
  //! Error naming the final path with the system's reason.
  void commit();

 private:
  std::string final_path_;
  std::string path_;
  int slot_ = -1;  //!< where the signal handler finds the name
  bool committed_ = false;
};

//! `<final>.<host>.<pid>.tmp` for this process.
std::string temporary_name(const std::string& final_path);

//! Removes the temporaries of `final_path` left by processes of this host that are gone;
//! returns how many were removed.
std::size_t remove_stale_temporaries(const std::string& final_path);

//! What the same signal handler tells the user before the process dies (how to resume, say):
//! printed on standard error after the temporaries are removed. One note at a time; "" (or
//! InterruptionNote's end) clears it. Installs the handler if it is not yet installed.
void set_interruption_note(const std::string& note);

//! Sets a note for its lifetime (a run that keeps a journal: "the same command resumes").
class InterruptionNote {
 public:
  explicit InterruptionNote(const std::string& note) { set_interruption_note(note); }
  ~InterruptionNote() { set_interruption_note(""); }
  InterruptionNote(const InterruptionNote&) = delete;
  InterruptionNote& operator=(const InterruptionNote&) = delete;
};

}  // namespace stengmc
