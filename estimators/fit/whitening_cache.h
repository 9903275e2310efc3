#pragma once
// A GLS fit asks for the whitening of its covariance model Omega(x) at the same x several times:
// the subset choice scores each subset's fit, the goodness of fit whitens the chosen one again, and
// the profile's searches revisit the same held values (their first steps outwards repeat for each
// level and each calibration round). Forming Omega(x) and its Cholesky factor each time was a
// third of the profile's cost. CachedWhitening remembers the last results keyed by the exact bits
// of x, so the answer is the one the wrapped function gives, bit for bit.
#include <cstddef>
#include <functional>

#include <Eigen/Dense>

namespace allanlab::estimators {

using WhiteningFunction = std::function<bool(const Eigen::VectorXd& x, Eigen::MatrixXd* w)>;

// `whitening` with its last `capacity` answers (failures included) kept; copies of the result
// share them. Safe to call from several threads. Precondition: `whitening` depends on x alone.
WhiteningFunction CachedWhitening(WhiteningFunction whitening, std::size_t capacity = 256);

}  // namespace allanlab::estimators
