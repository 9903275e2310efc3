// The MPI module (experiments/mpi_module_api.h): each entry a thin call into the MPI library.
#include <mpi.h>

#include "experiments/mpi_module_api.h"

namespace {

int Init(int* argc, char*** argv) {
  int provided = 0;
  return MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) == MPI_SUCCESS;
}

int Finalize() { return MPI_Finalize() == MPI_SUCCESS; }

int Active() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

int RankAndSize(int* rank, int* size) {
  return MPI_Comm_rank(MPI_COMM_WORLD, rank) == MPI_SUCCESS && MPI_Comm_size(MPI_COMM_WORLD, size) == MPI_SUCCESS;
}

int GatherU64(std::uint64_t value, std::uint64_t* out) {
  return MPI_Gather(&value, 1, MPI_UINT64_T, out, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD) == MPI_SUCCESS;
}

int SendBytes(const unsigned char* data, int count, int destination, int tag) {
  return MPI_Send(data, count, MPI_UNSIGNED_CHAR, destination, tag, MPI_COMM_WORLD) == MPI_SUCCESS;
}

int ReceiveBytes(unsigned char* data, int count, int source, int tag) {
  return MPI_Recv(data, count, MPI_UNSIGNED_CHAR, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE) == MPI_SUCCESS;
}

int AllAnd(int ok, int* all) {
  return MPI_Allreduce(&ok, all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD) == MPI_SUCCESS;
}

constexpr AllanlabMpiApi kApi = {kAllanlabMpiApiVersion, Init, Finalize, Active, RankAndSize,
                                 GatherU64, SendBytes, ReceiveBytes, AllAnd};

}  // namespace

extern "C" __attribute__((visibility("default"))) const AllanlabMpiApi* allanlab_mpi_api() { return &kApi; }
