#include "core/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <thread>

#include "core/error.hpp"

namespace stengmc {

namespace {

//! Resident and virtual size of process `pid` ("self" for this one) [bytes]; 0 when unknown.
struct MemoryUse {
  double resident_bytes = 0.0;
  double virtual_bytes = 0.0;
};

MemoryUse memory_of(const std::string& pid) {
  std::ifstream statm("/proc/" + pid + "/statm");
  double pages_virtual = 0.0, pages_resident = 0.0;
  if (!(statm >> pages_virtual >> pages_resident)) return {};
  const double page = static_cast<double>(::sysconf(_SC_PAGESIZE));
  return {pages_resident * page, pages_virtual * page};
}

//! The child's side: limits, then the work, then _exit without this process's clean-up.
[[noreturn]] void be_the_child(const std::function<void(int)>& work, int result_fd, pid_t parent,
                               const ChildBudget& budget, double virtual_at_fork) {
  // Ctrl-C and a batch system's SIGTERM kill the child plainly: the parent's handlers
  // (which remove the parent's temporary files) are not the child's to run.
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXCPU}) ::signal(signal_number, SIG_DFL);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);  // the parent died before the line above

  // CPU time: the kernel sends SIGXCPU at the soft limit (default action: die).
  const auto cpu = static_cast<rlim_t>(std::ceil(std::max(budget.cpu_seconds, 1.0)));
  const rlimit cpu_limit{cpu, cpu + 5};
  ::setrlimit(RLIMIT_CPU, &cpu_limit);
#if !defined(__SANITIZE_ADDRESS__)
  // Address space: what the parent had mapped at the fork plus the budget, so an
  // allocation beyond it fails inside the library instead of swapping the machine. (Not
  // under AddressSanitizer, whose shadow memory is mapped as it is touched; the parent's
  // watch of the resident size bounds it there.)
  const auto address_space = static_cast<rlim_t>(virtual_at_fork + budget.memory_bytes);
  const rlimit memory_limit{address_space, address_space};
  ::setrlimit(RLIMIT_AS, &memory_limit);
#else
  (void)virtual_at_fork;
#endif
  int status = 0;
  try {
    work(result_fd);
  } catch (...) {
    status = 1;
  }
  ::close(result_fd);
  ::_exit(status);
}

}  // namespace

bool write_to_pipe(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

std::string ChildOutcome::describe(const ChildBudget& budget) const {
  char text[160];
  switch (end) {
    case End::finished: return "finished";
    case End::failed: std::snprintf(text, sizeof text, "stopped with status %d", exit_status); return text;
    case End::crashed: return std::string("crashed (") + ::strsignal(signal_number) + ")";
    case End::out_of_time:
      std::snprintf(text, sizeof text, "was stopped at its time budget (%.0f s of CPU time, %.0f s elapsed)",
                    budget.cpu_seconds, budget.wall_seconds);
      return text;
    case End::out_of_memory:
      std::snprintf(text, sizeof text, "was stopped at its memory budget (%.3g GB)", budget.memory_bytes / 1e9);
      return text;
  }
  return "ended";
}

ChildOutcome run_in_child(const std::function<void(int result_fd)>& work, const ChildBudget& budget,
                          const std::function<void(std::string_view bytes)>& on_bytes) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
    throw Error(std::string("cannot make a pipe for a child process: ") + std::strerror(errno));
  const MemoryUse at_fork = memory_of("self");
  const pid_t parent = ::getpid();
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    const int error = errno;
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw Error(std::string("cannot start a child process: ") + std::strerror(error));
  }
  if (child == 0) {
    ::close(pipe_fds[0]);
    be_the_child(work, pipe_fds[1], parent, budget, at_fork.virtual_bytes);
  }
  ::close(pipe_fds[1]);

  ChildOutcome outcome;
  const auto start = std::chrono::steady_clock::now();
  const std::string pid = std::to_string(child);
  bool killed_for_memory = false, killed_for_time = false;
  auto watch = [&] {
    // The child starts sharing the parent's pages, so its growth is measured from there.
    const double resident = memory_of(pid).resident_bytes;
    outcome.peak_memory_bytes = std::max(outcome.peak_memory_bytes, resident - at_fork.resident_bytes);
    if (!killed_for_memory && !killed_for_time && resident - at_fork.resident_bytes > budget.memory_bytes) {
      killed_for_memory = true;
      ::kill(child, SIGKILL);
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!killed_for_memory && !killed_for_time && elapsed > budget.wall_seconds) {
      killed_for_time = true;
      ::kill(child, SIGKILL);
    }
  };
  char buffer[1 << 16];
  for (bool open = true; open;) {
    pollfd reader{pipe_fds[0], POLLIN, 0};
    const int ready = ::poll(&reader, 1, 20);
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0) {
      const ssize_t got = ::read(pipe_fds[0], buffer, sizeof buffer);
      if (got > 0) {
        outcome.result.append(buffer, static_cast<std::size_t>(got));
        if (on_bytes) on_bytes(std::string_view(buffer, static_cast<std::size_t>(got)));
      }
      else if (got == 0 || errno != EINTR) open = false;  // end of file: the child closed it or died
    }
    watch();
  }
  ::close(pipe_fds[0]);
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0 && errno != EINTR) throw Error(std::string("lost a child process: ") + std::strerror(errno));
    watch();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (killed_for_memory) {
    outcome.end = ChildOutcome::End::out_of_memory;
  } else if (killed_for_time) {
    outcome.end = ChildOutcome::End::out_of_time;
  } else if (WIFSIGNALED(status)) {
    outcome.signal_number = WTERMSIG(status);
    // SIGXCPU at the soft CPU limit: the budget, not a crash.
    outcome.end = outcome.signal_number == SIGXCPU ? ChildOutcome::End::out_of_time : ChildOutcome::End::crashed;
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    outcome.end = ChildOutcome::End::finished;
  } else {
    outcome.end = ChildOutcome::End::failed;
    outcome.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  return outcome;
}

}  // namespace stengmc
