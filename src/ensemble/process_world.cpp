#include "ensemble/process_world.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#ifdef STENGMC_WITH_MPI
#include <mpi.h>
#endif

#include "core/error.hpp"

namespace stengmc {

namespace {
ProcessWorld world_{};
}  // namespace

ProcessWorld process_world() { return world_; }

bool built_with_mpi() {
#ifdef STENGMC_WITH_MPI
  return true;
#else
  return false;
#endif
}

bool launched_by_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

int launcher_process_count() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* size = std::getenv(name)) return std::max(1, std::atoi(size));
  return 1;
}

MpiSession::MpiSession([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv) {
#ifdef STENGMC_WITH_MPI
  if (!launched_by_mpi_launcher()) return;
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS)
    throw Error("MPI_Init_thread failed: cannot start the MPI run");
  started_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_.size);
  if (provided < MPI_THREAD_MULTIPLE && world_.size > 1) {
    if (world_.rank == 0)
      std::fprintf(stderr, "stengmc: error: this MPI library does not provide MPI_THREAD_MULTIPLE, which the "
                           "distributed ensemble needs (every thread of a worker talks to rank 0); run one process "
                           "per node with threads, or use an MPI built with thread support (Debian's OpenMPI is)\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
#endif
}

MpiSession::~MpiSession() {
#ifdef STENGMC_WITH_MPI
  if (started_) MPI_Finalize();
#endif
}

void abort_every_process(int exit_code) {
  std::fflush(stdout);
  std::fflush(stderr);
#ifdef STENGMC_WITH_MPI
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (initialised && !finalised) MPI_Abort(MPI_COMM_WORLD, exit_code);
#endif
  std::exit(exit_code);
}

}  // namespace stengmc
