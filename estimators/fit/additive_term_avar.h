#pragma once
// The expected AVAR of a fit's additive parametric terms (Gauss-Markov, telegraph, harmonic, and
// effects held at an estimate: outliers, bias step, exponential drift), one term at a time and
// cached, for parametric_fit.h's Ceres iterations. A term held fixed (a bias step's AVAR is O(N)
// per tau) or not moved by an evaluation (the other parameters' central differences) is then
// computed once per fit instead of at every evaluation.
//
// Exactness: sim::SensorModel::ExpectedAvar (FlickerBandLimit::kStationaryChange) of base + terms is the left-to-right sum from zero of each
// term's own part (band-limit included), so summing Part(0), Part(1), ... in that order from zero
// gives the same bits as one ModelAvarOnCurve of all of them.
#include <cstddef>
#include <map>
#include <span>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/parametric_term.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {

class AdditiveTermAvar {
 public:
  // `curve` must outlive this object.
  explicit AdditiveTermAvar(const AvarCurve& curve) : curve_(curve) {}

  // E[AVAR] (rad/s)^2 on the curve's taus of `base` (no terms; at most its band-limit) with term
  // `slot` applied at `params` (SI, the term's parameters() order). `band_key` identifies base's
  // band-limit (empty without one; the cutoff otherwise): the cache key is (slot, params,
  // band_key). Returns nullptr when the term's ApplyTo does more than append sim terms (a
  // quantizer or band-limit: not a per-term part) or base has terms; the caller then evaluates
  // the whole model. The pointer is valid until the next call.
  const std::vector<double>* Part(std::size_t slot, const ParametricTerm& term,
                                  std::span<const double> params, const sim::SensorModel& base,
                                  std::span<const double> band_key);

 private:
  const AvarCurve& curve_;
  std::vector<std::map<std::vector<double>, std::vector<double>>> cache_;  // per slot
};

}  // namespace allanlab::estimators
