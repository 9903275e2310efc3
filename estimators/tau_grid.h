#pragma once
// Averaging-time grids. A grid proposes averaging factors m = tau / tau0; the estimator then keeps
// those with enough terms and reports the others as dropped, with the reason.
#include <cstdint>
#include <string>
#include <vector>

namespace allanlab::estimators {

enum class TauGridKind {
  kOctave,     // m = 1, 2, 4, 8, ...
  kDecade125,  // m = 1, 2, 5, 10, 20, 50, ...
  kLogDense,   // k points per decade, rounded to distinct integers
  kAll,        // every m (O(N^2) overall: never a default)
  kExplicit,   // the taus the user listed (rounded to the nearest m, duplicates merged)
};

struct TauGridOptions {
  TauGridKind kind = TauGridKind::kOctave;
  int points_per_decade = 10;           // kLogDense only
  std::vector<double> explicit_taus_s;  // kExplicit only, in seconds, > 0
  // Parses "octave", "decade", "dense:K", "all" or a comma list of taus in seconds.
  static bool Parse(const std::string& text, TauGridOptions* grid, std::string* why);
  bool IsValid(std::string* why) const;
};

// Candidate averaging factors for a sample period tau0_s, up to max_m inclusive, ascending and
// distinct. Explicit taus that round to m = 0 come back as m = 0 so the caller can report them.
std::vector<std::int64_t> CandidateAveragingFactors(const TauGridOptions& grid, double tau0_s,
                                                    std::int64_t max_m);

}  // namespace allanlab::estimators
