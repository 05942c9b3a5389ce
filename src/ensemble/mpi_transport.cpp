// The MPI module (libstengmc_mpi.so): ProcessTransport over MPI_COMM_WORLD. Built as a
// CMake MODULE of its own, the only code of stengmc that includes <mpi.h> or links MPI;
// the executable opens it when an MPI launcher started it (ensemble/mpi_module.cpp).
// Everything but the entry point is hidden (CXX_VISIBILITY_PRESET hidden).
#include <mpi.h>

#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include "ensemble/process_transport.hpp"

namespace stengmc {
namespace {

class MpiTransport final : public ProcessTransport {
 public:
  bool start(int& argc, char**& argv, Started& started) override {
    int provided = 0;
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS) return false;
    MPI_Comm_rank(MPI_COMM_WORLD, &started.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &started.size);
    started.thread_multiple = provided >= MPI_THREAD_MULTIPLE;
    return true;
  }

  void finish() override { MPI_Finalize(); }

  bool active() override {
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    return initialised && !finalised;
  }

  void send(std::string_view bytes, int destination, int tag) override {
    if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::length_error("a message of " + std::to_string(bytes.size()) +
                              " bytes is too large for one MPI message (2 GiB)");
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, destination, tag, MPI_COMM_WORLD);
  }

  bool try_receive(int source, int tag, std::string& bytes, int& from) override {
    // Probe and receive as one matched message: a plain MPI_Iprobe + MPI_Recv would let
    // another thread take the probed message in between.
    int flag = 0;
    MPI_Message message;
    MPI_Status status;
    MPI_Improbe(source == ANY_PROCESS ? MPI_ANY_SOURCE : source, tag, MPI_COMM_WORLD, &flag, &message, &status);
    if (!flag) return false;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    bytes.resize(static_cast<std::size_t>(count));
    MPI_Mrecv(bytes.data(), count, MPI_BYTE, &message, MPI_STATUS_IGNORE);
    from = status.MPI_SOURCE;
    return true;
  }

  void gather_to_root(int value, int* values) override {
    MPI_Gather(&value, 1, MPI_INT, values, 1, MPI_INT, 0, MPI_COMM_WORLD);
  }

  [[noreturn]] void abort(int exit_code) override {
    MPI_Abort(MPI_COMM_WORLD, exit_code);
    std::abort();  // MPI_Abort does not return; the standard does not promise it
  }
};

MpiTransport transport;

}  // namespace
}  // namespace stengmc

// Named PROCESS_TRANSPORT_ENTRY (ensemble/process_transport.hpp).
extern "C" __attribute__((visibility("default"))) stengmc::ProcessTransport* stengmc_process_transport(
    int interface_version) {
  return interface_version == stengmc::PROCESS_TRANSPORT_INTERFACE_VERSION ? &stengmc::transport : nullptr;
}
