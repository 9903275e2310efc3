#include "estimators/tau_grid.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string_view>

#include "common/number_text.h"

namespace allanlab::estimators {
namespace {

constexpr int kMaxPointsPerDecade = 1000;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// from_chars, not strtod: no locale, and the whole field must be the number.
bool ParseNumber(std::string_view text, double* value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

// Nearest averaging factor of a tau, saturating instead of overflowing for absurd taus.
std::int64_t NearestFactor(double tau_s, double tau0_s) {
  const double m = std::round(tau_s / tau0_s);
  constexpr double kLimit = static_cast<double>(std::numeric_limits<std::int64_t>::max() / 4);
  if (!(m > 0.0)) return 0;
  return m >= kLimit ? static_cast<std::int64_t>(kLimit) : static_cast<std::int64_t>(m);
}

}  // namespace

bool TauGridOptions::Parse(const std::string& text, TauGridOptions* grid, std::string* why) {
  const std::string_view s = Trim(text);
  TauGridOptions parsed;
  if (s == "octave") {
    parsed.kind = TauGridKind::kOctave;
  } else if (s == "decade") {
    parsed.kind = TauGridKind::kDecade125;
  } else if (s == "all") {
    parsed.kind = TauGridKind::kAll;
  } else if (s.starts_with("dense:")) {
    const std::string_view k = Trim(s.substr(6));
    int points = 0;
    auto [ptr, ec] = std::from_chars(k.data(), k.data() + k.size(), points);
    if (ec != std::errc() || ptr != k.data() + k.size() || k.empty()) {
      *why = "tau grid '" + text + "': expected dense:K with an integer K points per decade";
      return false;
    }
    parsed.kind = TauGridKind::kLogDense;
    parsed.points_per_decade = points;
  } else {
    parsed.kind = TauGridKind::kExplicit;
    std::string_view rest = s;
    while (true) {
      const std::size_t comma = rest.find(',');
      const std::string_view field = Trim(rest.substr(0, comma));
      double tau = 0.0;
      if (!ParseNumber(field, &tau)) {
        *why = "tau grid '" + text +
               "': expected octave, decade, dense:K, all or a comma list of taus in seconds; '" +
               std::string(field) + "' is not a number";
        return false;
      }
      parsed.explicit_taus_s.push_back(tau);
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
  }
  if (!parsed.IsValid(why)) {
    *why = "tau grid '" + text + "': " + *why;
    return false;
  }
  *grid = std::move(parsed);
  return true;
}

bool TauGridOptions::IsValid(std::string* why) const {
  switch (kind) {
    case TauGridKind::kOctave:
    case TauGridKind::kDecade125:
    case TauGridKind::kAll:
      return true;
    case TauGridKind::kLogDense:
      if (points_per_decade < 1 || points_per_decade > kMaxPointsPerDecade) {
        *why = "points per decade must be in [1, " + std::to_string(kMaxPointsPerDecade) +
               "], got " + std::to_string(points_per_decade);
        return false;
      }
      return true;
    case TauGridKind::kExplicit:
      if (explicit_taus_s.empty()) {
        *why = "an explicit tau grid needs at least one tau";
        return false;
      }
      for (double tau : explicit_taus_s) {
        if (!std::isfinite(tau) || tau <= 0.0) {
          *why = "taus must be finite and > 0 s, got " + SignificantDigits(tau, 9);
          return false;
        }
      }
      return true;
  }
  *why = "unknown tau grid kind";
  return false;
}

std::vector<std::int64_t> CandidateAveragingFactors(const TauGridOptions& grid, double tau0_s,
                                                    std::int64_t max_m) {
  std::vector<std::int64_t> ms;
  switch (grid.kind) {
    case TauGridKind::kOctave:
      for (std::int64_t m = 1; m <= max_m; m *= 2) {
        ms.push_back(m);
        if (m > max_m / 2) break;  // the next doubling would overflow or pass max_m
      }
      break;
    case TauGridKind::kDecade125:
      for (std::int64_t decade = 1; decade <= max_m; decade *= 10) {
        for (std::int64_t step : {1, 2, 5}) {
          if (step <= max_m / decade) ms.push_back(step * decade);
        }
        if (decade > max_m / 10) break;
      }
      break;
    case TauGridKind::kLogDense: {
      // Each point is 10^(k/K) afresh rather than a running product, so rounding cannot drift
      // along a long grid.
      const double k_per_decade = grid.points_per_decade;
      for (int k = 0;; ++k) {
        const double m = std::round(std::pow(10.0, k / k_per_decade));
        if (m > static_cast<double>(max_m)) break;
        const auto mi = static_cast<std::int64_t>(m);
        if (ms.empty() || ms.back() != mi) ms.push_back(mi);
      }
      break;
    }
    case TauGridKind::kAll:
      for (std::int64_t m = 1; m <= max_m; ++m) ms.push_back(m);
      break;
    case TauGridKind::kExplicit: {
      std::set<std::int64_t> distinct;
      for (double tau : grid.explicit_taus_s) {
        const std::int64_t m = NearestFactor(tau, tau0_s);
        if (m <= max_m) distinct.insert(m);
      }
      ms.assign(distinct.begin(), distinct.end());
      break;
    }
  }
  return ms;
}

}  // namespace allanlab::estimators
