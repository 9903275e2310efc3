#include "sim/sensor_spec.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "sim/embedded_presets.h"
#include "sim/quantity.h"

namespace allanlab::sim {
namespace {

// Where an error is reported: "<origin>:<line>: <path>: <message>". The first error wins.
class ErrorSink {
 public:
  explicit ErrorSink(std::string_view origin) : origin_(origin) {}

  bool Fail(const YAML::Mark& mark, std::string_view path, std::string_view message) {
    if (!failed_) {
      std::ostringstream os;
      os << origin_;
      if (mark.line >= 0) os << ':' << mark.line + 1;
      os << ": ";
      if (!path.empty()) os << path << ": ";
      os << message;
      message_ = os.str();
      failed_ = true;
    }
    return false;
  }
  const std::string& message() const { return message_; }

 private:
  std::string origin_;
  std::string message_;
  bool failed_ = false;
};

std::string Join(const std::vector<std::string_view>& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out;
}

enum class Sign { kAny, kNonNegative, kPositive };

// An example unit for "missing" messages, so the fix can be copied from the message.
std::string_view ExampleUnit(Dimension dimension) {
  switch (dimension) {
    case Dimension::kRate:
      return "deg/h";
    case Dimension::kArw:
      return "deg/sqrt(h)";
    case Dimension::kRrw:
      return "deg/h/sqrt(h)";
    case Dimension::kRamp:
      return "deg/h^2";
    case Dimension::kAngle:
      return "urad";
    case Dimension::kTime:
      return "s";
    case Dimension::kFrequency:
      return "Hz";
  }
  return "";
}

// One YAML mapping with a fixed set of allowed keys. Unknown and duplicate keys are rejected
// before any value is read, so a misspelt key is reported as unknown rather than as a missing
// required key.
class MapReader {
 public:
  // False (with the error in *sink) unless `node` is a mapping whose keys are all in `allowed`.
  static std::optional<MapReader> Open(const YAML::Node& node, std::string path,
                                       std::string_view what, std::vector<std::string_view> allowed,
                                       ErrorSink* sink) {
    if (!node.IsMap()) {
      sink->Fail(node.Mark(), path,
                 "expected a mapping (key: value) for " + std::string(what) + ", with keys " +
                     Join(allowed));
      return std::nullopt;
    }
    MapReader reader(node, std::move(path), std::move(allowed), sink);
    for (const auto& entry : node) {
      const std::string key = entry.first.Scalar();
      if (std::find(reader.allowed_.begin(), reader.allowed_.end(), key) == reader.allowed_.end()) {
        sink->Fail(
            entry.first.Mark(), reader.Path(key),
            "unknown key for " + std::string(what) + "; allowed keys: " + Join(reader.allowed_));
        return std::nullopt;
      }
      if (reader.entries_.count(key) > 0) {
        sink->Fail(entry.first.Mark(), reader.Path(key), "duplicate key");
        return std::nullopt;
      }
      reader.entries_.emplace(key, entry.second);
    }
    return reader;
  }

  std::string Path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }
  bool Has(std::string_view key) const { return entries_.count(std::string(key)) > 0; }
  YAML::Node Get(std::string_view key) const { return entries_.at(std::string(key)); }

  // A required value with a unit.
  bool Quantity(std::string_view key, Dimension dimension, Sign sign, double* out) {
    if (!Has(key)) {
      return Missing(key, "a value with a unit, e.g. \"" + std::string(key) + ": 1 " +
                              std::string(ExampleUnit(dimension)) + "\"");
    }
    return ReadQuantity(key, dimension, sign, out);
  }
  // An optional value with a unit; *out is left as is when the key is absent.
  bool OptionalQuantity(std::string_view key, Dimension dimension, Sign sign, double* out) {
    return !Has(key) || ReadQuantity(key, dimension, sign, out);
  }
  bool OptionalQuantity(std::string_view key, Dimension dimension, Sign sign,
                        std::optional<double>* out) {
    if (!Has(key)) return true;
    double value = 0.0;
    if (!ReadQuantity(key, dimension, sign, &value)) return false;
    *out = value;
    return true;
  }

  bool Text(std::string_view key, bool required, std::string* out) {
    if (!Has(key)) return !required || Missing(key, "a text value");
    const YAML::Node value = Get(key);
    if (!value.IsScalar()) return sink_->Fail(value.Mark(), Path(key), "expected a text value");
    *out = value.Scalar();
    return true;
  }

  // One of `choices`; returns its index in *out.
  bool Choice(std::string_view key, bool required, const std::vector<std::string_view>& choices,
              std::size_t* out) {
    std::string text;
    if (!Has(key)) {
      return !required || Missing(key, "one of " + Join(choices));
    }
    if (!Text(key, true, &text)) return false;
    const auto it = std::find(choices.begin(), choices.end(), text);
    if (it == choices.end()) {
      return sink_->Fail(Get(key).Mark(), Path(key),
                         "\"" + text + "\" is not one of " + Join(choices));
    }
    *out = static_cast<std::size_t>(it - choices.begin());
    return true;
  }

  // A plain number (no unit: a count or a ratio).
  bool Number(std::string_view key, Sign sign, double* out) {
    if (!Has(key)) return true;
    const YAML::Node value = Get(key);
    const std::string text = value.IsScalar() ? value.Scalar() : std::string();
    double number = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
        !std::isfinite(number)) {
      return sink_->Fail(value.Mark(), Path(key),
                         "expected a plain finite number, got \"" + text + "\"");
    }
    if (!CheckSign(key, sign, number, text)) return false;
    *out = number;
    return true;
  }

  bool Integer(std::string_view key, int* out) {
    if (!Has(key)) return true;
    const YAML::Node value = Get(key);
    const std::string text = value.IsScalar() ? value.Scalar() : std::string();
    int number = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
      return sink_->Fail(value.Mark(), Path(key), "expected an integer, got \"" + text + "\"");
    }
    *out = number;
    return true;
  }

  bool Missing(std::string_view key, const std::string& expected) {
    return sink_->Fail(node_.Mark(), Path(key), "missing; expected " + expected);
  }

 private:
  MapReader(const YAML::Node& node, std::string path, std::vector<std::string_view> allowed,
            ErrorSink* sink)
      : node_(node), path_(std::move(path)), allowed_(std::move(allowed)), sink_(sink) {}

  bool ReadQuantity(std::string_view key, Dimension dimension, Sign sign, double* out) {
    const YAML::Node value = Get(key);
    if (!value.IsScalar()) {
      return sink_->Fail(value.Mark(), Path(key), "expected a value with a unit");
    }
    std::string reason;
    double si = 0.0;
    if (!ParseQuantity(value.Scalar(), dimension, &si, &reason)) {
      return sink_->Fail(value.Mark(), Path(key), reason);
    }
    if (!CheckSign(key, sign, si, value.Scalar())) return false;
    *out = si;
    return true;
  }

  bool CheckSign(std::string_view key, Sign sign, double value, const std::string& text) {
    if (sign == Sign::kNonNegative && value < 0.0) {
      return sink_->Fail(Get(key).Mark(), Path(key), "must be >= 0, got " + text);
    }
    if (sign == Sign::kPositive && value <= 0.0) {
      return sink_->Fail(Get(key).Mark(), Path(key), "must be > 0, got " + text);
    }
    return true;
  }

  YAML::Node node_;
  std::string path_;
  std::vector<std::string_view> allowed_;
  std::map<std::string, YAML::Node> entries_;
  ErrorSink* sink_;
};

// How one term type is written: its keys (besides "type") and how to read them.
struct TermReader {
  std::string_view id;
  std::vector<std::string_view> keys;
  bool (*read)(MapReader& r, NoiseTerm* term);
};

template <typename T>
bool Store(bool ok, const T& value, NoiseTerm* term) {
  if (ok) *term = value;
  return ok;
}

using D = Dimension;

// TermReaders() below has one entry per NoiseTerm alternative; this fails to compile when a term
// is added to sim/noise_term.h without teaching the spec reader about it.
constexpr std::size_t kTermReaderCount = 13;
static_assert(std::variant_size_v<NoiseTerm> == kTermReaderCount,
              "add a TermReader for the new NoiseTerm alternative");

const std::vector<TermReader>& TermReaders() {
  static const std::vector<TermReader> kReaders = {
      {QuantizationNoise::kId,
       {"Q"},
       [](MapReader& r, NoiseTerm* t) {
         QuantizationNoise x;
         return Store(r.Quantity("Q", D::kAngle, Sign::kNonNegative, &x.q_rad), x, t);
       }},
      {WhiteRateNoise::kId,
       {"N"},
       [](MapReader& r, NoiseTerm* t) {
         WhiteRateNoise x;
         return Store(r.Quantity("N", D::kArw, Sign::kNonNegative, &x.arw_rad_per_sqrt_s), x, t);
       }},
      {FlickerNoise::kId,
       {"B"},
       [](MapReader& r, NoiseTerm* t) {
         FlickerNoise x;
         return Store(r.Quantity("B", D::kRate, Sign::kNonNegative, &x.bias_instability_rad_per_s),
                      x, t);
       }},
      {FlickerGaussMarkovSum::kId,
       {"B", "min_correlation_time", "max_correlation_time", "per_decade"},
       [](MapReader& r, NoiseTerm* t) {
         FlickerGaussMarkovSum x;
         const bool ok =
             r.Quantity("B", D::kRate, Sign::kNonNegative, &x.bias_instability_rad_per_s) &&
             r.Quantity("min_correlation_time", D::kTime, Sign::kPositive,
                        &x.min_correlation_time_s) &&
             r.Quantity("max_correlation_time", D::kTime, Sign::kPositive,
                        &x.max_correlation_time_s) &&
             r.Number("per_decade", Sign::kPositive, &x.processes_per_decade);
         return Store(ok, x, t);
       }},
      {RandomWalkRate::kId,
       {"K"},
       [](MapReader& r, NoiseTerm* t) {
         RandomWalkRate x;
         return Store(r.Quantity("K", D::kRrw, Sign::kNonNegative, &x.rrw_rad_per_s_per_sqrt_s), x,
                      t);
       }},
      {RateRamp::kId,
       {"R"},
       [](MapReader& r, NoiseTerm* t) {
         RateRamp x;
         return Store(r.Quantity("R", D::kRamp, Sign::kAny, &x.ramp_rad_per_s2), x, t);
       }},
      {Harmonic::kId,
       {"amplitude", "frequency", "phase"},
       [](MapReader& r, NoiseTerm* t) {
         Harmonic x;
         const bool ok =
             r.Quantity("amplitude", D::kRate, Sign::kNonNegative, &x.amplitude_rad_per_s) &&
             r.Quantity("frequency", D::kFrequency, Sign::kPositive, &x.frequency_hz) &&
             r.OptionalQuantity("phase", D::kAngle, Sign::kAny, &x.phase_rad);
         return Store(ok, x, t);
       }},
      {GaussMarkov::kId,
       {"sigma", "correlation_time"},
       [](MapReader& r, NoiseTerm* t) {
         GaussMarkov x;
         const bool ok =
             r.Quantity("sigma", D::kRate, Sign::kNonNegative, &x.sigma_rad_per_s) &&
             r.Quantity("correlation_time", D::kTime, Sign::kPositive, &x.correlation_time_s);
         return Store(ok, x, t);
       }},
      {Resonance::kId,
       {"sigma", "frequency", "damping"},
       [](MapReader& r, NoiseTerm* t) {
         Resonance x;
         const bool ok = r.Quantity("sigma", D::kRate, Sign::kNonNegative, &x.sigma_rad_per_s) &&
                         r.Quantity("frequency", D::kFrequency, Sign::kPositive, &x.frequency_hz) &&
                         r.Number("damping", Sign::kPositive, &x.damping);
         return Store(ok, x, t);
       }},
      {RandomTelegraph::kId,
       {"amplitude", "mean_dwell"},
       [](MapReader& r, NoiseTerm* t) {
         RandomTelegraph x;
         const bool ok =
             r.Quantity("amplitude", D::kRate, Sign::kNonNegative, &x.amplitude_rad_per_s) &&
             r.Quantity("mean_dwell", D::kTime, Sign::kPositive, &x.mean_dwell_s);
         return Store(ok, x, t);
       }},
      {ExponentialDrift::kId,
       {"amplitude", "time_constant"},
       [](MapReader& r, NoiseTerm* t) {
         ExponentialDrift x;
         const bool ok = r.Quantity("amplitude", D::kRate, Sign::kAny, &x.amplitude_rad_per_s) &&
                         r.Quantity("time_constant", D::kTime, Sign::kPositive, &x.time_constant_s);
         return Store(ok, x, t);
       }},
      {BiasStep::kId,
       {"size", "time"},
       [](MapReader& r, NoiseTerm* t) {
         BiasStep x;
         const bool ok = r.Quantity("size", D::kRate, Sign::kAny, &x.size_rad_per_s) &&
                         r.Quantity("time", D::kTime, Sign::kNonNegative, &x.time_s);
         return Store(ok, x, t);
       }},
      {Outliers::kId,
       {"rate", "size", "sign", "size_law"},
       [](MapReader& r, NoiseTerm* t) {
         Outliers x;
         std::size_t sign = 0, law = 0;
         const bool ok = r.Quantity("rate", D::kFrequency, Sign::kNonNegative, &x.rate_hz) &&
                         r.Quantity("size", D::kRate, Sign::kNonNegative, &x.size_rad_per_s) &&
                         r.Choice("sign", false, {"symmetric", "positive", "negative"}, &sign) &&
                         r.Choice("size_law", false, {"fixed", "exponential"}, &law);
         x.sign = std::array{SpikeSign::kSymmetric, SpikeSign::kPositive, SpikeSign::kNegative}[sign];
         x.size_law = law == 0 ? SpikeSize::kFixed : SpikeSize::kExponential;
         return Store(ok, x, t);
       }},
  };
  return kReaders;
}

bool ReadTerm(const YAML::Node& node, const std::string& path, double sample_rate_hz,
              ErrorSink* sink, NoiseTerm* term) {
  const auto& readers = TermReaders();
  std::vector<std::string_view> types;
  for (const auto& r : readers) types.push_back(r.id);
  if (!node.IsMap()) {
    return sink->Fail(node.Mark(), path, "expected a mapping {type: ..., ...}");
  }
  const YAML::Node type_node = node["type"];
  if (!type_node) {
    return sink->Fail(node.Mark(), path + ".type", "missing; expected one of " + Join(types));
  }
  const std::string type = type_node.IsScalar() ? type_node.Scalar() : std::string();
  const auto reader = std::find_if(readers.begin(), readers.end(),
                                   [&](const TermReader& r) { return r.id == type; });
  if (reader == readers.end()) {
    return sink->Fail(type_node.Mark(), path + ".type",
                      "unknown term type \"" + type + "\"; known types: " + Join(types));
  }
  std::vector<std::string_view> allowed = {"type"};
  allowed.insert(allowed.end(), reader->keys.begin(), reader->keys.end());
  auto map = MapReader::Open(node, path, "term type " + type, allowed, sink);
  if (!map || !reader->read(*map, term)) return false;
  // The term's own rules (and the model's per-term rules, such as at most one outlier per
  // sample), checked here so the message carries the term's path.
  SensorModel probe;
  probe.sample_clock = SampleClock::FromRateHz(sample_rate_hz);
  probe.terms = {*term};
  std::string reason;
  if (!probe.IsValid(&reason)) return sink->Fail(node.Mark(), path, reason);
  return true;
}

bool ReadBandLimit(const YAML::Node& node, double sample_rate_hz, ErrorSink* sink,
                   BandLimit* limit) {
  auto map = MapReader::Open(node, "band_limit", "band_limit",
                             {"type", "cutoff", "oversampling", "sampling"}, sink);
  if (!map) return false;
  static const std::vector<LowPassKind> kKindValues = {
      LowPassKind::kNone, LowPassKind::kFirstOrder, LowPassKind::kButterworth2,
      LowPassKind::kFirstOrderBilinear, LowPassKind::kButterworth2ImpulseInvariant,
      LowPassKind::kMovingAverage, LowPassKind::kCic2};
  static const std::vector<std::string_view> kKinds = [] {
    std::vector<std::string_view> names;
    for (LowPassKind k : kKindValues) names.push_back(LowPassKindName(k));
    return names;
  }();
  static const std::vector<std::string_view> kSampling = {"point", "average"};
  std::size_t kind = 0;
  std::size_t sampling = 0;
  if (!map->Choice("type", true, kKinds, &kind)) return false;
  limit->kind = kKindValues[kind];
  const bool cutoff_ok =
      limit->kind == LowPassKind::kNone
          ? map->OptionalQuantity("cutoff", Dimension::kFrequency, Sign::kPositive,
                                  &limit->cutoff_hz)
          : map->Quantity("cutoff", Dimension::kFrequency, Sign::kPositive, &limit->cutoff_hz);
  if (!cutoff_ok || !map->Integer("oversampling", &limit->oversampling) ||
      !map->Choice("sampling", false, kSampling, &sampling)) {
    return false;
  }
  if (map->Has("sampling")) {
    limit->sampling = sampling == 0 ? OutputSampling::kPoint : OutputSampling::kAverage;
  }
  std::string reason;
  if (!limit->IsValid(sample_rate_hz, &reason))
    return sink->Fail(node.Mark(), "band_limit", reason);
  return true;
}

bool ReadOutput(const YAML::Node& node, ErrorSink* sink, SensorModel* model) {
  auto map = MapReader::Open(node, "output", "output", {"angle_lsb", "rate_lsb", "rate_dither"}, sink);
  if (!map) return false;
  if (map->Has("angle_lsb")) {
    AngleQuantizer q;
    if (!map->Quantity("angle_lsb", Dimension::kAngle, Sign::kPositive, &q.lsb_rad)) return false;
    model->angle_quantizer = q;
  }
  if (map->Has("rate_lsb")) {
    RateQuantizer q;
    static const std::vector<std::string_view> kDither = {"none", "subtractive"};
    std::size_t dither = 0;
    if (!map->Quantity("rate_lsb", Dimension::kRate, Sign::kPositive, &q.lsb_rad_per_s) ||
        !map->Choice("rate_dither", false, kDither, &dither)) {
      return false;
    }
    q.subtractive_dither = dither == 1;
    model->rate_quantizer = q;
  } else if (map->Has("rate_dither")) {
    return sink->Fail(node.Mark(), "output.rate_dither", "a dither needs rate_lsb");
  }
  return true;
}

bool ReadModel(const YAML::Node& root, ErrorSink* sink, SensorModel* model) {
  if (!root || root.IsNull()) {
    return sink->Fail(YAML::Mark::null_mark(), "",
                      "empty spec; expected a mapping with name, sample_rate and terms");
  }
  auto map = MapReader::Open(
      root, "", "a sensor spec",
      {"name", "description", "sample_rate", "bias", "terms", "band_limit", "output"}, sink);
  double sample_rate_hz = 0.0;
  if (!map || !map->Text("name", true, &model->name) ||
      !map->Text("description", false, &model->description) ||
      !map->Quantity("sample_rate", Dimension::kFrequency, Sign::kPositive, &sample_rate_hz) ||
      !map->OptionalQuantity("bias", Dimension::kRate, Sign::kAny, &model->bias_rad_per_s)) {
    return false;
  }
  model->sample_clock = SampleClock::FromRateHz(sample_rate_hz);
  if (!map->Has("terms")) return map->Missing("terms", "a list of noise terms");
  const YAML::Node terms = map->Get("terms");
  if (!terms.IsSequence()) {
    return sink->Fail(terms.Mark(), "terms", "expected a list of noise terms (- {type: ...})");
  }
  for (std::size_t i = 0; i < terms.size(); ++i) {
    NoiseTerm term;
    if (!ReadTerm(terms[i], "terms[" + std::to_string(i) + "]", model->sample_clock.rate_hz(), sink,
                  &term)) {
      return false;
    }
    model->terms.push_back(term);
  }
  if (map->Has("band_limit") &&
      !ReadBandLimit(map->Get("band_limit"), model->sample_clock.rate_hz(), sink, &model->band_limit)) {
    return false;
  }
  if (map->Has("output") && !ReadOutput(map->Get("output"), sink, model)) return false;
  std::string reason;
  if (!model->IsValid(&reason)) return sink->Fail(root.Mark(), "", reason);
  return true;
}

}  // namespace

bool LoadSensorModelYaml(std::string_view yaml_text, std::string_view origin, SensorModel* model,
                         std::string* why) {
  ErrorSink sink(origin);
  SensorModel loaded;
  bool ok = false;
  try {
    ok = ReadModel(YAML::Load(std::string(yaml_text)), &sink, &loaded);
  } catch (const YAML::Exception& e) {
    // Syntax errors (and any node access the reader did not guard) carry their own position.
    ok = sink.Fail(e.mark, "", "YAML error: " + e.msg);
  }
  if (!ok) {
    if (why) *why = sink.message();
    return false;
  }
  *model = std::move(loaded);
  return true;
}

bool LoadSensorModelFile(const std::string& path, SensorModel* model, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (why) *why = "cannot open sensor spec " + path + ": " + std::strerror(errno);
    return false;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    if (why) *why = "cannot read sensor spec " + path;
    return false;
  }
  return LoadSensorModelYaml(text.str(), path, model, why);
}

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const EmbeddedPreset& preset : EmbeddedPresets()) names.emplace_back(preset.name);
  std::sort(names.begin(), names.end());
  return names;
}

bool LoadPreset(std::string_view name, SensorModel* model, std::string* why) {
  for (const EmbeddedPreset& preset : EmbeddedPresets()) {
    if (preset.name == name) {
      return LoadSensorModelYaml(preset.yaml, "preset " + std::string(name), model, why);
    }
  }
  if (why) {
    std::string known;
    for (const std::string& n : PresetNames()) known += (known.empty() ? "" : ", ") + n;
    *why = "unknown preset \"" + std::string(name) + "\"; known presets: " + known;
  }
  return false;
}

}  // namespace allanlab::sim
