#pragma once
// The MPI side of a sweep, compiled to single-process stand-ins without MPI
// (ALLANLAB_WITH_MPI off). Ranks only exist when the program was started by mpirun: a plain
// `allanlab sweep` never initialises MPI, nor loads it (the MPI calls are in a module loaded then
// only: experiments/mpi_module_api.h).
#include <string>
#include <vector>

#include "experiments/runner.h"

namespace allanlab::experiments {

struct RankInfo {
  int rank = 0;
  int size = 1;
};

// Initialises MPI when launched by mpirun (and built with MPI); finalises on destruction. Exits
// the process with an error message when launched by mpirun but the MPI module cannot be loaded.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

 private:
  bool initialised_ = false;
};

// This process's rank and the world size ({0, 1} when MPI is absent or not initialised).
RankInfo CurrentRanks();

// Moves every rank's rows to rank 0 (appended to its own); other ranks end with none.
// Collective: every rank must call it. Returns false on a communication error.
bool GatherRowsToRoot(std::vector<TrialRow>* rows, std::string* why);
// Logical AND of `ok` over the ranks (collective); `ok` itself without MPI.
bool AllRanksOk(bool ok);

}  // namespace allanlab::experiments
