#include "experiments/mpi_world.h"

#include <cstdlib>

#ifdef ALLANLAB_WITH_MPI
#include <mpi.h>

#include <cstdint>

#include "experiments/row_codec.h"
#endif

namespace allanlab::experiments {

#ifdef ALLANLAB_WITH_MPI

namespace {
// Set by mpirun / srun; without them the process was not started as a rank.
bool LaunchedByMpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}
bool Active() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}
}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) {
  if (LaunchedByMpi() && !Active()) {
    int provided = 0;
    initialised_ = MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) == MPI_SUCCESS;
  }
}

MpiSession::~MpiSession() {
  if (initialised_ && Active()) MPI_Finalize();
}

RankInfo CurrentRanks() {
  RankInfo info;
  if (!Active()) return info;
  MPI_Comm_rank(MPI_COMM_WORLD, &info.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &info.size);
  return info;
}

bool GatherRowsToRoot(std::vector<TrialRow>* rows, std::string* why) {
  const RankInfo ranks = CurrentRanks();
  if (ranks.size == 1) return true;
  std::vector<unsigned char> bytes;
  EncodeRows(*rows, &bytes);
  // Sizes first (as 64-bit counts), then the bytes in chunks below INT_MAX.
  const std::uint64_t size = bytes.size();
  std::vector<std::uint64_t> sizes(ranks.rank == 0 ? ranks.size : 0);
  if (MPI_Gather(&size, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD) !=
      MPI_SUCCESS) {
    *why = "MPI_Gather of row sizes failed";
    return false;
  }
  constexpr std::uint64_t kChunk = 1 << 30;
  if (ranks.rank != 0) {
    for (std::uint64_t off = 0; off < size; off += kChunk) {
      const int n = static_cast<int>(std::min(kChunk, size - off));
      if (MPI_Send(bytes.data() + off, n, MPI_UNSIGNED_CHAR, 0, 7, MPI_COMM_WORLD) != MPI_SUCCESS) {
        *why = "MPI_Send of rows failed";
        return false;
      }
    }
    rows->clear();
    return true;
  }
  for (int r = 1; r < ranks.size; ++r) {
    std::vector<unsigned char> in(sizes[r]);
    for (std::uint64_t off = 0; off < sizes[r]; off += kChunk) {
      const int n = static_cast<int>(std::min(kChunk, sizes[r] - off));
      if (MPI_Recv(in.data() + off, n, MPI_UNSIGNED_CHAR, r, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE) !=
          MPI_SUCCESS) {
        *why = "MPI_Recv of rows failed";
        return false;
      }
    }
    if (!DecodeRows(in, rows)) {
      *why = "rows received from rank " + std::to_string(r) + " are damaged";
      return false;
    }
  }
  return true;
}

bool AllRanksOk(bool ok) {
  if (CurrentRanks().size == 1) return ok;
  int mine = ok ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  return all != 0;
}

#else

MpiSession::MpiSession(int* /*argc*/, char*** /*argv*/) {}
MpiSession::~MpiSession() = default;
RankInfo CurrentRanks() { return {}; }
bool GatherRowsToRoot(std::vector<TrialRow>* /*rows*/, std::string* /*why*/) { return true; }
bool AllRanksOk(bool ok) { return ok; }

#endif

}  // namespace allanlab::experiments
