#include "app/input/record_support.h"

#include <cmath>

#include "app/reports/provenance.h"
#include "common/number_text.h"

namespace allanlab::app {
int SupportedOctaveTaus(std::int64_t samples) {
  int octaves = 0;
  for (std::int64_t m = 1; m <= samples / kMinClusters; m *= 2) ++octaves;
  return octaves;
}

bool CheckRecordSupportsFit(std::int64_t samples, double sample_rate_hz, int parameters,
                            std::string* why) {
  const int have = SupportedOctaveTaus(samples);
  if (have >= parameters + 1) return true;
  const std::int64_t needed = kMinClusters << parameters;
  *why = (SignificantDigits(static_cast<double>(samples) / sample_rate_hz, 3) + " s") + " (" + std::to_string(samples) +
         " samples at " + ShortestDecimal(sample_rate_hz) + " Hz) gives " + std::to_string(have) +
         " octave tau(s) with at least " + std::to_string(kMinClusters) +
         " clusters (tau <= T/" + std::to_string(kMinClusters) + "); fitting " +
         std::to_string(parameters) + " parameter(s) needs " + std::to_string(parameters + 1) +
         ": record at least " + (SignificantDigits(static_cast<double>(needed) / sample_rate_hz, 3) + " s") + " (" +
         std::to_string(needed) + " samples), or fit fewer terms (--terms)";
  return false;
}

std::vector<std::string> WeaklySupportedTerms(const std::vector<double>& tau_s,
                                              const std::vector<std::int64_t>& m,
                                              std::int64_t samples,
                                              const std::vector<FittedTermAvar>& terms) {
  std::vector<std::string> warnings;
  const std::int64_t longest_m = samples / kMinClusters;
  std::vector<double> total(tau_s.size(), 0.0);
  for (const FittedTermAvar& t : terms) {
    for (std::size_t k = 0; k < total.size(); ++k) total[k] += t.avar[k];
  }
  for (const FittedTermAvar& t : terms) {
    bool dominates = false, supported = false;
    double from_tau = 0.0;
    for (std::size_t k = 0; k < tau_s.size(); ++k) {
      if (!(t.avar[k] > 0.5 * total[k])) continue;
      if (!dominates) from_tau = tau_s[k];
      dominates = true;
      supported |= m[k] <= longest_m;
    }
    if (!dominates || supported) continue;
    warnings.push_back(t.name + " exceeds half of the fitted curve only from tau " +
                       (SignificantDigits(from_tau, 3) + " s") + ", above T/" + std::to_string(kMinClusters) + " = " +
                       (SignificantDigits(static_cast<double>(longest_m) * tau_s.front() /
                               static_cast<double>(m.front()), 3) + " s") +
                       " where fewer than " + std::to_string(kMinClusters) +
                       " clusters average: its value rests on the last few clusters of the "
                       "record; record longer to measure it");
  }
  return warnings;
}

}  // namespace allanlab::app
