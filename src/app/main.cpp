// stengmc: the command line. It parses, calls the library, prints, and is the only
// place that catches errors and chooses the exit code:
//   0 success, 1 unexpected failure, 2 bad input (study, file or command line),
//   3 the model left its domain of validity (x reaching l under policy `error`, integrator failure).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <vector>

#include "app/commands.hpp"
#include "core/build_info.hpp"
#include "core/creation_time.hpp"
#include "core/error.hpp"
#include "core/huge_page_heap.hpp"
#include "ensemble/process_world.hpp"

namespace {

[[nodiscard]] int fail(const char* kind, const char* what, int code) {
  std::fflush(stdout);  // what was printed so far stays ahead of the error in a combined log
  const stengmc::ProcessWorld world = stengmc::process_world();
  if (!world.distributed()) {
    std::fprintf(stderr, "stengmc: %s: %s\n", kind, what);
    return code;
  }
  // In an MPI run one rank's error ends the job at once: the others would wait for it forever.
  if (world.root()) std::fprintf(stderr, "stengmc: %s: %s\n", kind, what);
  else std::fprintf(stderr, "stengmc (rank %d): %s: %s\n", world.rank, kind, what);
  stengmc::abort_every_process(code);
}

//! In an MPI launch only `run` of an ensemble is distributed; another command would run P
//! times over the same output.
bool refused_under_mpi(int argc, char** argv) {
  const stengmc::ProcessWorld world = stengmc::process_world();
  if (!world.distributed() || argc < 2 || argv[1][0] == '-') return false;
  if (const std::string_view command = argv[1]; command == "run" || command == "calibrate") return false;
  if (world.root())
    std::fprintf(stderr, "stengmc: input error: `stengmc %s` under an MPI launch of %d processes: only `stengmc run` of "
                         "an [ensemble] study and `stengmc calibrate` are distributed over processes; run this command "
                         "without mpirun\n",
                 argv[1], world.size);
  return true;
}

//! A build without MPI started by mpirun with several processes: each would run the whole
//! study over the same output (they would meet at its journal). Refused with the way out.
bool refused_without_mpi() {
  const int processes = stengmc::launcher_process_count();
  if (stengmc::built_with_mpi() || processes <= 1) return false;
  std::fprintf(stderr, "stengmc: input error: this stengmc was built without MPI (STENGMC_WITH_MPI=OFF) but was "
                       "started as one of %d processes: each would run the whole study. Rebuild with MPI (Debian: "
                       "libopenmpi-dev), run one process with threads (-j), or split the work with --shard i/n and "
                       "stengmc merge\n",
               processes);
  return true;
}

//! Ends the process once everything it wrote is closed and flushed, without the destructors
//! of static objects and the atexit handlers: HDF5's clean-up alone frees each structure of
//! the library one by one, ~0.5 ms of a single run, just before the system drops the whole
//! address space. Files are closed by then (their writers are scoped in the commands) and
//! MPI is finalised (its session is scoped in run_command_line). The sanitizer build exits
//! normally: LeakSanitizer reports at exit.
[[noreturn]] void end_process(int code) {
  std::fflush(nullptr);
#if defined(__SANITIZE_ADDRESS__)
  std::exit(code);
#else
  std::_Exit(code);
#endif
}

int run_command_line(int argc, char** argv) {
  std::optional<stengmc::MpiSession> mpi;
  try {
    mpi.emplace(argc, argv);  // only when an MPI launcher started us
  } catch (const std::exception& e) {
    // No MPI run to end: every rank reports and exits, and the launcher ends the job.
    std::fprintf(stderr, "stengmc: error: %s\n", e.what());
    return 1;
  }
  if (refused_without_mpi()) return 2;
  if (refused_under_mpi(argc, argv)) stengmc::abort_every_process(2);
  CLI::App app{"stengmc: Monte Carlo studies of sliding triboelectric sensors (S-TENG) on rough surfaces.\n"
               "Every quantity is in SI units. Model: docs/model.md; file layouts: docs/study-files.md, docs/output-files.md.\n"
               "Exit codes: 0 ok, 2 bad input, 3 model out of its validity domain, 1 other failure."};
  app.set_version_flag("--version", std::string("stengmc ") + stengmc::program_version() + " (git " +
                                        stengmc::git_revision() + ")");
  app.require_subcommand(1);
  stengmc::app::add_run_command(app);
  stengmc::app::add_circuit_command(app);
  stengmc::app::add_spectrum_command(app);
  stengmc::app::add_surface_command(app);
  stengmc::app::add_plot_command(app);
  stengmc::app::add_calibrate_command(app);
  stengmc::app::add_invert_command(app);
  stengmc::app::add_track_command(app);
  stengmc::app::add_merge_command(app);
  stengmc::app::add_status_command(app);
  stengmc::app::add_export_netlist_command(app);
  if (argc == 1) {  // bare `stengmc`: what it can do, not a usage error
    std::printf("%s", app.help().c_str());
    return 0;
  }
  try {
    // A SOURCE_DATE_EPOCH that cannot be read is refused before any work, not by the file
    // written at the end of a long run; asking for help or the version writes no file.
    const std::vector<std::string> arguments(argv + 1, argv + argc);
    const bool writes_nothing = std::any_of(arguments.begin(), arguments.end(), [](const std::string& a) {
      return a == "-h" || a == "--help" || a == "--version";
    });
    if (!writes_nothing) static_cast<void>(stengmc::creation_time_utc());
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with code 0; every real usage error is bad input.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const stengmc::InputError& e) {
    return fail("input error", e.what(), 2);
  } catch (const stengmc::ModelError& e) {
    return fail("model error", e.what(), 3);
  } catch (const std::exception& e) {
    return fail("error", e.what(), 1);
  } catch (...) {
    return fail("error", "unknown failure (please report it with the command line and input files)", 1);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  stengmc::back_the_heap_with_huge_pages();  // before anything allocates much: ~1 000 page faults fewer per run
  end_process(run_command_line(argc, argv));
}
