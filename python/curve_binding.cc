// avar, fit and diagnose on a record in memory: the commands' options structs filled from the
// keyword arguments, then the commands' own steps (app/input/record_curve.h, app/commands/fit_command.h,
// app/commands/diagnose_command.h) and their JSON writers, so the numbers are the command line's.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/input/accel_units.h"
#include "app/input/record_curve.h"
#include "app/reports/avar_report.h"
#include "app/commands/diagnose_command.h"
#include "app/commands/fit_command.h"
#include "app/reports/provenance.h"
#include "app/input/record_reader.h"
#include "python/bindings.h"

namespace py = pybind11;

namespace allanlab::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> Samples(const Array& values) {
  if (values.ndim() != 1) {
    throw py::value_error("values: a 1-D array of samples is needed, got " + std::to_string(values.ndim()) +
                          " dimensions");
  }
  return std::vector<double>(values.data(), values.data() + values.size());
}

// The record options of every command: what `--rate`, `--units` and `--type` say on the command line.
app::RecordCurveOptions RecordOptions(double rate_hz, const std::string& units, const std::string& type) {
  app::RecordCurveOptions o;
  o.path = "values";
  o.rate_hz = rate_hz;
  o.units = units;
  o.type = type;
  return o;
}

void Check(int code, const std::string& error) {
  if (code != app::kExitOk) Raise(code, error);
}

std::string Avar(const Array& values, double rate_hz, const std::string& units, const std::string& type,
                 const std::string& estimator, const std::string& taus, const std::string& ci, double confidence,
                 const std::string& out_units) {
  app::RecordCurveOptions o = RecordOptions(rate_hz, units, type);
  o.estimator = estimator;
  o.taus = taus;
  o.ci = ci;
  o.confidence = confidence;
  o.out_units = out_units;
  std::vector<double> samples = Samples(values);
  app::AvarReport report;
  std::string error;
  int code = app::kExitOk;
  {
    py::gil_scoped_release release;
    code = app::ComputeCurveFromSamples(o, std::move(samples), &report, &error);
  }
  Check(code, error);
  report.provenance = app::MakeProvenance("avar", "allanlab.avar (Python)");
  return app::AvarJson(report).dump();
}

std::string Fit(const Array& values, double rate_hz, const std::string& units, const std::string& type,
                const std::string& taus, const std::string& method, const std::string& terms, bool select_terms,
                const std::string& band_limit, const std::string& uncertainty, int bootstrap_trials,
                std::uint64_t seed, double min_tau_s, double max_tau_s, const std::string& out_units) {
  app::FitCommandOptions o;
  o.curve = RecordOptions(rate_hz, units, type);
  o.curve.taus = taus;
  o.curve.out_units = out_units;
  o.method = method;
  o.terms = terms;
  o.select_terms = select_terms;
  o.band_limit = band_limit;
  o.uncertainty = uncertainty;
  o.bootstrap_trials = bootstrap_trials;
  o.seed = seed;
  o.min_tau_s = min_tau_s;
  o.max_tau_s = max_tau_s;
  estimators::ModelFitOptions fit;
  double max_tau = 0.0;
  if (auto failure = app::MakeModelFitOptions(o, &fit, &max_tau)) Raise(failure->code, failure->message);
  std::vector<double> samples = Samples(values);
  app::AvarReport report;
  app::FittedAxis axis;
  std::string error;
  std::optional<app::CommandFailure> failure;
  {
    py::gil_scoped_release release;
    const int code = app::ComputeCurveFromSamples(app::FitCurveOptions(o), std::move(samples), &report, &error);
    if (code != app::kExitOk) failure = app::CommandFailure{code, error};
    if (!failure) failure = app::FitAxis(o, fit, max_tau, &report, &axis);
  }
  if (failure) Raise(failure->code, failure->message);
  const app::Provenance p = app::FitProvenance(o, report, axis.fitted.fit, "allanlab.fit (Python)");
  nlohmann::ordered_json j = app::FitJson(o, axis.fitted, axis.bandwidth, p);
  nlohmann::ordered_json curve = app::AvarJson(report);
  curve.erase("provenance");
  j["curve"] = std::move(curve);
  return j.dump();
}

std::string Diagnose(const Array& values, double rate_hz, const std::string& units, const std::string& type,
                     std::optional<std::string> model, const std::string& preset, const std::string& sensor,
                     const std::string& float_terms, int trials, std::uint64_t seed, double false_alarm) {
  // An accelerometer unit (m/s^2, g, mg) makes the values an accelerometer axis, diagnosed in
  // m/s^2 and reported as `diagnose` reports an Accel_X column (app/reports/diagnose_units.h).
  app::AccelUnit accel_unit{};
  std::string why;
  const bool accelerometer = app::ParseAccelUnit(units, &accel_unit, &why);
  if (accelerometer && type != "rate") {
    Raise(app::kExitUsageError, "type: an accelerometer axis (units " + units + ") is read as acceleration: drop type");
  }
  if (accelerometer && (!preset.empty() || !sensor.empty())) {
    Raise(app::kExitUsageError, "units " + units + " make the values an accelerometer axis; preset and sensor "
                                "describe a gyro: diagnose it against its fitted model (no preset or sensor)");
  }
  app::DiagnoseCommandOptions o;
  // The checks of the samples (their count, finite values, the rate) do not depend on the unit;
  // an accelerometer's samples are scaled to m/s^2 below instead of as a gyro rate.
  o.record = RecordOptions(rate_hz, accelerometer ? "rad/s" : units, type);
  o.model = std::move(model);
  o.preset = preset;
  o.sensor_path = sensor;
  o.float_terms = float_terms;
  o.trials = trials;
  o.seed = seed;
  o.false_alarm = false_alarm;
  experiments::DiagnoseOptions d;
  if (auto failure = app::MakeDiagnoseOptions(o, &d)) Raise(failure->code, failure->message);
  std::vector<double> rate = Samples(values);
  app::RecordInfo info;
  std::string error;
  Check(app::RateFromSamples(o.record, &rate, &info, &error), error);
  if (accelerometer) app::AccelToSi(accel_unit, rate);
  experiments::DiagnosisSummary s;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = experiments::DiagnoseRecord(d, rate, info.sample_clock, &s);
  }
  if (!ok) Raise(app::kExitRuntimeError, o.record.path + ": " + s.message);
  const app::DiagnoseUnits unit = accelerometer
                                      ? app::DiagnoseUnits{app::ImuSensor::kAccelerometer, std::string(app::AccelUnitName(accel_unit))}
                                      : app::DiagnoseUnits{app::ImuSensor::kGyro, units};
  return app::DiagnosisJson(s, app::MakeProvenance("diagnose", "allanlab.diagnose (Python)"), nullptr, unit).dump();
}

}  // namespace

void AddCurveFunctions(py::module_& m) {
  const app::RecordCurveOptions avar;
  m.def("avar", &Avar, py::arg("values"), py::arg("rate_hz"), py::arg("units"), py::arg("type") = avar.type,
        py::arg("estimator") = avar.estimator, py::arg("taus") = avar.taus, py::arg("ci") = "auto",
        py::arg("confidence") = avar.confidence, py::arg("out_units") = avar.out_units);
  const app::FitCommandOptions fit;
  m.def("fit", &Fit, py::arg("values"), py::arg("rate_hz"), py::arg("units"), py::arg("type") = avar.type,
        py::arg("taus") = app::kFitTaus, py::arg("method") = fit.method, py::arg("terms") = fit.terms,
        py::arg("select_terms") = fit.select_terms, py::arg("band_limit") = fit.band_limit,
        py::arg("uncertainty") = fit.uncertainty, py::arg("bootstrap_trials") = fit.bootstrap_trials,
        py::arg("seed") = fit.seed, py::arg("min_tau_s") = fit.min_tau_s, py::arg("max_tau_s") = fit.max_tau_s,
        py::arg("out_units") = avar.out_units);
  const app::DiagnoseCommandOptions diagnose;
  m.def("diagnose", &Diagnose, py::arg("values"), py::arg("rate_hz"), py::arg("units"), py::arg("type") = avar.type,
        py::arg("model") = diagnose.model, py::arg("preset") = diagnose.preset, py::arg("sensor") = diagnose.sensor_path,
        py::arg("float_terms") = diagnose.float_terms, py::arg("trials") = diagnose.trials,
        py::arg("seed") = diagnose.seed, py::arg("false_alarm") = diagnose.false_alarm);
}

}  // namespace allanlab::python
