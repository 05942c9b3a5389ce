#include "ensemble/process_world.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/error.hpp"
#include "ensemble/mpi_module.hpp"
#include "ensemble/process_transport.hpp"

namespace stengmc {

namespace {
ProcessWorld world_{};
ProcessTransport* transport_ = nullptr;  //!< the started transport; null in a single process
}  // namespace

ProcessWorld process_world() { return world_; }

ProcessTransport& process_transport() {
  if (transport_ == nullptr)
    throw Error(built_with_mpi() ? "no MPI run was started: only an MPI launch distributes realisations"
                                 : "this stengmc was built without MPI (STENGMC_WITH_MPI=OFF)");
  return *transport_;
}

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

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!built_with_mpi() || !launched_by_mpi_launcher()) return;
  ProcessTransport& transport = load_mpi_module();
  ProcessTransport::Started started;
  if (!transport.start(argc, argv, started)) throw Error("MPI_Init_thread failed: cannot start the MPI run");
  transport_ = &transport;
  started_ = true;
  world_ = {started.rank, started.size};
  if (!started.thread_multiple && world_.size > 1) {
    if (world_.rank == 0)
      std::fprintf(stderr, "stengmc: error: this MPI library does not provide MPI_THREAD_MULTIPLE, which the "
                           "distributed ensemble needs (every thread of a worker talks to rank 0); run one process "
                           "per node with threads, or use an MPI built with thread support (Debian's OpenMPI is)\n");
    transport.abort(1);
  }
}

MpiSession::~MpiSession() {
  if (started_) transport_->finish();
}

void abort_every_process(int exit_code) {
  std::fflush(stdout);
  std::fflush(stderr);
  if (transport_ != nullptr && transport_->active()) transport_->abort(exit_code);
  std::exit(exit_code);
}

}  // namespace stengmc
