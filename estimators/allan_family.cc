#include "estimators/allan_family.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "estimators/difference_sums.h"
#include "estimators/modified_allan_sums.h"
#include "estimators/phase_integral.h"
#include "estimators/total_variance_sums.h"
#include "common/huge_pages.h"
#include "common/number_text.h"

namespace allanlab::estimators {
namespace {

// Why a candidate m is not reported, or empty if it is.
std::string DropReason(const AvarOptions& options, std::int64_t m, std::int64_t n) {
  const Statistic s = options.statistic;
  const std::string name(StatisticId(s));
  if (m < 1) {
    return "tau rounds to m = 0: below half the sample period " +
           SignificantDigits(options.sample_clock.period_s(), 9) + " s";
  }
  const std::int64_t max_m = MaxAveragingFactor(s, n);
  if (m > max_m) {
    return "m = " + std::to_string(m) + " exceeds the largest averaging factor " +
           std::to_string(max_m) + " of the " + name + " statistic on " + std::to_string(n) +
           " samples (0 terms)";
  }
  const std::int64_t terms = TermCount(s, m, n);
  if (terms < options.min_terms) {
    return "only " + std::to_string(terms) + " terms at m = " + std::to_string(m) +
           ", fewer than min_terms = " + std::to_string(options.min_terms);
  }
  return {};
}

// The variances from the sums of squared phase differences (x in rate x tau0 units, so tau0
// cancels): NIST SP 1065 eqs. for AVAR/OAVAR (sum / 2 m^2 T), HVAR/OHVAR (sum / 6 m^2 T), MVAR
// (sum / 2 m^4 T, the inner sum of m second differences), TOTVAR (sum / 2 m^2 (n - 1)).
std::vector<double> Scaled(Statistic s, std::int64_t n, std::span<const std::int64_t> ms,
                           std::span<const double> sums) {
  std::vector<double> values(ms.size());
  for (std::size_t k = 0; k < ms.size(); ++k) {
    const auto m = static_cast<double>(ms[k]);
    const auto terms = static_cast<double>(TermCount(s, ms[k], n));
    const double scale = DifferenceOrder(s) == 3 ? 6.0 : 2.0;
    const double m_power = IsModified(s) ? m * m * m * m : m * m;
    values[k] = sums[k] / (scale * m_power * terms);
  }
  return values;
}

// Empty when the record is not finite (a NaN or infinity anywhere reaches the end of the phase).
// workspace null: the caller does not need the phase afterwards, so the overlapping statistics
// may rebuild it in cache instead of storing it (difference_sums.h).
std::vector<double> Variances(Statistic s, std::span<const double> rate,
                              std::span<const std::int64_t> ms, AllanFamilyWorkspace* workspace) {
  const auto n = static_cast<std::int64_t>(rate.size());
  const double reference = ReferenceLevel(rate);
  std::vector<double> sums(ms.size());
  const bool overlapping = s == Statistic::kAllanOverlapping || s == Statistic::kHadamardOverlapping;
  double last_phase = 0.0;
  AllanFamilyWorkspace local;
  if (overlapping && workspace == nullptr &&
      SumOverlappingDifferencesFromRate(rate, reference, DifferenceOrder(s), ms, sums,
                                        &last_phase)) {
    if (!std::isfinite(last_phase)) return {};
    return Scaled(s, n, ms, sums);
  }
  if (overlapping && workspace != nullptr && workspace->checkpoints_only() &&
      FitsCheckpointPass(n, DifferenceOrder(s), ms)) {
    const PhaseCheckpoints& x = workspace->SetCheckpoints(rate, reference);
    if (!std::isfinite(x.Last())) return {};
    SumOverlappingDifferencesFromCheckpoints(x, DifferenceOrder(s), ms, sums);
    return Scaled(s, n, ms, sums);
  }
  if (workspace == nullptr) workspace = &local;
  const std::span<double> phase = workspace->Phase(rate.size() + 1);
  const AllanFamilyWorkspace::PhaseReadyHook& hook = workspace->phase_ready();
  if (overlapping) {
    const PhaseReady ready = [&](const std::function<void()>& rest) { hook(ms, rest); };
    IntegrateAndSumOverlappingDifferences(rate, reference, DifferenceOrder(s), ms, phase, sums,
                                          hook ? &ready : nullptr);
    if (!std::isfinite(phase.back())) return {};
  } else {
    IntegrateAbout(rate, reference, phase);
    if (!std::isfinite(phase.back())) return {};
    const std::function<void()> rest = [&] {
      switch (s) {
        case Statistic::kAllanNonOverlapping:
        case Statistic::kHadamardNonOverlapping:
          StridedDifferenceSums(phase, DifferenceOrder(s), ms, sums);
          break;
        case Statistic::kModifiedAllan:
        case Statistic::kTime: {
          const auto work = static_cast<std::size_t>(ModifiedAllanWorkSize(n, ms));
          ModifiedAllanSums(phase, ms, workspace->Scratch(work), sums);
          break;
        }
        case Statistic::kTotal:
          TotalVarianceSums(phase, ms, sums);
          break;
        case Statistic::kAllanOverlapping:
        case Statistic::kHadamardOverlapping:
          break;  // above
      }
    };
    if (hook) {
      hook(ms, rest);
    } else {
      rest();
    }
  }
  return Scaled(s, n, ms, sums);
}

}  // namespace

std::span<double> AllanFamilyWorkspace::Buffer::Get(std::size_t size) {
  if (size > capacity_) {
    data_.reset();  // release first: peak memory is the new size, not old + new
    data_ = std::make_unique_for_overwrite<double[]>(size);
    AdviseHugePages(data_.get(), size * sizeof(double));
    capacity_ = size;
  }
  return {data_.get(), size};
}

bool ComputeStatisticValues(const AvarOptions& options, std::span<const double> rate,
                            AvarSummary* summary) {
  return ComputeStatisticValues(options, rate, summary, nullptr);
}

bool ComputeStatisticValues(const AvarOptions& options, std::span<const double> rate,
                            AvarSummary* summary, AllanFamilyWorkspace* workspace) {
  *summary = AvarSummary{};
  if (workspace != nullptr) workspace->ClearCheckpoints();
  summary->options = options;
  const auto n = static_cast<std::int64_t>(rate.size());
  summary->num_samples = n;
  std::string why;
  if (!options.IsValid(&why)) {
    summary->message = "invalid options: " + why;
    return false;
  }
  if (n < 3) {
    summary->message = "need at least 3 rate samples, got " + std::to_string(n);
    return false;
  }
  const Statistic s = options.statistic;
  const double tau0 = options.sample_clock.period_s();
  // Generated grids stop at the statistic's largest m; explicit taus all come back, so that
  // the ones beyond it are reported rather than silently skipped.
  const std::int64_t limit = options.taus.kind == TauGridKind::kExplicit
                                 ? std::numeric_limits<std::int64_t>::max()
                                 : MaxAveragingFactor(s, n);
  std::vector<std::int64_t> used;
  for (std::int64_t m : CandidateAveragingFactors(options.taus, tau0, limit)) {
    std::string reason = DropReason(options, m, n);
    if (reason.empty()) {
      used.push_back(m);
    } else {
      summary->dropped.push_back({static_cast<double>(m) * tau0, m, std::move(reason)});
    }
  }
  if (used.empty()) {
    summary->message = "no averaging time has enough terms on " + std::to_string(n) + " samples (" +
                       std::to_string(summary->dropped.size()) + " dropped)";
    return false;
  }

  const std::vector<double> values = Variances(s, rate, used, workspace);
  if (values.empty()) {
    // Only now is the record searched: finite data pay for no separate pass.
    summary->dropped.clear();
    if (workspace != nullptr && workspace->Checkpoints() == nullptr &&
        workspace->Phase(rate.size() + 1).data() + 1 == rate.data()) {
      // Integrated in place: the samples are gone, the phase tells where it stopped being finite.
      const std::span<const double> phase = workspace->Phase(rate.size() + 1);
      std::int64_t k = 1;
      while (k < n && std::isfinite(phase[k])) ++k;
      summary->message = "rate sample " + std::to_string(k - 1) +
                         " is not finite, or the running sum overflows there";
      return false;
    }
    for (std::int64_t k = 0; k < n; ++k) {
      if (!std::isfinite(rate[k])) {
        summary->message =
            "rate sample " + std::to_string(k) + " is not finite (" + SignificantDigits(rate[k], 9) + ")";
        return false;
      }
    }
    summary->message = "rate samples too large: their running sum overflows";
    return false;
  }
  summary->points.reserve(used.size());
  for (std::size_t k = 0; k < used.size(); ++k) {
    AvarPoint point;
    point.m = used[k];
    point.tau_s = static_cast<double>(used[k]) * tau0;
    point.terms = TermCount(s, used[k], n);
    // TVAR = tau^2 MVAR / 3 (SP 1065 eq. 17): an angle variance.
    point.value = s == Statistic::kTime ? point.tau_s * point.tau_s * values[k] / 3.0 : values[k];
    summary->points.push_back(point);
  }
  summary->ok = true;
  if (!summary->dropped.empty()) {
    summary->message = std::to_string(summary->dropped.size()) + " tau" +
                       (summary->dropped.size() == 1 ? "" : "s") + " dropped";
  }
  return true;
}

std::vector<double> AngleToRate(std::span<const double> angle, double tau0_s) {
  if (angle.size() < 2) return {};
  std::vector<double> rate(angle.size() - 1);
  for (std::size_t k = 0; k + 1 < angle.size(); ++k) rate[k] = (angle[k + 1] - angle[k]) / tau0_s;
  return rate;
}

}  // namespace allanlab::estimators
