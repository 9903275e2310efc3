#include "experiments/injected_fault.h"

#include <cstdlib>

namespace allanlab::experiments {
namespace {

double ScaleFromEnvironment(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return 1.0;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return (*end == '\0' && value > 0.0) ? value : 1.0;
}

}  // namespace

double InjectedAvarScale() {
  static const double scale = ScaleFromEnvironment("ALLANLAB_INJECT_AVAR_SCALE");
  return scale;
}

double InjectedCoefficientScale() {
  static const double scale = ScaleFromEnvironment("ALLANLAB_INJECT_COEFFICIENT_SCALE");
  return scale;
}

}  // namespace allanlab::experiments
