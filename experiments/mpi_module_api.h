#pragma once
// What the MPI module (experiments/mpi_module.cc, built as a separate shared object that links
// the MPI library) offers the program that loads it (experiments/mpi_world.cc). Why a module:
// the MPI libraries cost every run of `allanlab` ~3 ms of dynamic loading (a quarter of its
// start-up), and only a sweep started by mpirun uses them; the module is loaded then only.
// Plain C types across the boundary, so the module and the program need not share a C++ ABI
// beyond the compiler's.
#include <cstdint>

extern "C" {

// Every function returns 1 on success and 0 on failure (an MPI call that did not return
// MPI_SUCCESS), except active.
struct AllanlabMpiApi {
  int version;  // kAllanlabMpiApiVersion
  int (*init)(int* argc, char*** argv);
  int (*finalize)();
  // 1 when MPI is initialised and not finalised.
  int (*active)();
  int (*rank_and_size)(int* rank, int* size);
  // Rank 0 receives every rank's value in rank order (out: `size` values on rank 0, unused
  // elsewhere). Collective.
  int (*gather_u64)(std::uint64_t value, std::uint64_t* out);
  // Point-to-point bytes, at most INT_MAX per call.
  int (*send_bytes)(const unsigned char* data, int count, int destination, int tag);
  int (*receive_bytes)(unsigned char* data, int count, int source, int tag);
  // Logical AND of `ok` over the ranks (collective).
  int (*all_and)(int ok, int* all);
};

inline constexpr int kAllanlabMpiApiVersion = 1;

// The module's one exported symbol.
const AllanlabMpiApi* allanlab_mpi_api();
}
