#pragma once
// Whether every value of a block is finite, in one vectorised pass: the readers check each
// block of a record before they keep it, and at 10^7 samples a per-value std::isfinite loop
// (not vectorised: a boolean reduction) cost as much as the Allan pass's integration.
#include <span>

namespace allanlab {

bool AllFinite(std::span<const double> values);

}  // namespace allanlab
