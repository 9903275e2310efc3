#include "experiments/sweep_spec.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "estimators/fit/noise_coefficient.h"
#include "estimators/tau_grid.h"
#include "experiments/registry.h"
#include "sim/embedded_presets.h"
#include "sim/quantity.h"
#include "sim/sensor_spec.h"
#include "common/number_text.h"

namespace allanlab::experiments {
namespace {

// Far more than any sweep runs; catches a product that explodes by mistake.
constexpr std::size_t kMaxPoints = 100000;
// The fewest samples a record may have: a tau grid needs a few clusters to mean anything.
constexpr std::int64_t kMinSamples = 16;
// One record lives in memory as doubles; beyond this it cannot.
constexpr std::int64_t kMaxSamples = 2'000'000'000;

// Thrown by the readers; carries "<key path>: <message>".
struct SpecError {
  std::string message;
};

[[noreturn]] void Fail(const std::string& path, const std::string& message) {
  throw SpecError{path.empty() ? message : path + ": " + message};
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out;
}

std::string Child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string Index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// Rejects keys outside `allowed`; returns the mapping.
YAML::Node CheckMap(const YAML::Node& node, const std::string& path,
                           const std::vector<std::string>& allowed) {
  if (!node.IsMap()) Fail(path, "expected a mapping with keys " + Join(allowed));
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      Fail(Child(path, key), "unknown key (known: " + Join(allowed) + ")");
    }
  }
  return node;
}

std::string Scalar(const YAML::Node& node, const std::string& path) {
  if (!node.IsScalar()) Fail(path, "expected a single value");
  return node.Scalar();
}

std::uint64_t ReadUnsigned(const YAML::Node& node, const std::string& path) {
  const std::string text = Scalar(node, path);
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    Fail(path, "expected a non-negative integer, got \"" + text + "\"");
  }
  return value;
}

std::int64_t ReadInteger(const YAML::Node& node, const std::string& path) {
  const std::string text = Scalar(node, path);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    Fail(path, "expected an integer, got \"" + text + "\"");
  }
  return value;
}

std::vector<YAML::Node> ListOrScalar(const YAML::Node& node, const std::string& path) {
  std::vector<YAML::Node> items;
  if (node.IsSequence()) {
    for (const auto& item : node) items.push_back(item);
  } else if (node.IsScalar()) {
    items.push_back(node);
  } else {
    Fail(path, "expected a value or a list of values");
  }
  return items;
}

// "<number> <unit>" split textually (the unit may be empty).
struct NumberWithUnit {
  double number = 0.0;
  std::string unit;
};

bool SplitNumber(const std::string& text, NumberWithUnit* out) {
  std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return false;
  const char* first = text.data() + begin;
  const char* last = text.data() + text.size();
  if (*first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, last, out->number);
  if (ec != std::errc() || !std::isfinite(out->number)) return false;
  std::string unit(end, last);
  const std::size_t ub = unit.find_first_not_of(" \t");
  const std::size_t ue = unit.find_last_not_of(" \t");
  out->unit = ub == std::string::npos ? "" : unit.substr(ub, ue - ub + 1);
  return true;
}

// 15 significant digits: 50 + 3 * 0.1 prints as 50.3, not 50.300000000000004.
std::string WithUnit(double number, const std::string& unit) {
  std::string text = SignificantDigits(number, 15);
  if (!unit.empty()) {
    text += ' ';
    text += unit;
  }
  return text;
}

NumberWithUnit ReadNumberWithUnit(const YAML::Node& node, const std::string& path) {
  const std::string text = Scalar(node, path);
  NumberWithUnit value;
  if (!SplitNumber(text, &value)) Fail(path, "expected a number with its unit, got \"" + text + "\"");
  return value;
}

// `value` expressed in `unit` (the unit of a range's `from`): both must be units of one dimension.
double InUnit(const NumberWithUnit& value, const std::string& unit, const std::string& path) {
  if (value.unit == unit) return value.number;
  for (sim::Dimension d : {sim::Dimension::kRate, sim::Dimension::kArw, sim::Dimension::kRrw,
                           sim::Dimension::kRamp, sim::Dimension::kAngle, sim::Dimension::kTime,
                           sim::Dimension::kFrequency}) {
    double one = 0.0;
    double si = 0.0;
    if (!unit.empty() && sim::ParseQuantity("1 " + unit, d, &one, nullptr) &&
        sim::ParseQuantity(WithUnit(value.number, value.unit), d, &si, nullptr)) {
      return si / one;
    }
  }
  Fail(path, "unit \"" + value.unit + "\" is not a unit of the same kind as \"" + unit +
                 "\" (the unit of from)");
}

// One swept parameter, its values expanded.
struct Parameter {
  std::string path;  // "sensor.terms[1].N" or "record.duration"
  std::vector<SweepCoordinate> values;
};

Parameter ReadParameter(const YAML::Node& node, const std::string& path) {
  CheckMap(node, path, {"path", "values", "range", "log_range"});
  Parameter parameter;
  if (!node["path"]) Fail(Child(path, "path"), "missing (e.g. sensor.terms[1].N)");
  parameter.path = Scalar(node["path"], Child(path, "path"));
  if (parameter.path.rfind("sensor.", 0) != 0 && parameter.path != "record.duration" &&
      parameter.path != "record.samples" && parameter.path != "record.sample_rate") {
    Fail(Child(path, "path"), "\"" + parameter.path +
                                  "\" is neither sensor.<key path> nor record.duration, "
                                  "record.samples or record.sample_rate");
  }
  const int kinds = (node["values"] ? 1 : 0) + (node["range"] ? 1 : 0) + (node["log_range"] ? 1 : 0);
  if (kinds != 1) Fail(path, "exactly one of values, range or log_range is needed");
  auto add = [&](double number, const std::string& unit) {
    if (parameter.path == "record.samples") number = std::round(number);  // a log range of counts
    parameter.values.push_back({parameter.path, WithUnit(number, unit), number});
  };
  if (node["values"]) {
    const std::string vpath = Child(path, "values");
    if (!node["values"].IsSequence() || node["values"].size() == 0) {
      Fail(vpath, "expected a non-empty list of values");
    }
    for (std::size_t i = 0; i < node["values"].size(); ++i) {
      const std::string text = Scalar(node["values"][i], Index(vpath, i));
      NumberWithUnit value;
      if (!SplitNumber(text, &value)) {
        // A word (band_limit.type: none, first_order) is a valid sensor value; sim/ checks it
        // when the point's model is parsed. The record's values are numbers.
        if (parameter.path.rfind("sensor.", 0) != 0) {
          Fail(Index(vpath, i), "expected a number (with its unit), got \"" + text + "\"");
        }
        value.number = std::numeric_limits<double>::quiet_NaN();
      }
      parameter.values.push_back({parameter.path, text, value.number});
    }
  } else if (node["range"]) {
    const std::string rpath = Child(path, "range");
    const YAML::Node range = CheckMap(node["range"], rpath, {"from", "to", "step"});
    for (const char* key : {"from", "to", "step"}) {
      if (!range[key]) Fail(Child(rpath, key), "missing");
    }
    const NumberWithUnit from = ReadNumberWithUnit(range["from"], Child(rpath, "from"));
    const double to = InUnit(ReadNumberWithUnit(range["to"], Child(rpath, "to")), from.unit,
                             Child(rpath, "to"));
    const double step = InUnit(ReadNumberWithUnit(range["step"], Child(rpath, "step")), from.unit,
                               Child(rpath, "step"));
    if (!(step > 0.0)) Fail(Child(rpath, "step"), "must be > 0");
    if (to < from.number) Fail(Child(rpath, "to"), "must be >= from");
    const double span = (to - from.number) / step;
    if (span > static_cast<double>(kMaxPoints)) Fail(rpath, "too many values");
    const auto count = static_cast<std::int64_t>(std::floor(span + 1e-9)) + 1;
    for (std::int64_t i = 0; i < count; ++i) {
      add(from.number + static_cast<double>(i) * step, from.unit);
    }
  } else {
    const std::string lpath = Child(path, "log_range");
    const YAML::Node range = CheckMap(node["log_range"], lpath, {"from", "to", "points"});
    for (const char* key : {"from", "to", "points"}) {
      if (!range[key]) Fail(Child(lpath, key), "missing");
    }
    const NumberWithUnit from = ReadNumberWithUnit(range["from"], Child(lpath, "from"));
    const double to = InUnit(ReadNumberWithUnit(range["to"], Child(lpath, "to")), from.unit,
                             Child(lpath, "to"));
    const std::int64_t points = ReadInteger(range["points"], Child(lpath, "points"));
    if (points < 2) Fail(Child(lpath, "points"), "must be >= 2");
    if (points > static_cast<std::int64_t>(kMaxPoints)) Fail(Child(lpath, "points"), "too many");
    if (!(from.number > 0.0)) Fail(Child(lpath, "from"), "must be > 0 for a log range");
    if (!(to > from.number)) Fail(Child(lpath, "to"), "must be > from");
    const double ratio = std::log(to / from.number);
    for (std::int64_t i = 0; i < points; ++i) {
      const double number =
          i == points - 1 ? to
                          : from.number * std::exp(ratio * static_cast<double>(i) /
                                                   static_cast<double>(points - 1));
      add(number, from.unit);
    }
  }
  return parameter;
}

// Splits "terms[1].N" into steps: a key, or an index.
struct PathStep {
  std::string key;
  std::optional<std::size_t> index;
};

std::vector<PathStep> ParseKeyPath(const std::string& text, const std::string& where) {
  std::vector<PathStep> steps;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '.') {
      ++i;
      continue;
    }
    if (text[i] == '[') {
      const std::size_t close = text.find(']', i);
      std::size_t index = 0;
      if (close == std::string::npos ||
          std::from_chars(text.data() + i + 1, text.data() + close, index).ptr != text.data() + close ||
          close == i + 1) {
        Fail(where, "bad index in \"" + text + "\"");
      }
      steps.push_back({"", index});
      i = close + 1;
      continue;
    }
    const std::size_t end = text.find_first_of(".[", i);
    steps.push_back({text.substr(i, end == std::string::npos ? std::string::npos : end - i), {}});
    i = end == std::string::npos ? text.size() : end;
  }
  if (steps.empty() || steps.back().index) Fail(where, "\"" + text + "\" must end in a key");
  return steps;
}

// Writes `value` at `key_path` inside `root` (all but the last step must exist; the last key
// may be new, e.g. a term's optional phase).
void SetByPath(YAML::Node root, const std::string& key_path, const std::string& value,
               const std::string& where) {
  const std::vector<PathStep> steps = ParseKeyPath(key_path, where);
  YAML::Node current;
  current.reset(root);
  std::string walked;
  for (std::size_t s = 0; s + 1 < steps.size(); ++s) {
    const PathStep& step = steps[s];
    YAML::Node next;
    if (step.index) {
      walked += '[';
      walked += std::to_string(*step.index);
      walked += ']';
      if (!current.IsSequence() || *step.index >= current.size()) {
        Fail(where, "\"" + walked + "\" does not exist in the sensor spec");
      }
      next.reset(current[*step.index]);
    } else {
      if (!walked.empty()) walked += '.';
      walked += step.key;
      if (!current.IsMap() || !current[step.key]) {
        Fail(where, "\"" + walked + "\" does not exist in the sensor spec");
      }
      next.reset(current[step.key]);
    }
    current.reset(next);
  }
  if (!current.IsMap()) Fail(where, "\"" + key_path + "\" does not name a key of a mapping");
  current[steps.back().key] = value;
}

std::string Emit(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

std::string PresetText(const std::string& name, const std::string& path) {
  for (const sim::EmbeddedPreset& preset : sim::EmbeddedPresets()) {
    if (preset.name == name) return std::string(preset.yaml);
  }
  Fail(path, "unknown preset \"" + name + "\" (known: " + Join(sim::PresetNames()) + ")");
}

// The record mapping of one point: samples (or duration x rate) and the rate.
void ReadRecord(const YAML::Node& record, const std::string& where, SweepPoint* point) {
  CheckMap(record, "record", {"duration", "samples", "sample_rate"});
  const bool has_duration = static_cast<bool>(record["duration"]);
  const bool has_samples = static_cast<bool>(record["samples"]);
  if (has_duration == has_samples) {
    Fail(where + "record", "exactly one of duration or samples is needed");
  }
  if (has_samples) {
    point->num_samples = ReadInteger(record["samples"], where + "record.samples");
  } else {
    double duration_s = 0.0;
    std::string why;
    const std::string text = Scalar(record["duration"], where + "record.duration");
    if (!sim::ParseQuantity(text, sim::Dimension::kTime, &duration_s, &why)) {
      Fail(where + "record.duration", why);
    }
    if (!(duration_s > 0.0)) Fail(where + "record.duration", "must be > 0");
    const double n = std::round(duration_s * point->model.sample_clock.rate_hz());
    if (n > static_cast<double>(kMaxSamples)) {
      Fail(where + "record.duration", text + " at " + SignificantDigits(point->model.sample_clock.rate_hz(), 15) +
                                         " Hz is more samples than one record can hold");
    }
    point->num_samples = static_cast<std::int64_t>(n);
  }
  const std::string key = has_samples ? "record.samples" : "record.duration";
  if (point->num_samples < kMinSamples) {
    Fail(where + key, "the record has " + std::to_string(point->num_samples) +
                          " samples; at least " + std::to_string(kMinSamples) + " are needed");
  }
  if (point->num_samples > kMaxSamples) Fail(where + key, "more samples than one record can hold");
}

std::string PointLabel(const std::vector<SweepCoordinate>& coordinates) {
  std::string label;
  for (const SweepCoordinate& c : coordinates) {
    label += label.empty() ? "" : ", ";
    label += c.path;
    label += " = ";
    label += c.value_text;
  }
  return label;
}

void Parse(const YAML::Node& root, const std::string& origin, SweepSpec* spec) {
  if (!root || root.IsNull()) Fail("", "empty sweep spec");
  CheckMap(root, "", {"name", "driver", "seed", "trials", "sensor", "record", "estimators",
                      "taus", "fit", "confidence", "sweep"});
  for (const char* key : {"name", "driver", "seed", "trials", "sensor", "record"}) {
    if (!root[key]) Fail(key, "missing");
  }
  spec->name = Scalar(root["name"], "name");
  if (spec->name.empty() || spec->name.find_first_of("/\\ \t") != std::string::npos) {
    Fail("name", "must be a non-empty file name without spaces or slashes");
  }
  spec->driver = Scalar(root["driver"], "driver");
  const std::vector<std::string> drivers = ExperimentNames();
  if (std::find(drivers.begin(), drivers.end(), spec->driver) == drivers.end()) {
    Fail("driver", "unknown experiment \"" + spec->driver + "\" (known: " +
                       (drivers.empty() ? std::string("none") : Join(drivers)) + ")");
  }
  spec->seed = ReadUnsigned(root["seed"], "seed");
  spec->trials = ReadInteger(root["trials"], "trials");
  if (spec->trials <= 0) Fail("trials", "must be >= 1");

  spec->estimators.clear();
  if (root["estimators"]) {
    const auto items = ListOrScalar(root["estimators"], "estimators");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string id = Scalar(items[i], Index("estimators", i));
      estimators::Statistic s{};
      if (!estimators::ParseStatistic(id, &s)) {
        Fail(Index("estimators", i),
             "unknown estimator \"" + id +
                 "\" (known: nonoverlapping, overlapping, modified, hadamard_nonoverlapping, "
                 "hadamard, total, time)");
      }
      if (std::find(spec->estimators.begin(), spec->estimators.end(), s) != spec->estimators.end()) {
        Fail(Index("estimators", i), "\"" + id + "\" is listed twice");
      }
      spec->estimators.push_back(s);
    }
  } else {
    spec->estimators = {estimators::Statistic::kAllanOverlapping};
  }

  if (root["taus"]) {
    const YAML::Node& taus = root["taus"];
    if (taus.IsSequence()) {
      if (taus.size() == 0) Fail("taus", "expected a non-empty list of taus");
      std::string list;
      for (std::size_t i = 0; i < taus.size(); ++i) {
        const std::string text = Scalar(taus[i], Index("taus", i));
        NumberWithUnit value;
        if (!SplitNumber(text, &value)) Fail(Index("taus", i), "expected a tau, got \"" + text + "\"");
        double seconds = value.number;
        std::string why;
        if (!value.unit.empty() && !sim::ParseQuantity(text, sim::Dimension::kTime, &seconds, &why)) {
          Fail(Index("taus", i), why);
        }
        if (!(seconds > 0.0)) Fail(Index("taus", i), "must be > 0");
        list += list.empty() ? "" : ",";
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, "%.17g", seconds);
        list += buffer;
      }
      spec->taus = list;
    } else {
      spec->taus = Scalar(taus, "taus");
    }
    estimators::TauGridOptions grid;
    std::string why;
    if (!estimators::TauGridOptions::Parse(spec->taus, &grid, &why)) Fail("taus", why);
  }

  spec->fit_methods.clear();
  spec->fit_terms.clear();
  if (root["fit"]) {
    const YAML::Node fit = CheckMap(root["fit"], "fit", {"methods", "terms", "tau_range"});
    if (!fit["methods"]) Fail("fit.methods", "missing (slope, wls, log_wls, gls, default)");
    const auto methods = ListOrScalar(fit["methods"], "fit.methods");
    for (std::size_t i = 0; i < methods.size(); ++i) {
      const std::string m = Scalar(methods[i], Index("fit.methods", i));
      if (m != "slope" && m != "wls" && m != "log_wls" && m != "gls" && m != "default") {
        Fail(Index("fit.methods", i), "unknown fit method \"" + m + "\" (known: slope, wls, log_wls, gls, default)");
      }
      spec->fit_methods.push_back(m);
    }
    if (fit["terms"]) {
      const auto terms = ListOrScalar(fit["terms"], "fit.terms");
      for (std::size_t i = 0; i < terms.size(); ++i) {
        const std::string t = Scalar(terms[i], Index("fit.terms", i));
        estimators::Coefficient c{};
        if (!estimators::ParseCoefficient(t, &c)) {
          Fail(Index("fit.terms", i), "unknown coefficient \"" + t + "\" (known: Q, N, B, K, R)");
        }
        spec->fit_terms.push_back(t);
      }
    } else {
      spec->fit_terms = {"Q", "N", "B", "K", "R"};
    }
    if (fit["tau_range"]) {
      const YAML::Node& range = fit["tau_range"];
      if (!range.IsSequence() || range.size() != 2) {
        Fail("fit.tau_range", "expected [shortest tau, longest tau], e.g. [2.56 s, 80 s]");
      }
      double ends[2];
      for (std::size_t i = 0; i < 2; ++i) {
        const std::string text = Scalar(range[i], Index("fit.tau_range", i));
        std::string why;
        if (!sim::ParseQuantity(text, sim::Dimension::kTime, &ends[i], &why)) {
          Fail(Index("fit.tau_range", i), why);
        }
        if (!(ends[i] > 0.0) || !std::isfinite(ends[i])) Fail(Index("fit.tau_range", i), "must be > 0");
      }
      if (!(ends[1] > ends[0])) Fail("fit.tau_range", "the longest tau must exceed the shortest");
      spec->fit_tau_min_s = ends[0];
      spec->fit_tau_max_s = ends[1];
    }
  }

  if (root["confidence"]) {
    spec->confidence_levels.clear();
    const auto levels = ListOrScalar(root["confidence"], "confidence");
    for (std::size_t i = 0; i < levels.size(); ++i) {
      const std::string text = Scalar(levels[i], Index("confidence", i));
      double level = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), level);
      if (ec != std::errc() || end != text.data() + text.size() || !(level > 0.0 && level < 1.0)) {
        Fail(Index("confidence", i), "expected a level in (0, 1), got \"" + text + "\"");
      }
      spec->confidence_levels.push_back(level);
    }
  }

  // The sensor's YAML text, which every point clones and edits.
  const YAML::Node sensor = CheckMap(root["sensor"], "sensor", {"preset", "model"});
  if (static_cast<bool>(sensor["preset"]) == static_cast<bool>(sensor["model"])) {
    Fail("sensor", "exactly one of preset or model is needed");
  }
  YAML::Node sensor_base;
  std::string sensor_origin;
  if (sensor["preset"]) {
    const std::string name = Scalar(sensor["preset"], "sensor.preset");
    sensor_base = YAML::Load(PresetText(name, "sensor.preset"));
    sensor_origin = "sensor.preset " + name;
  } else {
    if (!sensor["model"].IsMap()) Fail("sensor.model", "expected a sensor spec mapping");
    sensor_base = YAML::Clone(sensor["model"]);
    sensor_origin = "sensor.model";
  }
  const YAML::Node record_base = root["record"];
  if (!record_base.IsMap()) Fail("record", "expected a mapping ({duration: 1 h} or {samples: N})");

  // Parameters and the expansion order.
  std::vector<Parameter> parameters;
  bool zip = false;
  if (root["sweep"]) {
    const YAML::Node sweep = CheckMap(root["sweep"], "sweep", {"mode", "parameters"});
    if (sweep["mode"]) {
      const std::string mode = Scalar(sweep["mode"], "sweep.mode");
      if (mode == "zip") {
        zip = true;
      } else if (mode != "product") {
        Fail("sweep.mode", "expected product or zip, got \"" + mode + "\"");
      }
    }
    if (!sweep["parameters"] || !sweep["parameters"].IsSequence() || sweep["parameters"].size() == 0) {
      Fail("sweep.parameters", "expected a non-empty list of {path, values|range|log_range}");
    }
    for (std::size_t i = 0; i < sweep["parameters"].size(); ++i) {
      parameters.push_back(ReadParameter(sweep["parameters"][i], Index("sweep.parameters", i)));
      for (std::size_t j = 0; j < i; ++j) {
        if (parameters[j].path == parameters[i].path) {
          Fail(Index("sweep.parameters", i) + ".path", "\"" + parameters[i].path + "\" is swept twice");
        }
      }
    }
  }
  std::size_t num_points = 1;
  if (zip) {
    num_points = parameters[0].values.size();
    for (std::size_t i = 1; i < parameters.size(); ++i) {
      if (parameters[i].values.size() != num_points) {
        Fail(Index("sweep.parameters", i),
             "zip mode needs equal lengths: " + std::to_string(parameters[i].values.size()) +
                 " values here, " + std::to_string(num_points) + " in sweep.parameters[0]");
      }
    }
  } else {
    for (const Parameter& p : parameters) {
      num_points *= p.values.size();
      if (num_points > kMaxPoints) {
        Fail("sweep.parameters", "the product has more than " + std::to_string(kMaxPoints) + " points");
      }
    }
  }

  std::ostringstream canonical;
  canonical.precision(17);
  canonical << "allanlab sweep spec v1\nname: " << spec->name << "\ndriver: " << spec->driver
            << "\nseed: " << spec->seed << "\ntrials: " << spec->trials << "\nestimators:";
  for (estimators::Statistic s : spec->estimators) canonical << ' ' << estimators::StatisticId(s);
  canonical << "\ntaus: " << spec->taus << "\nfit_methods:";
  for (const std::string& m : spec->fit_methods) canonical << ' ' << m;
  canonical << "\nfit_terms:";
  for (const std::string& t : spec->fit_terms) canonical << ' ' << t;
  if (spec->fit_tau_max_s > 0.0) {
    canonical << "\nfit_tau_range: " << spec->fit_tau_min_s << ' ' << spec->fit_tau_max_s;
  }
  canonical << "\nconfidence:";
  for (double c : spec->confidence_levels) canonical << ' ' << c;
  canonical << '\n';

  spec->points.clear();
  spec->points.reserve(num_points);
  for (std::size_t p = 0; p < num_points; ++p) {
    SweepPoint point;
    point.index = static_cast<int>(p);
    std::vector<std::size_t> which(parameters.size());
    std::size_t rest = p;
    for (std::size_t i = parameters.size(); i-- > 0;) {
      which[i] = zip ? p : rest % parameters[i].values.size();
      if (!zip) rest /= parameters[i].values.size();
    }
    YAML::Node sensor_node = YAML::Clone(sensor_base);
    YAML::Node record_node = YAML::Clone(record_base);
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      const SweepCoordinate& c = parameters[i].values[which[i]];
      point.coordinates.push_back(c);
      const std::string where = Index("sweep.parameters", i) + ".path";
      if (c.path.rfind("sensor.", 0) == 0) {
        SetByPath(sensor_node, c.path.substr(7), c.value_text, where);
      } else {
        record_node[c.path.substr(7)] = c.value_text;
        if (c.path == "record.duration") record_node.remove("samples");
        if (c.path == "record.samples") record_node.remove("duration");
      }
    }
    const std::string where =
        parameters.empty() ? "" : "point " + std::to_string(p) + " (" + PointLabel(point.coordinates) + "): ";
    // The record's sample rate is the model's output rate.
    if (record_node["sample_rate"]) {
      if (!sensor_node.IsMap()) Fail("sensor", "expected a sensor spec mapping");
      sensor_node["sample_rate"] = Scalar(record_node["sample_rate"], where + "record.sample_rate");
    }
    const std::string sensor_text = Emit(sensor_node);
    std::string why;
    if (!sim::LoadSensorModelYaml(sensor_text, where + sensor_origin, &point.model, &why)) {
      throw SpecError{why};
    }
    ReadRecord(record_node, where, &point);
    canonical << "point " << p << ": samples " << point.num_samples << "; sensor " << sensor_text
              << '\n';
    spec->points.push_back(std::move(point));
  }
  (void)origin;
  spec->canonical_text = canonical.str();
}

}  // namespace

std::uint64_t SweepSpec::Hash() const {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (unsigned char c : canonical_text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

bool LoadSweepSpecYaml(std::string_view yaml_text, std::string_view origin, SweepSpec* spec,
                       std::string* why) {
  SweepSpec loaded;
  const std::string prefix = std::string(origin) + ": ";
  try {
    Parse(YAML::Load(std::string(yaml_text)), std::string(origin), &loaded);
  } catch (const SpecError& e) {
    if (why) *why = prefix + e.message;
    return false;
  } catch (const YAML::Exception& e) {
    if (why) {
      std::ostringstream os;
      os << origin;
      if (e.mark.line >= 0) os << ':' << e.mark.line + 1;
      os << ": YAML error: " << e.msg;
      *why = os.str();
    }
    return false;
  }
  *spec = std::move(loaded);
  return true;
}

bool LoadSweepSpecFile(const std::string& path, SweepSpec* spec, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (why) *why = "cannot open sweep spec " + path + ": " + std::strerror(errno);
    return false;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    if (why) *why = "cannot read sweep spec " + path;
    return false;
  }
  return LoadSweepSpecYaml(text.str(), path, spec, why);
}

}  // namespace allanlab::experiments
