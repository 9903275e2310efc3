#include "experiments/diagnosis/diagnose.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "experiments/diagnosis/baseline.h"
#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/diagnosis_context.h"
#include "experiments/diagnosis/envelope.h"
#include "experiments/diagnosis/heldout.h"
#include "experiments/diagnosis/physical_bounds.h"
#include "experiments/diagnosis/refit.h"
#include "experiments/diagnosis/verdict.h"

namespace allanlab::experiments {
namespace detail {

SharedFlicker RecordFlicker(const Context& ctx, int h) {
  return {&ctx.flicker_streams, ctx.options->seed + (h < 0 ? 0 : 500 + static_cast<std::uint64_t>(h))};
}

void ReportProgress(const Context& ctx, std::string_view stage, int done, int total) {
  if (ctx.options->progress && std::this_thread::get_id() == ctx.caller) ctx.options->progress(stage, done, total);
}

std::vector<ViewResiduals> RecordResiduals(std::span<const double> rate, const ViewLayout& layout,
                                           const ViewValues& observed, const sim::SensorModel& model,
                                           bool monte_carlo, int trials, std::uint64_t seed,
                                           std::string* note, const ViewSet& wanted,
                                           const SharedFlicker* shared_flicker, const OavarTheory* known_theory) {
  const OavarTheory theory = !wanted.test(static_cast<int>(View::kOavar)) ? OavarTheory{}
                             : known_theory != nullptr                    ? *known_theory
                                                      : ExactOavar(model, layout.oavar_m, layout.num_samples);
  // The simulated records give the Monte Carlo views only: OAVAR's distribution is exact, and
  // for a Gaussian model the others' come from theory too (gaussian_views.h).
  const bool beyond_oavar = monte_carlo && trials >= 3;
  const GaussianViewTheory gaussian = beyond_oavar && (wanted & MonteCarloViews()).any()
                                          ? ExactGaussianViews(model, layout)
                                          : GaussianViewTheory{};
  ViewEnvelope envelope;
  ViewSet simulated = wanted & MonteCarloViews();
  if (!gaussian.empty()) simulated.reset();
  const bool have_envelope = beyond_oavar && simulated.any() &&
                             SimulateEnvelope(model, layout, trials, seed, &envelope, note, simulated, shared_flicker);
  std::vector<ViewResiduals> out = Residuals(layout, observed, theory, have_envelope ? &envelope : nullptr, wanted,
                                             gaussian.empty() ? nullptr : &gaussian);
  const bool block_means = wanted.test(static_cast<int>(View::kChangePoint)) || wanted.test(static_cast<int>(View::kTrend));
  if (block_means && !layout.block_counts.empty() && static_cast<std::int64_t>(rate.size()) == layout.num_samples) {
    ViewResiduals change_point, trend;
    BlockMeanResiduals(rate, layout.sample_clock.period_s(), layout.block_counts, model, layout.rate_random_walk_bound,
                       &change_point, &trend);
    if (wanted.test(static_cast<int>(View::kChangePoint))) out.push_back(std::move(change_point));
    if (wanted.test(static_cast<int>(View::kTrend))) out.push_back(std::move(trend));
  }
  return out;
}

ModelGap Assess(const Context& ctx, const sim::SensorModel& model, bool monte_carlo,
                std::uint64_t seed, std::string* note, const OavarTheory* known_theory) {
  ModelGap gap;
  if (ctx.have_record) {
    const SharedFlicker flicker = RecordFlicker(ctx);
    gap.views = RecordResiduals(ctx.rate, ctx.layout, ctx.observed, model, monte_carlo, ctx.options->trials, seed, note,
                                EveryView(), &flicker, known_theory);
  } else {
    const OavarTheory theory =
        known_theory != nullptr ? *known_theory : ExactOavar(model, ctx.layout.oavar_m, ctx.layout.num_samples);
    ViewValues observed(kNumViews);
    for (double a : ctx.curve.avar) observed[0].push_back(std::log(a));
    gap.views = Residuals(ctx.layout, observed, theory, nullptr);
  }
  return gap;
}


// A curve against a model's exact OAVAR distribution (the exact view's z, ExactOavar).
GapMetrics CurveMetrics(const sim::SensorModel& model, const estimators::AvarCurve& second) {
  return CurveMetrics(ExactOavar(model, second.m, second.num_samples), second);
}

GapMetrics CurveMetrics(const OavarTheory& t, const estimators::AvarCurve& second) {
  std::vector<double> z;
  for (std::size_t i = 0; i < second.size(); ++i) z.push_back(ZFromChiSquare(second.avar[i], t.mean[i], t.edf[i]));
  return Metrics(z);
}

int ParameterCount(const std::vector<EffectInstance>& effects) {
  int k = 0;
  for (const auto& e : effects) k += static_cast<int>(EffectParameterNames(e.effect).size());
  return k;
}

double ExactChi2(const ModelGap& gap) {
  return gap.View(View::kOavar).chi2 + gap.View(View::kChangePoint).chi2 + gap.View(View::kTrend).chi2;
}

bool ClosesGap(const ModelGap& gap, double threshold) { return gap.All().max_abs_z <= threshold; }

std::optional<CandidateResult> TryCandidate(const Context& ctx, const DiagnosisSummary& s,
                                            const std::vector<EffectInstance>& effects,
                                            std::string* why) {
  CandidateResult c;
  c.effects = effects;
  // The held-out half's fit and exact OAVAR depend on the effects' starts alone, not on the
  // record's refit: a task beside it. Inside the candidates' parallel loop a thread that has run
  // out of candidates takes it up (the loop's last candidates left one core idle); outside one it
  // runs on this thread. Both write their own fields, so the bits are the same either way.
  struct Heldout {
    int half = 1;
    bool fitted = false;
    sim::SensorModel model;
    OavarTheory theory;
    GapMetrics before, after;
  } heldout;
  if (ctx.have_halves) {
#pragma omp task default(none) shared(ctx, effects, heldout)
    {
      heldout.half = ScoredHalf(ctx, effects);
      std::string ignored;
      if (HeldoutModel(ctx, effects, heldout.half, &heldout.model, &ignored)) {
        const HalfRecord& scored = ctx.halves[heldout.half];
        heldout.fitted = true;
        heldout.before = scored.against_other_baseline;
        heldout.theory = ExactOavar(heldout.model, scored.curve.m, scored.curve.num_samples);
        heldout.after = CurveMetrics(heldout.theory, scored.curve);
      }
    }
  }
  const bool refitted = [&] {
    if (!BestRefit(ctx.spec, ctx.curve, ctx.curve_edf, s.baseline, &c.effects, &c.fit, &c.model, why,
                   ctx.have_record ? ctx.rate : std::span<const double>())) {
      return false;
    }
    if (!PhysicallyPossible(c.effects, ctx.curve.sample_clock,
                            ctx.curve.sample_clock.period_s() * static_cast<double>(ctx.curve.num_samples), why)) {
      return false;
    }
    c.theory = ExactOavar(c.model, ctx.layout.oavar_m, ctx.layout.num_samples);
    c.after = Assess(ctx, c.model, false, 0, why, &c.theory);
    const int k = ParameterCount(effects);
    c.score = ExactChi2(s.before) - ExactChi2(c.after) - 2.0 * k;
    return true;
  }();
#pragma omp taskwait
  if (!refitted) return std::nullopt;
  if (ctx.have_halves) {
    c.heldout_half = heldout.half;
    if (heldout.fitted) {
      c.heldout_model = std::move(heldout.model);
      c.heldout_before = heldout.before;
      c.heldout_theory = std::move(heldout.theory);
      c.after.heldout = heldout.after;
      c.after.has_heldout = true;
    }
  }
  return c;
}

}  // namespace detail

namespace {

using namespace detail;

constexpr std::int64_t kMinSamples = 1024;


bool CommonChecks(const DiagnoseOptions& options, DiagnosisSummary* summary) {
  std::string why;
  if (!options.IsValid(&why)) {
    summary->message = why;
    return false;
  }
  return true;
}

// The finest block-mean view's blocks (block_means.h), with the baseline's and the verdict's (or
// best tried) model's deterministic paths over them.
BlockMeanSeries RecordBlockMeans(std::span<const double> rate, double tau0, const DiagnosisSummary& s) {
  BlockMeanSeries out;
  const auto n = static_cast<std::int64_t>(rate.size());
  const std::vector<int> counts = BlockMeanCounts(n);
  if (counts.empty()) return out;
  const int blocks = counts.front();
  const std::int64_t m = n / blocks;
  out.block_s = static_cast<double>(m) * tau0;
  for (int b = 0; b < blocks; ++b) out.time_s.push_back((b + 0.5) * out.block_s);
  out.record = BlockMeans(rate, blocks);
  auto path = [&](const sim::SensorModel& model) {
    const std::vector<double> p = DeterministicPath(model, n);
    return p.empty() ? std::vector<double>(static_cast<std::size_t>(blocks), 0.0) : BlockMeans(p, blocks);
  };
  out.baseline_path = path(s.baseline_model);
  out.baseline_sd = BlockMeanDeviationSd(s.baseline_model, m, blocks);
  if (s.verdict_candidate >= 0) {
    out.verdict_path = path(s.candidates[s.verdict_candidate].model);
    out.verdict_sd = BlockMeanDeviationSd(s.candidates[s.verdict_candidate].model, m, blocks);
  }
  return out;
}

}  // namespace

bool DiagnoseOptions::IsValid(std::string* why) const {
  if (terms.empty() && baseline != Baseline::kSensor) {
    *why = "no model terms";
    return false;
  }
  if (!(false_alarm > 0.0 && false_alarm < 1.0)) {
    *why = "false-alarm rate must be in (0, 1)";
    return false;
  }
  if (trials != 0 && (trials < 3 || trials > 100000)) {
    *why = "trials must be 0 (OAVAR view only) or in [3, 100000]";
    return false;
  }
  if (envelope_candidates < 0) {
    *why = "envelope_candidates must be >= 0";
    return false;
  }
  return true;
}

GapMetrics ModelGap::View(experiments::View v) const {
  for (const ViewResiduals& r : views) {
    if (r.view == v) return Metrics(r.z);
  }
  GapMetrics none;
  return none;
}

std::string CandidateResult::id() const {
  std::string id;
  for (const EffectInstance& e : effects) {
    if (!id.empty()) id += "+";
    id += EffectId(e.effect);
  }
  return id;
}

bool DiagnoseRecord(const DiagnoseOptions& options, std::span<const double> rate, SampleClock sample_clock,
                    DiagnosisSummary* summary) {
  DiagnosisSummary& s = *summary;
  s = DiagnosisSummary{};
  if (!CommonChecks(options, summary)) return false;
  if (!sample_clock.IsValid()) {
    s.message = "sample period must be finite and > 0";
    return false;
  }
  if (static_cast<std::int64_t>(rate.size()) < kMinSamples) {
    s.message = "the record has " + std::to_string(rate.size()) + " samples; diagnosis needs at least " +
                std::to_string(kMinSamples);
    return false;
  }
  for (std::size_t k = 0; k < rate.size(); ++k) {
    if (!std::isfinite(rate[k])) {
      s.message = "sample " + std::to_string(k) + " is not finite (drop or fill non-finite values first)";
      return false;
    }
  }
  Context ctx;
  ctx.options = &options;
  ctx.rate = rate;
  ctx.have_record = true;
  s.num_samples = static_cast<std::int64_t>(rate.size());
  s.sample_clock = sample_clock;
  std::string why;
  ReportProgress(ctx, "baseline", 0, 0);
  if (!RecordCurve(rate, sample_clock, &ctx.curve, &why)) {
    s.message = why;
    return false;
  }
  std::string fallback;
  s.baseline_source = options.baseline;
  if (!FitBaseline(options, ctx.curve, &ctx.spec, &s.baseline, &fallback, &s.message)) return false;
  if (!fallback.empty()) s.notes.push_back("baseline: " + fallback);
  s.baseline_model = ctx.spec.Model(s.baseline, sample_clock);
  s.curve = ctx.curve;
  ctx.layout = MakeViewLayout(sample_clock, s.num_samples, ctx.curve.m);
  ctx.layout.rate_random_walk_bound = RandomWalkBound(ctx.spec, s.baseline);
  if (!ComputeViews(ctx.layout, rate, &ctx.observed, &why)) {
    s.message = why;
    return false;
  }
  // Held-out halves: each half's own baseline, curve and views (a candidate is fitted on one
  // and scored on the other).
  const std::size_t half = rate.size() / 2;
  // The halves are independent: one per thread (each half's own results, whichever thread).
  bool half_ok[2] = {false, false};
#pragma omp parallel for schedule(static, 1)
  for (int h = 0; h < 2; ++h) {
    HalfRecord& r = ctx.halves[h];
    std::string half_why;
    r.rate = rate.subspan(h * half, half);
    half_ok[h] = RecordCurve(r.rate, sample_clock, &r.curve, &half_why) && FitLinear(ctx.spec, r.curve, &r.baseline, nullptr);
    if (!half_ok[h]) continue;
    r.own_baseline_theory = ExactOavar(ctx.spec.Model(r.baseline, sample_clock), r.curve.m, r.curve.num_samples);
    r.edf = r.own_baseline_theory.edf;
    r.layout = MakeViewLayout(sample_clock, static_cast<std::int64_t>(half), r.curve.m);
    r.have_views = ComputeViews(r.layout, r.rate, &r.observed, &half_why);
  }
  ctx.have_halves = half_ok[0] && half_ok[1];
  if (ctx.have_halves) {
    ctx.half_length_s = static_cast<double>(half) * sample_clock.period_s();
    // A half is judged against models fitted on the other half: K up to what that half allows.
#pragma omp parallel for schedule(static, 1)
    for (int h = 0; h < 2; ++h) {
      HalfRecord& r = ctx.halves[h];
      r.layout.rate_random_walk_bound = RandomWalkBound(ctx.spec, ctx.halves[1 - h].baseline);
      // Halves of one length share their taus: the other half's own theory is this one's.
      const HalfRecord& other = ctx.halves[1 - h];
      r.other_baseline_theory = other.curve.m == r.curve.m && other.curve.num_samples == r.curve.num_samples
                                    ? other.own_baseline_theory
                                    : ExactOavar(ctx.spec.Model(other.baseline, sample_clock), r.curve.m,
                                                 r.curve.num_samples);
      r.against_other_baseline = CurveMetrics(r.other_baseline_theory, r.curve);
    }
  } else {
    s.notes.push_back("no held-out score: the halves are too short or their fit failed");
  }
  // The baseline's exact OAVAR: the EDFs every refit weighs the curve with, and its OAVAR view.
  s.baseline_theory = ExactOavar(s.baseline_model, ctx.curve.m, ctx.curve.num_samples);
  ctx.curve_edf = s.baseline_theory.edf;
  std::string note;
  ReportProgress(ctx, "views", 0, 0);
  s.before = Assess(ctx, s.baseline_model, true, options.seed, &note, &s.baseline_theory);
  if (!note.empty()) s.notes.push_back("envelope: " + note);
  if (ctx.have_halves) {
    s.before.heldout = ctx.halves[1].against_other_baseline;
    s.before.has_heldout = true;
  }
  Finish(ctx, &s);
  s.block_means = RecordBlockMeans(rate, sample_clock.period_s(), s);
  s.ok = true;
  return true;
}

bool DiagnoseCurve(const DiagnoseOptions& options, const estimators::AvarCurve& curve,
                   DiagnosisSummary* summary) {
  DiagnosisSummary& s = *summary;
  s = DiagnosisSummary{};
  if (!CommonChecks(options, summary)) return false;
  std::string why;
  if (!curve.IsValid(&why)) {
    s.message = why;
    return false;
  }
  if (curve.num_samples <= 0 || curve.estimator != sim::AvarEstimatorKind::kOverlapping) {
    s.message = "curve mode needs an overlapping curve and its record length";
    return false;
  }
  if (curve.size() < kMinTaus) {
    s.message = "the curve has " + std::to_string(curve.size()) + " taus (need " + std::to_string(kMinTaus) + ")";
    return false;
  }
  Context ctx;
  ctx.options = &options;
  ctx.curve = curve;
  s.curve_mode = true;
  s.num_samples = curve.num_samples;
  s.sample_clock = curve.sample_clock;
  std::string fallback;
  s.baseline_source = options.baseline;
  if (!FitBaseline(options, curve, &ctx.spec, &s.baseline, &fallback, &s.message)) return false;
  if (!fallback.empty()) s.notes.push_back("baseline: " + fallback);
  s.baseline_model = ctx.spec.Model(s.baseline, curve.sample_clock);
  s.curve = curve;
  ctx.layout.sample_clock = curve.sample_clock;
  ctx.layout.num_samples = curve.num_samples;
  ctx.layout.oavar_m = curve.m;
  s.baseline_theory = ExactOavar(s.baseline_model, curve.m, curve.num_samples);
  ctx.curve_edf = s.baseline_theory.edf;
  std::string note;
  s.before = Assess(ctx, s.baseline_model, false, options.seed, &note, &s.baseline_theory);
  s.notes.push_back("curve mode: OAVAR view only (exact distribution), no held-out score");
  Finish(ctx, &s);
  s.ok = true;
  return true;
}

}  // namespace allanlab::experiments

