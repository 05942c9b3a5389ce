#pragma once
// What the benchmark programs share: scratch folders, the ensemble studies they time
// (surfaces/lognormal_count.toml with its count rewritten), medians and log-log slopes,
// CPU clocks, and child processes measured with wait4 (wall time, CPU time, peak memory).
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ensemble/study_file.hpp"

extern char** environ;

namespace bench {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

//! Least-squares slope of log(y) against log(x).
inline double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

//! CPU time of the calling thread [s]: unlike wall time, not inflated by other processes
//! waiting for or holding the machine's cores (cache sharing still shows).
inline double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

//! CPU time the whole machine spent busy so far (all processes, /proc/stat) [s]; 0 if unknown.
inline double machine_busy_seconds() {
  std::ifstream in("/proc/stat");
  std::string cpu;
  double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) || cpu != "cpu") return 0.0;
  return (user + nice + system + irq + softirq + steal) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

//! A scratch folder, removed at exit.
struct ScratchDir {
  fs::path path;
  explicit ScratchDir(const std::string& name) {
    path = fs::temp_directory_path() / ("stengmc_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

//! Ensemble studies over surfaces/lognormal_count.toml with a fixed asperity count: Model 2,
//! v_b = 10 m/s, 100 MHz, domain policy flag, FFT spectra only (Hann, no ESPRIT), no
//! traces kept (the ensemble).
class StudyFactory {
 public:
  StudyFactory(const fs::path& source_dir, const fs::path& scratch)
      : scratch_(scratch), surface_template_(read_text(source_dir / "surfaces" / "lognormal_count.toml")) {
    if (surface_template_.find("\ncount = 4") == std::string::npos)
      throw std::runtime_error("surfaces/lognormal_count.toml no longer has a line 'count = 4'");
  }

  //! The study file's path (written once per parameter set).
  fs::path file(int count, double duration_s, std::uint64_t realisations) const {
    const fs::path surface = scratch_ / ("surface_n" + std::to_string(count) + ".toml");
    if (!fs::exists(surface)) {
      std::string text = surface_template_;
      const std::string from = "\ncount = 4";
      text.replace(text.find(from), from.size(), "\ncount = " + std::to_string(count));
      write_text(surface, text);
    }
    char name[128];
    std::snprintf(name, sizeof name, "study_n%d_T%.6g_R%llu.toml", count, duration_s * 1e6,
                  static_cast<unsigned long long>(realisations));
    const fs::path study = scratch_ / name;
    char duration[32];
    std::snprintf(duration, sizeof duration, "%.17g", duration_s);
    write_text(study, std::string("seed = 1\nduration_s = ") + duration +
                          "\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
                          "[surface]\nfile = \"" + surface.string() +
                          "\"\n[domain]\npolicy = \"flag\"\n[spectrum]\nwindow = \"hann\"\nstart_s = " +
                          (duration_s > 10e-6 ? "5e-6" : "0") +
                          "\nprominence_over_floor = 10\nmin_frequency_hz = 100e3\nhigh_resolution = false\n"
                          "[ensemble]\nrealisations = " + std::to_string(realisations) + "\ntrace_realisations = []\n");
    return study;
  }

  stengmc::StudyFile make(int count, double duration_s, std::uint64_t realisations) const {
    const fs::path path = file(count, duration_s, realisations);
    return stengmc::parse_study_file(read_text(path), path.string(), std::nullopt);
  }

 private:
  fs::path scratch_;
  std::string surface_template_;
};

//! A finished child process.
struct ProcessRun {
  int exit_status = -1;
  double wall_s = 0.0;
  double cpu_s = 0.0;       //!< user + system, the child and its threads
  double max_rss_mb = 0.0;  //!< peak resident memory [MiB] (0: not measured)
};

//! Whether run_process measures the child's peak memory too.
enum class PeakMemory { measured, not_measured };

//! Runs `arguments` (argv[0] is the program) with stdout and stderr to /dev/null. The
//! peak memory comes from GNU time running it (/usr/bin/time, when present): the kernel
//! carries a process's peak over exec, so a child started from this (large) process would
//! report at least this process's own size. GNU time's own start and exit then count in
//! cpu_s (~1.4 ms here): a few-millisecond process is timed with PeakMemory::not_measured.
inline ProcessRun run_process(std::vector<std::string> arguments, PeakMemory memory = PeakMemory::measured) {
  const fs::path memory_file = fs::temp_directory_path() / ("stengmc_rss_" + std::to_string(::getpid()));
  const bool timed = memory == PeakMemory::measured && fs::exists("/usr/bin/time");
  if (timed) arguments.insert(arguments.begin(), {"/usr/bin/time", "-f", "%M", "-o", memory_file.string()});
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const auto start = Clock::now();
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0)
    throw std::runtime_error("cannot start " + arguments.front());
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed for " + arguments.front());
  ProcessRun run;
  run.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
              1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  run.max_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  if (timed) {
    std::ifstream in(memory_file);
    double kib = 0.0;
    if (in >> kib) run.max_rss_mb = kib / 1024.0;
    fs::remove(memory_file);
  }
  return run;
}

}  // namespace bench
