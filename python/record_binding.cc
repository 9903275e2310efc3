// simulate and the exact expected OAVAR of its records, from the sensor model `allanlab simulate`
// loads (app/commands/simulate_command.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/reports/simulated_record.h"
#include "python/bindings.h"
#include "sim/avar_theory.h"
#include "sim/sensor_model.h"

namespace py = pybind11;

namespace allanlab::python {
namespace {

app::SimulateOptions Options(const std::string& preset, const std::string& sensor, std::optional<double> rate_hz) {
  app::SimulateOptions o;
  o.preset = preset;
  o.sensor_path = sensor;
  o.rate_hz = rate_hz;
  return o;
}

sim::SensorModel Model(const app::SimulateOptions& o) {
  sim::SensorModel model;
  if (auto failure = app::LoadSimulateModel(o, &model)) Raise(failure->code, failure->message);
  return model;
}

// A vector handed to numpy without a copy: the array owns it.
py::array_t<double> ToArray(std::vector<double> values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

py::tuple Simulate(const std::string& preset, const std::string& sensor, double duration_s, std::uint64_t seed,
                   std::uint64_t trial, std::optional<double> rate_hz) {
  app::SimulateOptions o = Options(preset, sensor, rate_hz);
  o.duration_s = duration_s;
  o.seed = seed;
  o.trial = trial;
  const sim::SensorModel model = Model(o);
  std::int64_t n = 0;
  if (auto failure = app::SimulateSampleCount(o, model.sample_clock.rate_hz(), &n)) Raise(failure->code, failure->message);
  std::vector<double> rate;
  {
    py::gil_scoped_release release;
    rate = model.Generate(seed, trial, n);
  }
  py::dict info;
  info["sensor_name"] = model.name;
  info["sample_rate_hz"] = model.sample_clock.rate_hz();
  info["expected_is_exact"] = model.ExpectedAvarIsExact();
  return py::make_tuple(ToArray(std::move(rate)), info);
}

py::array_t<double> ExpectedAvar(const std::string& preset, const std::string& sensor, std::optional<double> rate_hz,
                                 const std::vector<std::int64_t>& m, std::int64_t num_samples, bool overlapping) {
  const sim::SensorModel model = Model(Options(preset, sensor, rate_hz));
  for (std::int64_t mi : m) {
    if (mi < 1 || 2 * mi > num_samples) {
      throw py::value_error("m = " + std::to_string(mi) + " is outside [1, num_samples / 2] for " +
                            std::to_string(num_samples) + " samples");
    }
  }
  const sim::RecordShape shape{num_samples, overlapping ? sim::AvarEstimatorKind::kOverlapping
                                                        : sim::AvarEstimatorKind::kNonOverlapping};
  return ToArray(model.ExpectedAvar(m, shape));
}

}  // namespace

void AddRecordFunctions(py::module_& m) {
  m.def("simulate", &Simulate, py::arg("preset"), py::arg("sensor"), py::arg("duration_s"), py::arg("seed"),
        py::arg("trial"), py::arg("rate_hz"));
  m.def("expected_avar", &ExpectedAvar, py::arg("preset"), py::arg("sensor"), py::arg("rate_hz"), py::arg("m"),
        py::arg("num_samples"), py::arg("overlapping"));
}

}  // namespace allanlab::python
