#include "experiments/diagnosis/refit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "estimators/fit/parametric_fit.h"
#include "estimators/fit/parametric_term.h"
#include "experiments/diagnosis/baseline.h"
#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/envelope.h"
#include "experiments/diagnosis/gap.h"
#include "experiments/diagnosis/physical_bounds.h"

namespace allanlab::experiments::detail {
namespace {

using estimators::Coefficient;

// Adds a kept fit's profile ranges (its values unchanged): the refits form them only for the
// option BestRefit keeps, and only when asked.
using RangesLater = std::function<bool(estimators::FitSummary* fit)>;


// The linear terms refitted with `effects` in the model, three passes: the curve divided by the
// model's E[linear + effects] / E[linear] (exact for an additive effect at the solution, and the
// right correction for a band-limit, which scales rather than adds), or for quantizers (whose
// error is uncorrelated with the signal: additive) the curve minus E[linear + effects] -
// E[linear]. `ranges` (may be null): receives how to add the fit's profile ranges, which are
// left unset (RangesLater).
bool FitWithEffects(const BaselineSpec& spec, const estimators::AvarCurve& curve,
                    const estimators::FitSummary& start, const std::vector<EffectInstance>& effects,
                    estimators::FitSummary* fit, sim::SensorModel* model, std::string* why,
                    RangesLater* ranges) {
  const sim::RecordShape shape{curve.num_samples, curve.estimator};
  estimators::FitSummary current = start;
  const bool subtract = std::all_of(effects.begin(), effects.end(), [](const EffectInstance& e) {
    return SpecOf(e.effect).held == HeldRefit::kSubtractive;
  });
  for (int pass = 0; pass < 3; ++pass) {
    const sim::SensorModel linear = spec.Model(current, curve.sample_clock);
    sim::SensorModel full;
    if (!WithEffects(linear, effects, &full, why)) return false;
    const auto e_lin = linear.ExpectedAvar(curve.m, shape);
    const auto e_full = full.ExpectedAvar(curve.m, shape);
    estimators::AvarCurve adjusted = curve;
    for (std::size_t i = 0; i < curve.size(); ++i) {
      const double ratio = e_full[i] > 0.0 && e_lin[i] > 0.0 ? e_lin[i] / e_full[i] : 1.0;
      adjusted.avar[i] = std::max(curve.avar[i] * ratio, 1e-300);
      // A quantizer: the curve minus its AVAR, floored at a tenth of the ratio's value where the
      // record lies far below the model. From a baseline whose Q absorbed the quantizer the ratio
      // converges only geometrically (~1/8 of Q^2 left after 3 passes), which left the exact
      // quantizer worse than the baseline (benchmark #14: OAVAR chi2 938 -> 2196). Not for the
      // other effects: the joint fit holds additive ones at their estimate, and subtracting
      // spikes' white variance from the noisy long taus of a half record misplaced K (held-out
      // chi2 19 -> 45, diagnose_stat_test's spikes).
      if (subtract) adjusted.avar[i] = std::max(curve.avar[i] - (e_full[i] - e_lin[i]), 0.1 * adjusted.avar[i]);
    }
    estimators::FitSummary next;
    // Every pass is read for its values only (the next pass's ratio; the last one's ranges, when
    // asked, are added by `ranges` from the same curve).
    if (!FitLinear(spec, adjusted, &next, nullptr, /*profile_ranges=*/false)) {
      *why = "refit failed: " + next.message;
      return false;
    }
    current = next;
    if (pass == 2 && ranges != nullptr) {
      *ranges = [&spec, adjusted](estimators::FitSummary* f) {
        return FitLinear(spec, adjusted, f, nullptr, /*profile_ranges=*/true);
      };
    }
  }
  *fit = current;
  return WithEffects(spec.Model(current, curve.sample_clock), effects, model, why);
}


// A library term whose fit starts at given values (the candidate's estimate from the record)
// rather than at the term's own guess from the curve; optionally kept within a factor of the
// start for some parameters (`within[q]` > 1; 0 leaves the term's own bounds).
class SeededTerm final : public estimators::ParametricTerm {
 public:
  SeededTerm(std::shared_ptr<const estimators::ParametricTerm> inner, std::vector<double> start,
             std::vector<double> within = {})
      : inner_(std::move(inner)), start_(std::move(start)), within_(std::move(within)) {}
  std::string_view id() const override { return inner_->id(); }
  std::string_view short_name() const override { return inner_->short_name(); }
  const std::vector<estimators::ParameterSpec>& parameters() const override { return inner_->parameters(); }
  void Bounds(const estimators::AvarCurve& curve, std::vector<double>* lo, std::vector<double>* hi) const override {
    inner_->Bounds(curve, lo, hi);
    for (std::size_t q = 0; q < within_.size() && q < lo->size(); ++q) {
      if (!(within_[q] > 1.0)) continue;
      (*lo)[q] = std::max((*lo)[q], start_[q] / within_[q]);
      (*hi)[q] = std::min((*hi)[q], start_[q] * within_[q]);
    }
  }
  bool InitialGuess(const estimators::AvarCurve& curve, std::span<const double>, const sim::SensorModel&,
                    std::vector<double>* params, std::string*) const override {
    std::vector<double> lo, hi;
    Bounds(curve, &lo, &hi);
    *params = start_;
    for (std::size_t q = 0; q < params->size(); ++q) {
      // Strictly inside the bounds: Ceres needs a feasible interior start.
      (*params)[q] = std::clamp((*params)[q], lo[q] * 1.001, hi[q] * 0.999);
    }
    return true;
  }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override { inner_->ApplyTo(p, model); }
  bool modifies_other_terms() const override { return inner_->modifies_other_terms(); }

 private:
  std::shared_ptr<const estimators::ParametricTerm> inner_;
  std::vector<double> start_;
  std::vector<double> within_;
};


// An additive effect held at its estimate (outliers, bias_step, exponential_drift): a term with no
// free parameters, so the linear terms are fitted to the curve minus its exact AVAR instead of
// absorbing it (spikes' white variance belongs to the spikes, not to N).
class FixedEffectTerm final : public estimators::ParametricTerm {
 public:
  explicit FixedEffectTerm(EffectInstance e) : effect_(std::move(e)) {}
  std::string_view id() const override { return EffectId(effect_.effect); }
  std::string_view short_name() const override { return EffectId(effect_.effect); }
  const std::vector<estimators::ParameterSpec>& parameters() const override { return none_; }
  bool InitialGuess(const estimators::AvarCurve&, std::span<const double>, const sim::SensorModel&,
                    std::vector<double>* params, std::string*) const override {
    params->clear();
    return true;
  }
  void ApplyTo(std::span<const double>, sim::SensorModel* model) const override {
    std::string ignored;
    AddEffect(effect_, model, &ignored);
  }

 private:
  EffectInstance effect_;
  std::vector<estimators::ParameterSpec> none_;
};


// The fit term of each effect (the registry's, or, for an additive effect held at its start, one
// with no free parameter)
// and the effect's parameters it frees (the first ones, effect.h); nullptr when the effect has
// neither (a quantizer: the caller then uses the ratio refit).
std::shared_ptr<const estimators::ParametricTerm> TermOf(const EffectInstance& e, std::vector<std::string>* keys) {
  const EffectSpec& spec = SpecOf(e.effect);
  const bool held = HeldAtItsStart(e);
  std::shared_ptr<const estimators::ParametricTerm> term = spec.fit_term != nullptr && !held ? spec.fit_term(e) : nullptr;
  if (!term && (spec.held == HeldRefit::kJointFit || held)) term = std::make_shared<FixedEffectTerm>(e);
  if (term) keys->assign(spec.params.begin(), spec.params.begin() + static_cast<std::ptrdiff_t>(term->parameters().size()));
  return term;
}


// Whether the effects with the parameters a fit gave them are physically possible
// (physical_bounds.h); a parameter the fit left out counts as possible (the caller reports it).
bool FittedEffectsPossible(const std::vector<EffectInstance>& effects, const std::vector<std::vector<std::string>>& keys,
                           const estimators::ParametricFitSummary& ps, const estimators::AvarCurve& curve) {
  std::vector<EffectInstance> fitted = effects;
  for (std::size_t i = 0; i < fitted.size() && i < ps.extra.size(); ++i) {
    if (!ps.extra[i].fitted) return true;
    for (std::size_t q = 0; q < keys[i].size() && q < ps.extra[i].value_si.size(); ++q) {
      fitted[i].params[keys[i][q]] = ps.extra[i].value_si[q];
    }
  }
  std::string ignored;
  const double length_s = static_cast<double>(curve.num_samples) * curve.sample_clock.period_s();
  return PhysicallyPossible(fitted, curve.sample_clock, length_s, &ignored);
}

// The linear terms and the effects' parameters fitted together (estimators/fit/parametric_fit.h,
// GLS) from the estimates in `effects`; for a correlation time (Gauss-Markov, telegraph) the fit
// is also started a factor 3 either side and the lowest chi2 kept, as the Allan bump of a
// dominant process is flat enough near its peak to hold a local minimum. Returns false when an
// effect is not a library term (the caller then uses the ratio refit).
bool FitParametric(const BaselineSpec& spec, const estimators::AvarCurve& curve,
                   const estimators::FitSummary& baseline, std::vector<EffectInstance>* effects,
                   estimators::FitSummary* fit, sim::SensorModel* model, std::string* why,
                   RangesLater* ranges) {
  // Every coefficient held (a sensor model as given, nothing floated): the fit library needs a
  // linear term to solve for (an empty design crashes its QR), so the effects keep their starts.
  if (spec.terms.empty()) return false;
  std::vector<std::vector<std::string>> keys(effects->size());
  std::vector<std::shared_ptr<const estimators::ParametricTerm>> terms;
  for (std::size_t i = 0; i < effects->size(); ++i) {
    auto t = TermOf((*effects)[i], &keys[i]);
    if (!t) return false;
    terms.push_back(std::move(t));
  }
  // Starts: the estimate, then the scale parameter of each Gauss-Markov-like effect x 1/3 and 3,
  // and each resonance kept near the line its start came from (below).
  struct Start {
    std::vector<std::vector<double>> values;  // per effect, its keys' values
    std::vector<std::vector<double>> within;  // per effect (may be empty): SeededTerm's factors
  };
  Start base_start{std::vector<std::vector<double>>(effects->size()), std::vector<std::vector<double>>(effects->size())};
  for (std::size_t i = 0; i < effects->size(); ++i) {
    for (const std::string& k : keys[i]) base_start.values[i].push_back((*effects)[i].params.at(k));
  }
  std::vector<Start> starts = {base_start};
  for (std::size_t i = 0; i < effects->size(); ++i) {
    const Effect e = (*effects)[i].effect;
    if (e == Effect::kResonance && keys[i].size() == 3) {
      // The line's frequency and width from the periodogram (resonance_estimate.h), which the
      // Allan curve alone cannot pin: free, a fit can trade the line for a broad hump that
      // lowers chi2 and has no peak (independent benchmark seed 4, #222: a 20.3 Hz line of
      // damping 0.032 fitted at damping 0.95, then refused). Kept within 1.2x of f0 and 3x
      // of the damping, the fit still polishes both.
      Start s = base_start;
      s.within[i] = {0.0, 1.2, 3.0};
      starts.push_back(s);
    }
    if ((e != Effect::kGaussMarkov && e != Effect::kRandomTelegraph) || keys[i].size() < 2) continue;  // held: no Tc to move
    for (double f : {1.0 / 3.0, 3.0}) {
      Start s = base_start;
      s.values[i][1] *= f;
      starts.push_back(s);
    }
  }
  bool any = false;
  estimators::ParametricFitSummary best;
  estimators::ParametricFitOptions best_options;
  // Linear term sets: every asked term, and those the baseline's selection kept (parametric_fit
  // does not select; a term the data do not support extrapolates badly onto the held-out half,
  // while a bump the baseline soaked into other terms may need a dropped one back). AIC decides.
  std::vector<std::vector<Coefficient>> term_sets = {spec.terms};
  std::vector<Coefficient> kept;
  for (Coefficient c : spec.terms) {
    if (baseline.at(c).fitted) kept.push_back(c);
  }
  // With no free effect parameter (spikes, step, drift held at their estimates) the effect only
  // takes variance from the terms, so the baseline's selection stands.
  const bool free_parameters = std::any_of(terms.begin(), terms.end(), [](const auto& t) { return !t->parameters().empty(); });
  if (!kept.empty() && !free_parameters) term_sets = {kept};
  if (!kept.empty() && free_parameters && kept.size() != spec.terms.size()) term_sets.push_back(kept);
  // Except under a warm-up drift, which the baseline's selection absorbed (benchmark #5: N, K,
  // R = 9586 deg/h^2, B dropped): every term, R excepted. The held drift and a ramp compete for
  // the same long-tau rise and the curve cannot tell them apart (#5: OAVAR chi2 8.8 with
  // R = 593 deg/h^2 in place of B and K, 9.9 for the true model), while the halves can (a
  // deterministic ramp lifts the quiet second half: max |z| 10); the drift's block-mean fit
  // already carries the record's trend.
  if (std::any_of(effects->begin(), effects->end(), [](const EffectInstance& e) { return e.effect == Effect::kExponentialDrift; })) {
    auto without_ramp = [](std::vector<Coefficient> set) {
      std::erase(set, Coefficient::kR);
      return set;
    };
    term_sets = {without_ramp(spec.terms)};
    if (free_parameters && !kept.empty()) term_sets.push_back(without_ramp(kept));
  }
  const estimators::AvarCurve fit_curve = spec.WithoutHeldAdditive(curve);
  const bool replaces_band_limit = std::any_of(effects->begin(), effects->end(), [](const EffectInstance& e) {
    return e.effect == Effect::kBandwidth;
  });
  double best_aic = 0.0;
  bool best_possible = false;
  for (const auto& term_set : term_sets)
  for (const auto& start : starts) {
    estimators::ParametricFitOptions po;
    po.method = estimators::FitMethod::kGls;
    po.terms = term_set;
    po.covariance = spec.Covariance(fit_curve);
    // Only the kept fit's profile ranges are read: they are formed once it is chosen (below).
    po.profile_ranges = false;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      po.extra.push_back(std::make_shared<SeededTerm>(terms[i], start.values[i], start.within[i]));
    }
    // A band-limit candidate replaces the held one (AddBandwidth): not both in series.
    if (auto band = spec.HeldBandLimitTerm(); band && !replaces_band_limit) po.extra.push_back(std::move(band));
    estimators::ParametricFitSummary ps;
    if (!estimators::FitAvarModelWithTerms(po, fit_curve, &ps)) {
      // As the baseline: WLS when the GLS covariance is singular.
      po.method = estimators::FitMethod::kWls;
      if (!estimators::FitAvarModelWithTerms(po, fit_curve, &ps)) {
        *why = ps.base.message;
        continue;
      }
    }
    // Judged under each fit's own covariance (the goodness of fit `fit` prints, docs/theory.md
    // §4.8), not the held weight, which is the baseline's: a process far above the noise that
    // the baseline soaked into B and K makes the long taus' variances under that weight too
    // small, and the right correlation time scored worse there than a vanishing process (a
    // 235 deg/h telegraph of 21 s dwell: chi2 151 at a 22.6 s dwell against 74 at 2 ms; a
    // 110 deg/h Gauss-Markov of Tc 21 s, unexplained under that weight, is named under its own).
    const double aic = ps.base.gof_chi2 + 2.0 * static_cast<double>(ps.base.taus_used - ps.base.dof);
    // A fit the candidate would be refused for (physical_bounds.h) loses to any that is not.
    const bool possible = FittedEffectsPossible(*effects, keys, ps, curve);
    if (!any || (possible && !best_possible) || (possible == best_possible && aic < best_aic)) {
      best_possible = possible;
      best_aic = aic;
      best = std::move(ps);
      best_options = std::move(po);
      any = true;
    }
  }
  if (!any) return false;
  // The kept fit's profile ranges, when asked: the same options give the same fit (ranges do not
  // move it), and one more fit costs less than the ranges of every fit tried (up to six: 40 % of
  // their time went to ranges nobody read).
  if (ranges != nullptr) {
    *ranges = [options = best_options, fit_curve](estimators::FitSummary* f) mutable {
      options.profile_ranges = true;
      estimators::ParametricFitSummary again;
      if (!estimators::FitAvarModelWithTerms(options, fit_curve, &again)) return false;
      *f = again.base;
      return true;
    };
  }
  std::vector<EffectInstance> fitted = *effects;
  for (std::size_t i = 0; i < fitted.size(); ++i) {
    const auto& pe = best.extra[i];
    if (!pe.fitted) {
      *why = "the fit left " + pe.id + " out: " + pe.note;
      return false;
    }
    for (std::size_t q = 0; q < keys[i].size(); ++q) fitted[i].params[keys[i][q]] = pe.value_si[q];
  }
  *effects = std::move(fitted);
  *fit = best.base;
  // The fitted terms and effects, then the held terms and quantizers the fit's curve was
  // cleared of.
  *model = estimators::FittedModel(best_options, curve, best);
  sim::SensorModel held = spec.held;
  held.sample_clock = model->sample_clock;
  model->terms.insert(model->terms.end(), held.terms.begin(), held.terms.end());
  if (held.angle_quantizer && !model->angle_quantizer) model->angle_quantizer = held.angle_quantizer;
  if (held.rate_quantizer && !model->rate_quantizer) model->rate_quantizer = held.rate_quantizer;
  return true;
}


// A candidate with events (bias steps, warm-up drifts): the linear terms (and the other effects)
// fitted to the Allan curve of the record less the events' paths, as the baseline is fitted,
// rather than to the record's curve less the events' expected AVAR. That expectation leaves out
// the cross term of the event with the noise, which is as large as the noise's own long-tau AVAR
// and had the fit drop or inflate K (independent benchmark #103: a -188 deg/h step left K out with
// an upper limit of 72.9 deg/h/sqrt(h), where the cleared record gives 7.8 +- 3.4, and the trend
// view judged the record's wander at K = 0: |z| 9); the block-mean views judge the same cleared
// record (block_means.h).
bool RefitOnClearedRecord(const BaselineSpec& spec, SampleClock sample_clock, std::span<const double> rate,
                          const std::vector<EffectInstance>& events, std::vector<EffectInstance> rest,
                          std::vector<EffectInstance>* effects, estimators::FitSummary* fit,
                          sim::SensorModel* model, std::string* why, bool profile_ranges) {
  sim::SensorModel event_model;
  event_model.sample_clock = sample_clock;
  for (const EffectInstance& e : events) {
    if (!AddEffect(e, &event_model, why)) return false;
  }
  const std::vector<double> path = DeterministicPath(event_model, static_cast<std::int64_t>(rate.size()));
  std::vector<double> cleared(rate.begin(), rate.end());
  for (std::size_t i = 0; i < cleared.size(); ++i) cleared[i] -= path[i];
  estimators::AvarCurve cleared_curve;
  if (!RecordCurve(cleared, sample_clock, &cleared_curve, why)) return false;
  estimators::FitSummary cleared_fit;
  if (!FitLinear(spec, cleared_curve, &cleared_fit, nullptr, profile_ranges)) {
    *why = "refit on the record less the events failed: " + cleared_fit.message;
    return false;
  }
  sim::SensorModel rest_model = spec.Model(cleared_fit, sample_clock);
  if (!rest.empty()) {
    const OavarTheory theory = ExactOavar(rest_model, cleared_curve.m, cleared_curve.num_samples);
    if (!BestRefit(spec, cleared_curve, theory.edf, cleared_fit, &rest, &cleared_fit, &rest_model, why, {},
                   profile_ranges)) {
      return false;
    }
  }
  *fit = cleared_fit;
  // The effects in their asked order, those refitted with their fitted parameters.
  std::vector<EffectInstance> out;
  std::size_t next_rest = 0;
  for (const EffectInstance& e : *effects) out.push_back(IsOneOffEvent(e.effect) ? e : rest[next_rest++]);
  *effects = std::move(out);
  return WithEffects(std::move(rest_model), events, model, why);
}

}  // namespace


bool WithEffects(sim::SensorModel model, const std::vector<EffectInstance>& effects,
                 sim::SensorModel* out, std::string* why) {
  for (const EffectInstance& e : effects) {
    if (!AddEffect(e, &model, why)) return false;
  }
  if (!model.IsValid(why)) return false;
  *out = std::move(model);
  return true;
}


// The effects added to `start` (a fit without them) by the best of the refits, judged by the
// AIC of `curve` against the resulting model (exact OAVAR chi2 + 2 per linear term kept): the
// joint GLS fit (FitParametric), again without the linear terms it leaves within 2 sigma of zero
// (rlg + a 6.7e-5 rad/s step: K 1.9 +- 1.7 deg/h/sqrt(h), 3900 x the truth, kept the halves view
// at |z| 8 after the step), the ratio refit (FitWithEffects, from the joint fit's effect
// parameters when it ran), and `start` with the effects added unchanged. The last keeps the
// nested model from fitting worse than the model without the effect (the GLS iterations of the
// joint fit can settle elsewhere: OAVAR chi2 54 -> 92 for a 1e-5 rad/s step on a 1e6-sample
// record) and keeps an effect outside the Allan view (spikes, quantizers) at its data-domain
// estimate when the curve cannot place it.
// `edf`: the exact EDFs of the curve under the start model (computed once per curve: the exact
// moments are the costly part, and the EDFs barely move between the options).
bool BestRefit(const BaselineSpec& spec, const estimators::AvarCurve& curve,
               std::span<const double> edf,
               const estimators::FitSummary& start, std::vector<EffectInstance>* effects,
               estimators::FitSummary* fit, sim::SensorModel* model, std::string* why,
               std::span<const double> record_rate, bool profile_ranges) {
  if (!record_rate.empty()) {
    std::vector<EffectInstance> events, rest;
    // The one-off events (effect.h) are the effects with a deterministic path.
    for (const EffectInstance& e : *effects) (IsOneOffEvent(e.effect) ? events : rest).push_back(e);
    if (!events.empty()) {
      return RefitOnClearedRecord(spec, curve.sample_clock, record_rate, events, rest, effects, fit, model, why,
                                  profile_ranges);
    }
  }
  struct Option {
    std::vector<EffectInstance> effects;
    estimators::FitSummary fit;
    sim::SensorModel model;
    double chi2 = 0.0;  // then AIC
    RangesLater ranges;  // empty: fit already has its ranges (the start's)
  };
  std::vector<Option> options_tried;
  std::string ignored;
  std::vector<std::vector<EffectInstance>> starts = {*effects};
  {
    Option o{*effects, {}, {}, 0.0, {}};
    if (FitParametric(spec, curve, start, &o.effects, &o.fit, &o.model, &ignored, &o.ranges)) {
      starts.push_back(o.effects);
      // A linear term the effect has made insignificant (a bias step's variance left to a rate
      // random walk within its sigma of zero) still shapes the other views, where it is wrong:
      // the joint fit again without it, AIC below deciding.
      estimators::FitSummary reduced = start;
      bool dropped = false;
      for (Coefficient c : estimators::kAllCoefficients) {
        const auto& e = o.fit.at(c);
        if (e.fitted && start.at(c).fitted && !(e.value_si > 2.0 * e.sigma_si)) {
          reduced.coefficients[static_cast<int>(c)].fitted = false;
          dropped = true;
        }
      }
      Option r{*effects, {}, {}, 0.0, {}};
      if (dropped && FitParametric(spec, curve, reduced, &r.effects, &r.fit, &r.model, &ignored, &r.ranges)) {
        options_tried.push_back(std::move(r));
      }
      options_tried.push_back(std::move(o));
    }
  }
  for (const auto& from : starts) {
    Option o{from, {}, {}, 0.0, {}};
    if (FitWithEffects(spec, curve, start, o.effects, &o.fit, &o.model, why, &o.ranges)) {
      options_tried.push_back(std::move(o));
    }
    Option held{from, start, {}, 0.0, {}};
    if (WithEffects(spec.Model(start, curve.sample_clock), held.effects, &held.model, &ignored)) options_tried.push_back(std::move(held));
  }
  if (options_tried.empty()) return false;
  // AIC over the options: chi2 + 2 x the linear terms each keeps (the effects' parameters are
  // the same in every option). An option whose effects are physically impossible (the candidate
  // would be refused for them, physical_bounds.h) loses to any that is not.
  const double length_s = static_cast<double>(curve.num_samples) * curve.sample_clock.period_s();
  const auto possible = [&](const Option& o) { return PhysicallyPossible(o.effects, curve.sample_clock, length_s, &ignored); };
  std::size_t best = 0;
  bool best_possible = false;
  for (std::size_t i = 0; i < options_tried.size(); ++i) {
    const auto mean = options_tried[i].model.ExpectedAvar(curve.m, {curve.num_samples, curve.estimator});
    std::vector<double> z;
    for (std::size_t t = 0; t < curve.size(); ++t) z.push_back(ZFromChiSquare(curve.avar[t], mean[t], edf[t]));
    options_tried[i].chi2 = Metrics(z).chi2;
    for (Coefficient c : estimators::kAllCoefficients) options_tried[i].chi2 += options_tried[i].fit.at(c).fitted ? 2.0 : 0.0;
    const bool p = possible(options_tried[i]);
    if (i == 0 || (p && !best_possible) || (p == best_possible && options_tried[i].chi2 < options_tried[best].chi2)) {
      best = i;
      best_possible = p;
    }
  }
  // Only the kept option's ranges are formed (a refit's ranges cost more than the refit).
  Option& kept = options_tried[best];
  if (profile_ranges && kept.ranges && !kept.ranges(&kept.fit)) {
    *why = "the refit's profile ranges failed: " + kept.fit.message;
    return false;
  }
  *effects = std::move(kept.effects);
  *fit = std::move(kept.fit);
  *model = std::move(kept.model);
  return true;
}

}  // namespace allanlab::experiments::detail
