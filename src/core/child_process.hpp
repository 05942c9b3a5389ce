#pragma once
//! Work that may take this process down, done in a child process instead: a library that
//! can crash, loop or grow without bound on what a user gave it (ngspice on a netlist) runs
//! in a forked child under a time and memory budget, and its result comes back through a
//! pipe. A crash, a kill at the budget or a child that never answers is then a report the
//! caller turns into a named error, not the death of stengmc (docs/faults.md).
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace stengmc {

//! What the child may spend. Wall time is the backstop for a child that blocks (no CPU
//! spent); CPU time is what a loaded machine does not shorten.
struct ChildBudget {
  double cpu_seconds = 600.0;   //!< CPU time [s]
  double wall_seconds = 1800.0; //!< elapsed time [s]
  double memory_bytes = 8e9;    //!< resident memory it may grow by [bytes]
};

//! How the child ended.
struct ChildOutcome {
  enum class End {
    finished,       //!< exited with status 0 after writing its result
    failed,         //!< exited with another status
    crashed,        //!< died of a signal it raised or received (not ours; SIGKILL may be the system's OOM killer)
    out_of_time,    //!< stopped at its CPU (SIGXCPU) or wall-time budget
    out_of_memory,  //!< killed at its memory budget
  };
  End end = End::finished;
  int exit_status = 0;             //!< the status, when failed
  int signal_number = 0;           //!< the signal, when crashed
  std::string result;              //!< every byte the child wrote to its result pipe
  double peak_memory_bytes = 0.0;  //!< the most resident memory seen [bytes]

  //! "crashed (Segmentation fault)", "was stopped after 600 s of CPU time", ...
  [[nodiscard]] std::string describe(const ChildBudget& budget) const;
};

//! Runs `work` in a forked child with the budget and collects what it writes to the file
//! descriptor it is given. In the child: the signal handlers of this process are reset (a
//! Ctrl-C kills it plainly), it dies with its parent, stdio is not flushed twice, and it
//! ends with _exit (0 when `work` returned, 1 when it threw). The child has only the
//! calling thread: `work` must not use OpenMP or wait on locks other threads may hold.
//! `on_bytes`, when given, sees every chunk as it arrives (live progress), in order.
//! @throws Error when no child can be made (a process limit) or the pipe fails
ChildOutcome run_in_child(const std::function<void(int result_fd)>& work, const ChildBudget& budget,
                          const std::function<void(std::string_view bytes)>& on_bytes = {});

//! Writes all of `bytes` to a pipe, retrying short writes; false when the reader is gone.
bool write_to_pipe(int fd, std::string_view bytes);

}  // namespace stengmc
