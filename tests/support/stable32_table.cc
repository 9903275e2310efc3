#include "tests/support/stable32_table.h"

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace allanlab::testing_support {
namespace {

std::ifstream Open(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  return in;
}

bool IsContent(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first != std::string::npos && line[first] != '#';
}

}  // namespace

std::vector<Stable32Row> ReadStable32Table(const std::string& path) {
  std::ifstream in = Open(path);
  std::vector<Stable32Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (!IsContent(line)) continue;
    std::istringstream fields(line);
    Stable32Row r;
    if (!(fields >> r.m >> r.tau_s >> r.terms >> r.alpha >> r.min_sigma >> r.sigma >>
          r.max_sigma)) {
      throw std::runtime_error(path + ": cannot parse row '" + line + "'");
    }
    rows.push_back(r);
  }
  return rows;
}

std::vector<double> ReadDataColumn(const std::string& path) {
  std::ifstream in = Open(path);
  std::vector<double> values;
  std::string line;
  while (std::getline(in, line)) {
    if (!IsContent(line)) continue;
    std::istringstream fields(line);
    double v = 0.0;
    if (!(fields >> v)) throw std::runtime_error(path + ": cannot parse '" + line + "'");
    values.push_back(v);
  }
  return values;
}

estimators::Interval Stable32Interval(double variance, double edf) {
  constexpr double kConfidence = 0.683;
  constexpr double kExactUpTo = 100.0;
  if (edf <= kExactUpTo) return estimators::ChiSquareInterval(variance, edf, kConfidence);
  const double z = boost::math::quantile(boost::math::normal(), 0.84);
  const double s = std::sqrt(2.0 / (9.0 * edf));
  auto quantile = [&](double zz) { return edf * std::pow(1.0 - s * s + zz * s, 3); };
  return {variance * edf / quantile(z), variance * edf / quantile(-z)};
}

::testing::AssertionResult NearRelative(const char* what, double actual, double expected,
                                        double tol) {
  if (std::abs(actual / expected - 1.0) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << what << ": expected " << expected << ", got " << actual << ", relative error "
         << actual / expected - 1.0 << ", tolerance " << tol;
}

::testing::AssertionResult MatchesStable32Interval(double variance, double edf,
                                                   const Stable32Row& row) {
  const estimators::Interval s32 = Stable32Interval(variance, edf);
  const double tol = 1.5e-4 + 2e-3 / edf;
  auto low = NearRelative("min sigma", std::sqrt(s32.low), row.min_sigma, tol);
  if (!low) return low << " (edf " << edf << ")";
  auto high = NearRelative("max sigma", std::sqrt(s32.high), row.max_sigma, tol);
  if (!high) return high << " (edf " << edf << ")";
  return ::testing::AssertionSuccess();
}

}  // namespace allanlab::testing_support
