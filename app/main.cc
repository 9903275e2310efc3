// The `allanlab` command: one binary, one subcommand per job.
#include "app/commands/cli.h"
#include "app/input/heap_tuning.h"
#include "experiments/mpi_world.h"

int main(int argc, char** argv) {
  allanlab::app::KeepFreedMemoryInHeap();
  // MPI only when started by mpirun (and built with MPI); a no-op otherwise.
  allanlab::experiments::MpiSession mpi(&argc, &argv);
  return allanlab::app::RunCli(argc, argv);
}
