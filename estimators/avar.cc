#include "estimators/avar.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/piece_sharing.h"
#include "estimators/allan_family.h"
#include "estimators/confidence.h"
#include "estimators/estimate_distribution.h"
#include "estimators/noise_identification.h"
#include "estimators/phase_checkpoints.h"
#include "estimators/record_edf.h"

namespace allanlab::estimators {
namespace {

void AppendNote(const std::string& note, std::string* message) {
  if (!message->empty()) *message += "; ";
  *message += note;
}

// The integrated record as identification and the record EDF read it: the whole record, or its
// checkpoints (phase_checkpoints.h), from which only the values they read are rebuilt.
struct RecordPhase {
  std::span<const double> whole;
  const PhaseCheckpoints* checkpoints = nullptr;
};

// Identification at one tau, on the middle options.identification_max_averages m-averages
// when the record has more (avar_summary.h).
NoiseId IdentifyAt(const AvarOptions& options, std::span<const double> rate, const RecordPhase& phase,
                   std::int64_t m) {
  const std::int64_t cap = options.identification_max_averages;
  const std::int64_t count = m > 0 ? static_cast<std::int64_t>(rate.size()) / m : 0;
  const bool capped = !(cap <= 0 || count <= cap);
  const std::int64_t first = capped ? (count - cap) / 2 * m : 0;
  const std::int64_t length = capped ? cap * m : static_cast<std::int64_t>(rate.size());
  if (phase.checkpoints != nullptr) {
    if (m < 1 || length < m) return {};
    const PhaseCheckpoints& x = *phase.checkpoints;
    std::vector<double> sampled(static_cast<std::size_t>(length / m + 1));
    x.Decimate(first, m, sampled);
    return IdentifyNoiseFromSampledPhase(
        sampled, m, [&] { return ModifiedToAllanRatioOfCheckpoints(x, first, length, m); });
  }
  if (!capped) return IdentifyNoise(rate, phase.whole, m);
  const auto from = static_cast<std::size_t>(first);
  const auto size = static_cast<std::size_t>(length);
  return IdentifyNoise(rate.subspan(from, size),
                       phase.whole.size() == rate.size() + 1 ? phase.whole.subspan(from, size + 1) : phase.whole, m);
}

// RecordEdf of the record, from the stretch it reads alone when only checkpoints are kept.
double RecordEdfOf(Statistic s, const RecordPhase& phase, std::int64_t n_rate, std::int64_t m) {
  if (phase.checkpoints == nullptr) return RecordEdf(s, phase.whole, m);
  const RecordEdfStretch reads = RecordEdfReads(s, n_rate, m);
  if (reads.hi < reads.lo) return 0.0;
  std::vector<double> stretch(static_cast<std::size_t>(reads.hi - reads.lo + 1));
  phase.checkpoints->Rebuild(reads.lo, stretch);
  return RecordEdfFromStretch(s, n_rate, stretch, m);
}

// The exponent a point uses, and whether it was read at that point's own tau.
struct PointAlpha {
  int alpha = 0;
  bool read_here = true;
};

// kAuto at a tau with few m-averages: the shorter tau's exponent unless the unrounded estimate
// is more than one step from it, and never a phase noise (alpha > 0) after a frequency noise. In
// a sum of power laws the term that dominates at longer taus has the steeper Allan slope, so the
// exponent cannot rise into phase noise (AVAR ~ 1/tau^2 fades fastest); such a reading at few
// averages is the ACF's scatter, and its Greenhall-Riley EDF is several times too large.
PointAlpha SteadyAlpha(const AvarOptions& options, const NoiseId& id, int previous, bool first) {
  if (options.confidence_method != ConfidenceMethod::kAuto || first ||
      id.averages >= kSteadyIdentificationAverages || !std::isfinite(id.estimate)) {
    return {id.alpha, true};
  }
  // At few clusters the reading scatters by a step or more (random-walk records at 8 clusters read
  // as flicker or white in 4 of 10), and there the interval rests on alpha's whole distribution
  // (estimate_distribution.h): the longer-averaged reading stands, and this tau's is not used.
  if (id.averages <= kDistributionIntervalMaxClusters) return {previous, false};
  if (std::abs(id.estimate - previous) <= 1.0) return {previous, true};
  return {id.alpha > std::max(previous, 0) ? previous : id.alpha, true};
}

// What each tau's point needs from the record, measured for every tau before the choices that
// chain the taus (SteadyAlpha) are made in order: its noise identification and, for --ci auto,
// the record's EDF where it is available (0 elsewhere). Each tau's measures depend neither on
// the others nor on the thread, so on long records this thread and a helper share them
// (common/piece_sharing.h), the costliest first: the record EDF at the longest lag windows, then
// the identifications from the longest m down.
struct TauMeasures {
  std::vector<NoiseId> ids;         // empty when alpha is fixed
  std::vector<double> record_edfs;  // one per point
};

// Below this many samples the measures take well under a millisecond: no helper.
constexpr std::size_t kSharedMeasuresSamples = std::size_t{1} << 20;

// `rest` (may be null): the rest of the Allan pass, run as the first piece beside the measures.
TauMeasures MeasureEveryTau(const AvarOptions& options, std::span<const double> rate, const RecordPhase& phase,
                            std::span<const std::int64_t> ms, const std::function<void()>* rest = nullptr) {
  TauMeasures t;
  const auto n_rate = static_cast<std::int64_t>(rate.size());
  t.record_edfs.assign(ms.size(), 0.0);
  if (!options.alpha_fixed) t.ids.resize(ms.size());
  std::vector<std::size_t> edf_points;  // longest m first
  for (std::size_t k = ms.size(); k-- > 0;) {
    if (options.confidence_method == ConfidenceMethod::kAuto &&
        RecordEdfAvailable(options.statistic, ms[k], n_rate)) {
      edf_points.push_back(k);
    }
  }
  const int first = rest != nullptr ? 1 : 0;
  const auto edf_count = static_cast<int>(edf_points.size());
  const std::function<void(int)> piece = [&](int p) {
    p -= first;
    if (p < 0) {
      (*rest)();
    } else if (p < edf_count) {
      const std::size_t k = edf_points[static_cast<std::size_t>(p)];
      t.record_edfs[k] = RecordEdfOf(options.statistic, phase, n_rate, ms[k]);
    } else {
      // The longest m first: its identification reads the most (up to the whole record for
      // R(n)), and a long piece left for last keeps the other thread waiting.
      const std::size_t k = t.ids.size() - 1 - static_cast<std::size_t>(p - edf_count);
      t.ids[k] = IdentifyAt(options, rate, phase, ms[k]);
    }
  };
  const int count = first + edf_count + static_cast<int>(t.ids.size());
  if (rate.size() >= kSharedMeasuresSamples && PieceSharing::Useful()) {
    PieceSharing sharing;
    sharing.Run(count, piece);
  } else {
    for (int p = 0; p < count; ++p) piece(p);
  }
  return t;
}

// Noise exponent of every point: fixed, or identified from the record. Where identification
// cannot run (fewer than three m-averages, e.g. TOTVAR beyond n/3), the nearest shorter tau's
// exponent stands in: noise type changes slowly with tau, and white FM (0) is the neutral start.
// A point whose exponent was not read at its own tau says so (alpha_identified false).
int AssignNoiseExponents(const AvarOptions& options, const TauMeasures& measures,
                         std::vector<AvarPoint>* points) {
  int unidentified = 0;
  int previous = 0;
  for (std::size_t k = 0; k < points->size(); ++k) {
    AvarPoint& point = (*points)[k];
    if (options.alpha_fixed) {
      point.alpha = options.alpha;
      continue;
    }
    const NoiseId& id = measures.ids[k];
    point.alpha_identified = id.identified;
    if (id.identified) {
      const PointAlpha steady = SteadyAlpha(options, id, previous, &point == &points->front());
      previous = steady.alpha;
      point.alpha_identified = steady.read_here;
    } else {
      ++unidentified;
    }
    point.alpha = previous;
  }
  return unidentified;
}

// record_edf: RecordEdf(options.statistic, phase, m) where --ci auto uses it (TauMeasures).
double PointEdf(const AvarOptions& options, const RecordPhase& phase, AvarPoint* point,
                std::int64_t n_rate, double record_edf) {
  switch (options.confidence_method) {
    case ConfidenceMethod::kNone:
      return 0.0;
    case ConfidenceMethod::kSimple:
      return SimpleEdf(n_rate / point->m);
    case ConfidenceMethod::kGreenhallRiley:
      return StatisticEdf(options.statistic, point->alpha, point->m, n_rate,
                          options.sample_clock.period_s());
    case ConfidenceMethod::kAuto:
      if (RecordEdfAvailable(options.statistic, point->m, n_rate)) {
        const double edf = record_edf;
        if (edf > 0.0) {
          point->edf_from_record = true;
          return edf;
        }
      }
      if (options.statistic == Statistic::kTotal) {
        // Bounded by OAVAR's EDF at the same m, measured on the record where it can be.
        double oavar = 0.0;
        if (RecordEdfAvailable(Statistic::kAllanOverlapping, point->m, n_rate)) {
          oavar = RecordEdfOf(Statistic::kAllanOverlapping, phase, n_rate, point->m);
        }
        if (!(oavar > 0.0)) {
          oavar = StatisticEdf(Statistic::kAllanOverlapping, point->alpha, point->m, n_rate,
                               options.sample_clock.period_s());
        }
        return BoundTotalVarianceEdf(
            StatisticEdf(Statistic::kTotal, point->alpha, point->m, n_rate, options.sample_clock.period_s()),
            oavar, point->m, n_rate);
      }
      return StatisticEdf(options.statistic, point->alpha, point->m, n_rate,
                          options.sample_clock.period_s());
  }
  return 0.0;
}

// Values, then exponents, EDF and intervals. `workspace` keeps the integrated record, from which
// identification takes its averages.
bool Compute(const AvarOptions& options, std::span<const double> rate, AvarSummary* summary,
             AllanFamilyWorkspace* workspace) {
  // Once the pass has the whole integrated record, the taus are measured on it while the pass
  // finishes its long lags: the measures are mostly arithmetic, the long lags mostly memory
  // traffic, so a helper thread overlaps them.
  TauMeasures measures;
  bool measured = false;
  workspace->SetPhaseReady([&](std::span<const std::int64_t> lags, const std::function<void()>& rest) {
    const std::span<const double> whole = workspace->Phase(rate.size() + 1);
    if (!std::isfinite(whole.back())) {  // the pass fails: nothing to measure
      rest();
      return;
    }
    measures = MeasureEveryTau(options, rate, RecordPhase{whole, nullptr}, lags, &rest);
    measured = true;
  });
  const bool ok = ComputeStatisticValues(options, rate, summary, workspace);
  workspace->SetPhaseReady(nullptr);
  if (!ok) return false;
  RecordPhase phase;
  phase.checkpoints = workspace->Checkpoints();
  if (phase.checkpoints == nullptr) phase.whole = workspace->Phase(rate.size() + 1);
  if (!measured) {
    std::vector<std::int64_t> ms;
    for (const AvarPoint& point : summary->points) ms.push_back(point.m);
    measures = MeasureEveryTau(options, rate, phase, ms);
  }
  const int unidentified = AssignNoiseExponents(options, measures, &summary->points);
  if (unidentified > 0) {
    AppendNote("noise type not identifiable at " + std::to_string(unidentified) +
                   " tau(s) (too few averages): the next shorter tau's alpha used",
               &summary->message);
  }
  const auto n_rate = static_cast<std::int64_t>(rate.size());
  for (std::size_t k = 0; k < summary->points.size(); ++k) {
    AvarPoint& point = summary->points[k];
    point.edf = PointEdf(options, phase, &point, n_rate, measures.record_edfs[k]);
    if (point.edf > 0.0) {
      // kAuto at few clusters: the estimate's own distribution at the point's alpha, where
      // chi-square(EDF) misses the nominal level (estimate_distribution.h).
      point.ci_from_distribution =
          options.confidence_method == ConfidenceMethod::kAuto &&
          n_rate / point.m <= kDistributionIntervalMaxClusters &&
          EstimateQuantilesAt(options.statistic, point.alpha, point.m, n_rate, options.confidence).ok;
      const Interval interval = PointInterval(*summary, point, options.confidence);
      point.ci_low = interval.low;
      point.ci_high = interval.high;
    }
  }
  if (options.confidence_method == ConfidenceMethod::kSimple) {
    AppendNote("intervals: seed paper's simple formula, EDF = K - 1 for K = floor(N/m) clusters",
               &summary->message);
  }
  return true;
}

}  // namespace

Interval PointInterval(const AvarSummary& summary, const AvarPoint& point, double confidence) {
  if (!(point.edf > 0.0)) return {0.0, std::numeric_limits<double>::infinity()};
  if (!point.ci_from_distribution) return ChiSquareInterval(point.value, point.edf, confidence);
  const EstimateQuantiles q = EstimateQuantilesAt(summary.options.statistic, point.alpha, point.m,
                                                  summary.num_samples, confidence);
  if (!q.ok) return {0.0, std::numeric_limits<double>::infinity()};
  return {point.value / q.high, point.value / q.low};
}

bool ComputeAvar(const AvarOptions& options, std::span<const double> data, AvarSummary* summary) {
  std::vector<double> differenced;
  std::span<const double> rate = data;
  if (options.input == InputKind::kAngle) {
    differenced = AngleToRate(data, options.sample_clock.period_s());
    rate = differenced;
  }
  AllanFamilyWorkspace workspace;
  if (rate.size() >= kCheckpointMinSamples) workspace.KeepCheckpointsOnly();
  return Compute(options, rate, summary, &workspace);
}

bool ComputeAvar(const AvarOptions& options, std::span<const double> data, AvarSummary* summary,
                 std::span<double> phase) {
  if (options.input != InputKind::kRate || data.size() >= kCheckpointMinSamples || phase.size() != data.size() + 1) {
    return ComputeAvar(options, data, summary);
  }
  AllanFamilyWorkspace workspace;
  workspace.AdoptPhase(phase);
  return Compute(options, data, summary, &workspace);
}

bool ComputeAvarFromCheckpoints(const AvarOptions& options, PhaseCheckpoints checkpoints, AvarSummary* summary) {
  if (options.input != InputKind::kRate) return ComputeAvar(options, checkpoints.rate(), summary);
  const std::span<const double> rate = checkpoints.rate();
  AllanFamilyWorkspace workspace;
  workspace.AdoptCheckpoints(std::move(checkpoints));
  return Compute(options, rate, summary, &workspace);
}

bool ComputeAvarOnStorage(const AvarOptions& options, std::span<double> storage,
                          AvarSummary* summary) {
  if (storage.empty()) return ComputeAvar(options, {}, summary);  // no spare slot: no samples
  std::span<double> phase = storage;
  if (options.input == InputKind::kAngle && storage.size() >= 2) {
    // rate_k = (angle_{k+1} - angle_k) / tau0 into the slot of angle_{k+1}, from the top down, so
    // that each angle is read before its slot is written; the first angle's slot becomes the
    // integrated record's spare.
    const double tau0 = options.sample_clock.period_s();
    for (std::size_t k = storage.size(); k-- > 2;) storage[k] = (storage[k] - storage[k - 1]) / tau0;
    phase = storage.subspan(1);
  }
  AllanFamilyWorkspace workspace;
  workspace.AdoptPhase(phase);
  return Compute(options, phase.subspan(1), summary, &workspace);
}

bool ComputeAvarInPlace(const AvarOptions& options, std::vector<double>* record,
                        AvarSummary* summary) {
  record->insert(record->begin(), 0.0);
  return ComputeAvarOnStorage(options, *record, summary);
}

}  // namespace allanlab::estimators
