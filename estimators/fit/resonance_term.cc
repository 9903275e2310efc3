// The narrowband resonance as a parametric term (parametric_term.h: MakeResonanceTerm).
#include <algorithm>
#include <cmath>
#include <limits>

#include "estimators/fit/parametric_term.h"
#include "sim/resonance.h"
#include "sim/units.h"

namespace allanlab::estimators {
namespace {

double Edf(const AvarCurve& c, std::size_t k) {
  return c.edf.empty() ? std::max(1.0, static_cast<double>(c.num_samples / c.m[k] - 1)) : c.edf[k];
}

class ResonanceTerm final : public ParametricTerm {
 public:
  ResonanceTerm() {
    specs_ = {{"sigma", "rad/s", "deg/h", units::DegPerHour(1.0), 0.0, std::numeric_limits<double>::infinity(), true},
              {"f0", "Hz", "Hz", 1.0, 0.0, std::numeric_limits<double>::infinity(), true},
              {"zeta", "1", "1", 1.0, kResonanceMinDamping, kResonanceMaxDamping, true}};
  }
  std::string_view id() const override { return sim::Resonance::kId; }
  std::string_view short_name() const override { return "RES"; }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  void Bounds(const AvarCurve& c, std::vector<double>* lower, std::vector<double>* upper) const override {
    const auto [lo, hi] = std::minmax_element(c.avar.begin(), c.avar.end());
    *lower = {std::sqrt(*lo) * 1e-4, 0.1 / c.tau_s.back(), kResonanceMinDamping};
    *upper = {std::sqrt(*hi) * 30.0, 0.499 / c.sample_clock.period_s(), kResonanceMaxDamping};
  }
  // The (f0, zeta) on a grid whose exact unit AVAR, scaled by the weighted projection onto the
  // residual (weights nu / (2 AVAR^2)), lowers the weighted SSE most.
  bool InitialGuess(const AvarCurve& c, std::span<const double> residual, const sim::SensorModel&,
                    std::vector<double>* params, std::string* why) const override {
    std::vector<double> lower, upper;
    Bounds(c, &lower, &upper);
    const sim::RecordShape shape{c.num_samples, c.estimator};
    double best = 0.0;
    std::vector<double> best_params;
    for (double f0 = lower[1]; f0 <= upper[1]; f0 *= std::pow(10.0, 1.0 / 20.0)) {
      for (double zeta : {0.01, 0.03, 0.1, 0.3}) {
        const sim::Resonance unit{1.0, f0, zeta};
        double sr = 0.0, ss = 0.0;
        for (std::size_t k = 0; k < c.size(); ++k) {
          const double shape_k = unit.ExpectedAvar(c.m[k], c.sample_clock.period_s(), shape);
          const double w = 0.5 * Edf(c, k) / (c.avar[k] * c.avar[k]);
          sr += w * shape_k * residual[k];
          ss += w * shape_k * shape_k;
        }
        if (!(ss > 0.0) || sr <= 0.0 || sr * sr / ss <= best) continue;
        best = sr * sr / ss;
        best_params = {std::clamp(std::sqrt(sr / ss), lower[0] * 1.01, upper[0] * 0.99), f0, zeta};
      }
    }
    if (best_params.empty()) {
      if (why) *why = "no positive residual a resonance could explain";
      return false;
    }
    *params = best_params;
    return true;
  }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override {
    model->terms.push_back(sim::Resonance{p[0], p[1], p[2]});
  }

 private:
  std::vector<ParameterSpec> specs_;
};

}  // namespace

std::unique_ptr<ParametricTerm> MakeResonanceTerm() { return std::make_unique<ResonanceTerm>(); }

}  // namespace allanlab::estimators
