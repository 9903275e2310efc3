#pragma once
// The JSON sidecar of a raw float32/float64 record: `allanlab simulate --format f64 -o r.f64`
// writes r.f64.json, whose "data" object states the sample type ("dtype": "<f8" or "<f4"), the
// sample count, the sample rate and the units. A raw record carries none of these itself, so the
// reader takes them from the sidecar when it exists: PATH.json, or for a compressed PATH.gz /
// PATH.xz also the name without that suffix + ".json" (r.f64.xz -> r.f64.json).
#include <cstdint>
#include <optional>
#include <string>

namespace allanlab::app {

struct RawSidecar {
  std::string path;                       // the sidecar that was read
  std::optional<std::string> dtype;       // "<f8", "<f4"
  std::optional<std::int64_t> num_samples;
  std::optional<double> sample_rate_hz;
  std::optional<std::string> units;       // as written, e.g. "rad/s"
};

// Looks for the sidecar of `record_path`. Returns true with *sidecar unset when there is none;
// false (*why names the sidecar) when one exists but is not readable JSON or holds a field of the
// wrong type or value (a rate not finite and > 0, a negative count).
bool ReadRawSidecar(const std::string& record_path, std::optional<RawSidecar>* sidecar,
                    std::string* why);

}  // namespace allanlab::app
