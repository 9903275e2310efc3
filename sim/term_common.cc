#include "sim/term_common.h"

#include <cmath>
#include <sstream>

#include <boost/random/normal_distribution.hpp>

namespace allanlab::sim {
namespace {
bool Fail(std::string_view name, double v, std::string_view rule, std::string* why) {
  if (why) {
    std::ostringstream os;
    os << name << " must be " << rule << ", got " << v;
    *why = os.str();
  }
  return false;
}
}  // namespace

bool CheckNonNegative(double v, std::string_view name, std::string* why) {
  if (!std::isfinite(v) || v < 0.0) return Fail(name, v, "a finite number >= 0", why);
  return true;
}

bool CheckPositive(double v, std::string_view name, std::string* why) {
  if (!std::isfinite(v) || v <= 0.0) return Fail(name, v, "a finite number > 0", why);
  return true;
}

void AddGaussian(Engine& engine, double std_dev, std::span<double> out) {
  if (std_dev == 0.0) return;
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  for (double& v : out) v += std_dev * normal(engine);
}

}  // namespace allanlab::sim
