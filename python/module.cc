#include <pybind11/pybind11.h>

#include <cctype>
#include <string>
#include <string_view>
#include <utility>

#include "app/reports/provenance.h"
#include "app/commands/subcommand.h"
#include "python/bindings.h"

namespace allanlab::python {
namespace {

// The commands' options as the Python functions name them. Longer spellings first: an option with
// its placeholder ("--preset NAME") before the bare option.
constexpr std::pair<std::string_view, std::string_view> kArgumentNames[] = {
    {"--preset NAME", "preset"},
    {"--sensor SPEC.yaml", "sensor"},
    {"--float LIST", "float_terms"},
    {"--rate HZ", "rate_hz"},
    {"--bootstrap-trials", "bootstrap_trials"},
    {"--band-limit", "band_limit"},
    {"--out-units", "out_units"},
    {"--false-alarm", "false_alarm"},
    {"--confidence", "confidence"},
    {"--uncertainty", "uncertainty"},
    {"--estimator", "estimator"},
    {"--duration", "duration_s"},
    {"--min-tau", "min_tau_s"},
    {"--max-tau", "max_tau_s"},
    {"--no-select", "select_terms=False"},
    {"--method", "method"},
    {"--preset", "preset"},
    {"--sensor", "sensor"},
    {"--trials", "trials"},
    {"--terms", "terms"},
    {"--model", "model"},
    {"--float", "float_terms"},
    {"--trial", "trial"},
    {"--units", "units"},
    {"--taus", "taus"},
    {"--type", "type"},
    {"--rate", "rate_hz"},
    {"--seed", "seed"},
    {"--ci", "ci"},
};

bool OptionCharacter(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

// The message with every command-line option the Python functions take named as their argument.
std::string WithArgumentNames(const std::string& message) {
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    bool replaced = false;
    if (message.compare(i, 2, "--") == 0 && (i == 0 || !OptionCharacter(message[i - 1]))) {
      for (const auto& [option, argument] : kArgumentNames) {
        const std::size_t end = i + option.size();
        if (message.compare(i, option.size(), option) == 0 &&
            (end == message.size() || !OptionCharacter(message[end]))) {
          out += argument;
          i = end;
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += message[i++];
  }
  return out;
}

}  // namespace

void Raise(int exit_code, const std::string& message) {
  const std::string text = WithArgumentNames(message);
  if (exit_code == app::kExitUsageError) throw pybind11::value_error(text);
  throw std::runtime_error(text);
}

}  // namespace allanlab::python

PYBIND11_MODULE(_allanlab, m) {
  m.doc() = "allanlab's commands on records in memory (use the allanlab package, not this module)";
  m.attr("version") = allanlab::app::VersionLine();
  allanlab::python::AddRecordFunctions(m);
  allanlab::python::AddCurveFunctions(m);
}
