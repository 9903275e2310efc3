// PieceSharing runs every piece once, in the caller and one helper, whether the caller waits for
// them (Run) or works meanwhile and joins them later (Start, Finish).
#include "common/piece_sharing.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace allanlab {
namespace {

TEST(PieceSharingTest, RunTakesEveryPieceOnce) {
  PieceSharing sharing;
  std::vector<std::atomic<int>> runs(1000);
  sharing.Run(1000, [&](int p) { runs[static_cast<std::size_t>(p)].fetch_add(1); });
  for (const std::atomic<int>& r : runs) EXPECT_EQ(r.load(), 1);
}

TEST(PieceSharingTest, StartedPiecesAllRunByFinish) {
  PieceSharing sharing;
  for (int round = 0; round < 50; ++round) {
    std::vector<std::atomic<int>> runs(64);
    sharing.Start(64, [&runs](int p) { runs[static_cast<std::size_t>(p)].fetch_add(1); });
    long own = 0;  // the caller's own work meanwhile
    for (int k = 0; k < 1000 * round; ++k) own += k % 7;
    sharing.Finish();
    for (const std::atomic<int>& r : runs) EXPECT_EQ(r.load(), 1) << "round " << round << ", own " << own;
  }
}

// A started run is finished by the next Start, by Run and by the destructor.
TEST(PieceSharingTest, StartedRunsAreFinishedBeforeTheNext) {
  std::vector<std::atomic<int>> first(32), second(32), third(32);
  {
    PieceSharing sharing;
    sharing.Start(32, [&first](int p) { first[static_cast<std::size_t>(p)].fetch_add(1); });
    sharing.Start(32, [&first, &second](int p) {
      for (const std::atomic<int>& r : first) EXPECT_EQ(r.load(), 1);
      second[static_cast<std::size_t>(p)].fetch_add(1);
    });
    sharing.Run(32, [&second](int) {
      for (const std::atomic<int>& r : second) EXPECT_EQ(r.load(), 1);
    });
    sharing.Start(32, [&third](int p) { third[static_cast<std::size_t>(p)].fetch_add(1); });
  }
  for (const std::atomic<int>& r : third) EXPECT_EQ(r.load(), 1);
}

}  // namespace
}  // namespace allanlab
