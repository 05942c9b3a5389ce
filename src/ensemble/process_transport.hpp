#pragma once
//! The messages between the processes of a distributed run (docs/cluster.md), behind one
//! small interface: MPI implements it in a module of its own (libstengmc_mpi.so,
//! ensemble/mpi_transport.cpp) that the executable opens only when an MPI launcher started
//! it (ensemble/mpi_module.cpp). Linked instead, MPI's C library and the six it brings
//! (libopen-rte, libopen-pal, hwloc, libevent x2, udev) were mapped and relocated at every
//! start of stengmc, though only a launch by mpirun or srun ever uses them.
//!
//! The module is built with the executable by the same compiler and standard library, so
//! the interface is a C++ class (each links libstdc++ statically, the module's copy hidden:
//! what crosses is a std::string, whose storage both copies take from malloc, and
//! std::length_error, matched by its name as GCC's run time does); the entry point is a C function checked against
//! PROCESS_TRANSPORT_INTERFACE_VERSION, so a module left over from another build is refused
//! instead of called through a table it does not have.
#include <string>
#include <string_view>

namespace stengmc {

//! `source` of ProcessTransport::try_receive: a message from any process.
constexpr int ANY_PROCESS = -1;

class ProcessTransport {
 public:
  //! What start() found.
  struct Started {
    int rank = 0;                 //!< this process's rank in the run
    int size = 1;                 //!< processes in the run
    bool thread_multiple = false; //!< every thread may call send/try_receive concurrently
  };

  virtual ~ProcessTransport() = default;

  //! Starts the run's communication (MPI_Init_thread asking for MPI_THREAD_MULTIPLE); may
  //! remove the launcher's own arguments from argc/argv. False when it cannot start.
  virtual bool start(int& argc, char**& argv, Started& started) = 0;
  //! Ends it (MPI_Finalize); every process calls it once, after its last message.
  virtual void finish() = 0;
  //! Started and not finished yet.
  virtual bool active() = 0;

  //! Sends `bytes` to process `destination` with `tag`; returns once `bytes` may be reused.
  //! Throws std::length_error beyond the transport's largest message (2 GiB for MPI).
  virtual void send(std::string_view bytes, int destination, int tag) = 0;
  //! Takes a waiting message with `tag` from `source` (or ANY_PROCESS), if there is one,
  //! into `bytes`, its sender into `from`; never waits. Safe from several threads at once:
  //! a message is taken by exactly one caller (MPI_Improbe + MPI_Mrecv).
  virtual bool try_receive(int source, int tag, std::string& bytes, int& from) = 0;
  //! Collective: process 0 receives every process's `value` in rank order into `values`
  //! (size ints); `values` is ignored elsewhere.
  virtual void gather_to_root(int value, int* values) = 0;

  //! Ends every process of the run with `exit_code` (MPI_Abort).
  [[noreturn]] virtual void abort(int exit_code) = 0;
};

//! The module's one exported function: its transport when it implements `interface_version`,
//! null otherwise.
using OpenProcessTransport = ProcessTransport* (*)(int interface_version);
constexpr const char* PROCESS_TRANSPORT_ENTRY = "stengmc_process_transport";
//! Changed with every change of ProcessTransport above.
constexpr int PROCESS_TRANSPORT_INTERFACE_VERSION = 1;

}  // namespace stengmc
