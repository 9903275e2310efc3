// The `allanlab` command: one binary, one subcommand per job.
#include "app/cli.h"
#include "app/heap_tuning.h"
#include "experiments/mpi_world.h"

int main(int argc, char** argv) {
  allanlab::app::KeepFreedMemoryInHeap();
  // MPI only when started by mpirun (and built with MPI); a no-op otherwise.
  allanlab::experiments::MpiSession mpi(&argc, &argv);
  return allanlab::app::RunCli(argc, argv);
}
