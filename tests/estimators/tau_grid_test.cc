#include "estimators/tau_grid.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace allanlab::estimators {
namespace {

using Ms = std::vector<std::int64_t>;

TauGridOptions Grid(TauGridKind kind) {
  TauGridOptions grid;
  grid.kind = kind;
  return grid;
}

TEST(TauGrid, OctaveIsPowersOfTwoUpToTheLimit) {
  EXPECT_EQ(CandidateAveragingFactors(Grid(TauGridKind::kOctave), 1.0, 100),
            (Ms{1, 2, 4, 8, 16, 32, 64}));
  EXPECT_EQ(CandidateAveragingFactors(Grid(TauGridKind::kOctave), 1.0, 64),
            (Ms{1, 2, 4, 8, 16, 32, 64}));
  EXPECT_EQ(CandidateAveragingFactors(Grid(TauGridKind::kOctave), 1.0, 1), (Ms{1}));
  EXPECT_TRUE(CandidateAveragingFactors(Grid(TauGridKind::kOctave), 1.0, 0).empty());
  // No overflow at the top of the range.
  const Ms huge = CandidateAveragingFactors(Grid(TauGridKind::kOctave), 1.0,
                                            std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(huge.size(), 63u);
}

TEST(TauGrid, DecadeIsOneTwoFive) {
  EXPECT_EQ(CandidateAveragingFactors(Grid(TauGridKind::kDecade125), 1.0, 600),
            (Ms{1, 2, 5, 10, 20, 50, 100, 200, 500}));
  EXPECT_EQ(CandidateAveragingFactors(Grid(TauGridKind::kDecade125), 1.0, 4), (Ms{1, 2}));
  EXPECT_FALSE(CandidateAveragingFactors(Grid(TauGridKind::kDecade125), 1.0,
                                         std::numeric_limits<std::int64_t>::max())
                   .empty());
}

TEST(TauGrid, LogDenseRoundsToDistinctIntegers) {
  TauGridOptions grid = Grid(TauGridKind::kLogDense);
  grid.points_per_decade = 10;
  EXPECT_EQ(CandidateAveragingFactors(grid, 1.0, 100),
            (Ms{1, 2, 3, 4, 5, 6, 8, 10, 13, 16, 20, 25, 32, 40, 50, 63, 79, 100}));
  grid.points_per_decade = 1;
  EXPECT_EQ(CandidateAveragingFactors(grid, 1.0, 99999), (Ms{1, 10, 100, 1000, 10000}));
}

TEST(TauGrid, AllIsEveryFactor) {
  EXPECT_EQ(CandidateAveragingFactors(Grid(TauGridKind::kAll), 1.0, 5), (Ms{1, 2, 3, 4, 5}));
}

TEST(TauGrid, ExplicitTausRoundMergeAndKeepZero) {
  TauGridOptions grid = Grid(TauGridKind::kExplicit);
  grid.explicit_taus_s = {0.5, 0.26, 0.24, 0.1, 0.01, 2.0, 100.0};
  // tau0 = 0.1 s: 5, 3 (0.26 -> 2.6), 2 (2.4), 1, 0 (0.1 -> m = 0), 20, 1000 > limit.
  EXPECT_EQ(CandidateAveragingFactors(grid, 0.1, 999), (Ms{0, 1, 2, 3, 5, 20}));
  grid.explicit_taus_s = {1.0, 1.04, 0.96};
  EXPECT_EQ(CandidateAveragingFactors(grid, 0.1, 999), (Ms{10}));
}

TEST(TauGrid, ParsesEveryDocumentedForm) {
  TauGridOptions grid;
  std::string why;
  ASSERT_TRUE(TauGridOptions::Parse("octave", &grid, &why)) << why;
  EXPECT_EQ(grid.kind, TauGridKind::kOctave);
  ASSERT_TRUE(TauGridOptions::Parse("decade", &grid, &why)) << why;
  EXPECT_EQ(grid.kind, TauGridKind::kDecade125);
  ASSERT_TRUE(TauGridOptions::Parse("all", &grid, &why)) << why;
  EXPECT_EQ(grid.kind, TauGridKind::kAll);
  ASSERT_TRUE(TauGridOptions::Parse("dense:7", &grid, &why)) << why;
  EXPECT_EQ(grid.kind, TauGridKind::kLogDense);
  EXPECT_EQ(grid.points_per_decade, 7);
  ASSERT_TRUE(TauGridOptions::Parse("0.01, 1,10.5,2e3", &grid, &why)) << why;
  EXPECT_EQ(grid.kind, TauGridKind::kExplicit);
  EXPECT_EQ(grid.explicit_taus_s, (std::vector<double>{0.01, 1.0, 10.5, 2000.0}));
  ASSERT_TRUE(TauGridOptions::Parse("3", &grid, &why)) << why;
  EXPECT_EQ(grid.explicit_taus_s, (std::vector<double>{3.0}));
}

TEST(TauGrid, RejectsMalformedTextAndKeepsTheOldGrid) {
  for (const char* bad : {"", "octaves", "dense:", "dense:0", "dense:x", "dense:2.5", "1,,2",
                          "1,abc", "-1", "0", "1,inf", "nan", "1e999"}) {
    TauGridOptions grid;
    grid.kind = TauGridKind::kAll;
    std::string why;
    EXPECT_FALSE(TauGridOptions::Parse(bad, &grid, &why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
    EXPECT_EQ(grid.kind, TauGridKind::kAll) << bad;
  }
  TauGridOptions grid;
  std::string why;
  EXPECT_FALSE(TauGridOptions::Parse("1,abc", &grid, &why));
  EXPECT_NE(why.find("'abc' is not a number"), std::string::npos) << why;
}

TEST(TauGrid, ValidityNamesTheProblem) {
  std::string why;
  EXPECT_TRUE(Grid(TauGridKind::kOctave).IsValid(&why));
  TauGridOptions dense = Grid(TauGridKind::kLogDense);
  dense.points_per_decade = 0;
  EXPECT_FALSE(dense.IsValid(&why));
  EXPECT_NE(why.find("points per decade"), std::string::npos) << why;
  TauGridOptions listed = Grid(TauGridKind::kExplicit);
  EXPECT_FALSE(listed.IsValid(&why));
  listed.explicit_taus_s = {1.0, -2.0};
  EXPECT_FALSE(listed.IsValid(&why));
  EXPECT_NE(why.find("-2"), std::string::npos) << why;
}

}  // namespace
}  // namespace allanlab::estimators
