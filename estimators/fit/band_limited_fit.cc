#include "estimators/fit/band_limited_fit.h"

#include <cmath>
#include <memory>
#include <sstream>

#include <boost/math/distributions/chi_squared.hpp>

#include "estimators/fit/avar_covariance.h"

namespace allanlab::estimators {
namespace {

std::string ChainText(const BandLimitedFitOptions& o) {
  std::ostringstream os;
  os << (o.sampling == sim::OutputSampling::kAverage ? "averaged" : "point-sampled") << " output, L = "
     << o.oversampling;
  return os.str();
}

}  // namespace

bool BandLimitedFitOptions::IsValid(std::string* why) const {
  if (!fit.IsValid(why)) return false;
  if (oversampling < 1 || oversampling > 256) {
    if (why) *why = "fit: band-limit oversampling must be an integer in [1, 256]";
    return false;
  }
  if (!(detection_level > 0.0 && detection_level < 1.0)) {
    if (why) *why = "fit: band-limit detection level must be in (0, 1)";
    return false;
  }
  return true;
}

bool FitWithBandLimit(const BandLimitedFitOptions& options, const AvarCurve& curve,
                      BandLimitedFitSummary* summary) {
  *summary = BandLimitedFitSummary{};
  std::string why;
  if (!options.IsValid(&why)) {
    summary->fit.message = why;
    return false;
  }
  // Detection compares covariance fits; a bootstrap (if asked) runs once, on the reported fit.
  const bool bootstrap = options.fit.uncertainty == FitUncertainty::kBootstrap;
  // GLS: one covariance model for the plain fit and both band-limited candidates (same curve,
  // same terms), instead of one each.
  std::shared_ptr<const AvarCovarianceModel> covariance = options.fit.covariance;
  if (!covariance && options.fit.method == FitMethod::kGls && curve.IsValid(nullptr) &&
      curve.estimator == sim::AvarEstimatorKind::kOverlapping && curve.num_samples > 0) {
    covariance = std::make_shared<const AvarCovarianceModel>(curve, options.fit.terms);
  }
  FitOptions plain_options = options.fit;
  plain_options.uncertainty = FitUncertainty::kCovariance;
  plain_options.covariance = covariance;
  FitSummary plain;
  if (!FitAvarModel(plain_options, curve, &plain)) {
    summary->fit = plain;
    return false;
  }
  summary->plain_chi2 = plain.chi2;
  summary->plain_dof = plain.dof;
  summary->fit = plain;
  summary->ok = true;
  auto finish = [&](const std::string& decision) {
    if (bootstrap && !summary->band_limited) {
      FitSummary with;
      FitOptions with_options = options.fit;
      with_options.covariance = covariance;
      if (!FitAvarModel(with_options, curve, &with)) {
        summary->fit = with;
        summary->ok = false;
        return false;
      }
      summary->fit = with;
    }
    summary->fit.band_limit = decision;
    if (curve.size() > 0) {
      summary->fit.tau_min_s = curve.tau_s.front();
      summary->fit.tau_max_s = curve.tau_s.back();
    }
    return true;
  };
  if (options.policy == BandLimitPolicy::kOff) return finish("off (not asked)");
  if (options.fit.method == FitMethod::kSlope) return finish("none (the slope method reads each line where it is)");

  // The band-limited candidates.
  ParametricFitSummary best;
  ParametricFitOptions best_options;
  bool have = false;
  std::string notes;
  for (sim::LowPassKind kind : {sim::LowPassKind::kFirstOrder, sim::LowPassKind::kButterworth2}) {
    ParametricFitOptions p;
    p.method = options.fit.method;
    p.terms = options.fit.terms;
    p.extra = {std::shared_ptr<const ParametricTerm>(
        MakeBandLimitTerm(kind, options.sampling, options.oversampling))};
    p.covariance = covariance;
    // Candidates without a starting cutoff are discarded below: skip their pilot and GLS stages.
    p.stop_without_start = true;
    ParametricFitSummary s;
    const std::string name = kind == sim::LowPassKind::kFirstOrder ? "BW" : "BW2";
    if (!FitAvarModelWithTerms(p, curve, &s)) {
      notes += "; " + name + " fit failed: " + s.base.message;
      continue;
    }
    if (!s.extra[0].fitted || !s.extra[0].note.empty()) {
      notes += "; " + name + ": " + (s.extra[0].note.empty() ? "not fitted" : s.extra[0].note);
      continue;
    }
    if (!have || s.base.chi2 < best.base.chi2) {
      best = s;
      best_options = p;
      have = true;
    }
  }
  if (!have) return finish("none detected (no band-limited fit usable" + notes + ")");
  summary->band_limited_chi2 = best.base.chi2;
  summary->band_limited_dof = best.base.dof;
  const double drop = plain.chi2 - best.base.chi2;
  const int extra_parameters = std::max(1, plain.dof - best.base.dof);
  const double critical = boost::math::quantile(
      boost::math::complement(boost::math::chi_squared(extra_parameters), options.detection_level));
  std::ostringstream os;
  os << "chi2 " << plain.chi2 << " (" << plain.dof << " dof) without, " << best.base.chi2 << " ("
     << best.base.dof << " dof) with " << best.extra[0].short_name << " (" << ChainText(options)
     << "); threshold " << critical << " at " << options.detection_level;
  if (!(drop > critical)) return finish("none detected: " + os.str() + notes);

  // The reported fit chooses its terms as the plain fit does (parametric_fit.h); the detection
  // above compared the fits of every term.
  best_options.select_terms = options.fit.select_terms;
  if (bootstrap || best_options.select_terms) {
    best_options.uncertainty = options.fit.uncertainty;
    best_options.bootstrap = options.fit.bootstrap;
    if (!FitAvarModelWithTerms(best_options, curve, &best)) {
      summary->fit = best.base;
      summary->ok = false;
      return false;
    }
  }
  summary->band_limited = true;
  summary->parametric = best_options;
  summary->extra = best.extra;
  summary->fit = best.base;
  std::ostringstream decision;
  decision << "fitted " << best.extra[0].short_name << " ("
           << (best.extra[0].short_name == "BW2" ? "2nd-order Butterworth" : "first order") << ", "
           << ChainText(options) << (best_options.select_terms ? "; terms chosen by AIC" : "; every term kept")
           << "): " << os.str();
  return finish(decision.str());
}

}  // namespace allanlab::estimators
