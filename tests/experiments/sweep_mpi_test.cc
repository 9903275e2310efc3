// `mpirun -np 2 allanlab sweep` writes the same table as one process (trials split over the
// ranks by batch, rows gathered on rank 0 in (point, trial) order). Skipped in builds without MPI.
#include <gtest/gtest.h>
#include <unistd.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/command_test.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

#ifdef ALLANLAB_MPIEXEC
int Shell(const std::string& command, const fs::path& dir) {
  std::ostringstream full;
  full << command << " > '" << (dir / "out.txt").string() << "' 2> '" << (dir / "err.txt").string()
       << "'";
  const int status = std::system(full.str().c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
#endif

TEST(SweepMpi, TwoRanksGiveTheTableOfOneProcess) {
#ifndef ALLANLAB_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  fs::path dir = fs::temp_directory_path() / "allanlab_sweep_mpi_";
  dir += std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "spec.yaml")
      << "name: mpi\ndriver: avar_bias\nseed: 4\ntrials: 45\n"
         "sensor: {model: {name: m, sample_rate: 100 Hz, terms: [{type: arw, N: 0.1 deg/sqrt(h)}, "
         "{type: bias_instability, B: 1 deg/h}]}}\n"
         "record: {samples: 4096}\nestimators: [overlapping, nonoverlapping]\n"
         "sweep: {parameters: [{path: 'sensor.terms[1].B', values: [1 deg/h, 2 deg/h, 3 "
         "deg/h]}]}\n";
  const std::string spec = (dir / "spec.yaml").string();
  std::ostringstream one;
  one << ALLANLAB_BINARY << " sweep " << spec << " --out " << (dir / "one").string()
      << " --threads 2";
  ASSERT_EQ(Shell(one.str(), dir), 0) << testing_support::ReadAll(dir / "err.txt");
  std::ostringstream two;
  two << "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 "
      << ALLANLAB_MPIEXEC << " -np 2 --oversubscribe --allow-run-as-root " << ALLANLAB_BINARY
      << " sweep " << spec << " --out " << (dir / "two").string() << " --batch 7";
  ASSERT_EQ(Shell(two.str(), dir), 0) << testing_support::ReadAll(dir / "err.txt");
  const std::string table = testing_support::ReadAll(dir / "two/mpi.csv");
  EXPECT_NE(table.find("# ranks: 2"), std::string::npos) << table;
  EXPECT_EQ(testing_support::WithoutCommentLines(testing_support::ReadAll(dir / "one/mpi.csv")),
            testing_support::WithoutCommentLines(table));
  // Every rank removed its checkpoint.
  for (const auto& entry : fs::directory_iterator(dir / "two")) {
    EXPECT_EQ(entry.path().string().find("checkpoint"), std::string::npos) << entry.path();
  }
  fs::remove_all(dir);
#endif
}

}  // namespace
}  // namespace allanlab::app
