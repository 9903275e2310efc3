#include "experiments/mpi_world.h"

#include <cstdlib>

#ifdef ALLANLAB_WITH_MPI
#include <dlfcn.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "experiments/mpi_module_api.h"
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

// The loaded module (mpi_module_api.h), or null: loaded by MpiSession only.
const AllanlabMpiApi* module_api = nullptr;

// The module beside the running program first (a copied or installed build), then where this
// build made it.
const AllanlabMpiApi* LoadModule(std::string* why) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  std::vector<std::string> tried;
  if (!error) tried.push_back((self.parent_path() / ALLANLAB_MPI_MODULE_NAME).string());
  if (tried.empty() || tried.front() != ALLANLAB_MPI_MODULE_PATH) tried.emplace_back(ALLANLAB_MPI_MODULE_PATH);
  for (const std::string& path : tried) {
    if (!std::filesystem::exists(path, error)) continue;
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr) {
      *why = path + ": " + dlerror();
      return nullptr;
    }
    const auto entry = reinterpret_cast<const AllanlabMpiApi* (*)()>(dlsym(handle, "allanlab_mpi_api"));
    const AllanlabMpiApi* api = entry != nullptr ? entry() : nullptr;
    if (api == nullptr || api->version != kAllanlabMpiApiVersion) {
      *why = path + ": not this build's MPI module";
      return nullptr;
    }
    return api;
  }
  *why = "not found (looked for " + tried.front() + (tried.size() > 1 ? " and " + tried.back() : "") + ")";
  return nullptr;
}

bool Active() { return module_api != nullptr && module_api->active(); }
}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) {
  if (!LaunchedByMpi()) return;
  std::string why;
  module_api = LoadModule(&why);
  if (module_api == nullptr) {
    std::fprintf(stderr, "allanlab: started by mpirun, but the MPI module %s could not be loaded: %s\n",
                 ALLANLAB_MPI_MODULE_NAME, why.c_str());
    std::exit(1);
  }
  if (!module_api->active()) initialised_ = module_api->init(argc, argv) != 0;
}

MpiSession::~MpiSession() {
  if (initialised_ && Active()) module_api->finalize();
}

RankInfo CurrentRanks() {
  RankInfo info;
  if (!Active()) return info;
  module_api->rank_and_size(&info.rank, &info.size);
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
  if (!module_api->gather_u64(size, sizes.data())) {
    *why = "MPI_Gather of row sizes failed";
    return false;
  }
  constexpr std::uint64_t kChunk = 1 << 30;
  static_assert(kChunk <= INT_MAX);
  if (ranks.rank != 0) {
    for (std::uint64_t off = 0; off < size; off += kChunk) {
      const int n = static_cast<int>(std::min(kChunk, size - off));
      if (!module_api->send_bytes(bytes.data() + off, n, 0, 7)) {
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
      if (!module_api->receive_bytes(in.data() + off, n, r, 7)) {
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
  int all = 0;
  module_api->all_and(ok ? 1 : 0, &all);
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
