#pragma once
// The GLS covariance models of the curves a diagnosis fits, built once per curve shape and shared
// by every fit of that shape. A diagnosis fits the record's curve, and each half's, dozens of times
// (baseline, every candidate's refits and their passes, the held-out refits), and the covariance
// model (estimators/fit/avar_covariance.h) depends only on the curve's averaging factors, record
// length and sample period, not on its values; building it was a tenth of a diagnosis's CPU. A
// model built with more terms than a fit uses gives that fit the same bits (the others' weights
// are zero and skipped), so one per shape with every fitted term serves every fit.
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "estimators/fit/avar_covariance.h"
#include "estimators/fit/avar_curve.h"
#include "estimators/fit/noise_coefficient.h"

namespace allanlab::experiments::detail {

class CurveCovariances {
 public:
  // The covariance model of curves shaped like `curve` with `terms`: built on first use (under a
  // lock, so once), then shared. Thread-safe.
  std::shared_ptr<const estimators::AvarCovarianceModel> For(const estimators::AvarCurve& curve,
                                                             const std::vector<estimators::Coefficient>& terms);

 private:
  struct Entry {
    std::int64_t num_samples = 0;
    double period_s = 0.0;
    std::vector<std::int64_t> m;
    std::vector<estimators::Coefficient> terms;
    std::shared_ptr<const estimators::AvarCovarianceModel> model;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
};

}  // namespace allanlab::experiments::detail
