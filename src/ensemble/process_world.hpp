#pragma once
//! The processes of one run: a single process, or the ranks of an MPI launch (mpirun,
//! srun). MPI is optional at build time (CMake option STENGMC_WITH_MPI) and at run time:
//! it is started only when the environment says an MPI launcher started this process, so
//! a plain `stengmc ...` of an MPI-enabled build behaves exactly as a build without MPI
//! (docs/cluster.md). MPI itself is in a module opened only then (ensemble/mpi_module.hpp):
//! the executable does not link it.
#include <string>

namespace stengmc {

class ProcessTransport;

struct ProcessWorld {
  int rank = 0;  //!< this process's rank (0: the one that journals and writes)
  int size = 1;  //!< processes in the run
  [[nodiscard]] bool distributed() const { return size > 1; }
  [[nodiscard]] bool root() const { return rank == 0; }
};

//! MPI_COMM_WORLD's rank and size once an MpiSession started MPI; {0, 1} otherwise.
ProcessWorld process_world();

//! True when this build can use MPI (STENGMC_WITH_MPI).
bool built_with_mpi();

//! True when an MPI launcher started this process: OpenMPI's mpirun (OMPI_COMM_WORLD_SIZE)
//! or a PMI/PMIx launch such as Slurm's srun (PMIX_RANK, PMI_SIZE).
bool launched_by_mpi_launcher();

//! How many processes the launcher says it started (OMPI_COMM_WORLD_SIZE or PMI_SIZE), 1
//! when none says so; readable without MPI, so a build without it can tell it was launched.
int launcher_process_count();

//! The messages between the processes of the run MpiSession started.
//! @throws Error when it started none (a single process; a build without MPI)
ProcessTransport& process_transport();

//! Starts MPI (MPI_THREAD_MULTIPLE: every OpenMP thread of a worker talks to rank 0) when
//! built with it and launched by an MPI launcher, opening the MPI module first; finalises it
//! at the end of the scope.
//! @throws Error when the module does not load (naming its path) or MPI does not start
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

 private:
  bool started_ = false;
};

//! Ends every process of a distributed run with `exit_code` (MPI_Abort): one rank's error
//! must not leave the others waiting for it forever.
[[noreturn]] void abort_every_process(int exit_code);

}  // namespace stengmc
