#include "app/reports/sensor_coefficients.h"

#include "app/input/accel_units.h"

namespace allanlab::app {

using estimators::Coefficient;

std::string_view SensorCoefficientName(ImuSensor sensor, Coefficient c) {
  if (sensor == ImuSensor::kAccelerometer) return AccelCoefficientName(c);
  switch (c) {
    case Coefficient::kQ:
      return "angle quantization";
    case Coefficient::kN:
      return "angle random walk (ARW)";
    case Coefficient::kB:
      return "bias instability";
    case Coefficient::kK:
      return "rate random walk";
    case Coefficient::kR:
      return "rate ramp";
  }
  return "?";
}

std::string_view SensorDatasheetUnit(ImuSensor sensor, Coefficient c) {
  return sensor == ImuSensor::kAccelerometer ? AccelDatasheetUnit(c) : estimators::DatasheetUnit(c);
}

double SensorDatasheetValue(ImuSensor sensor, Coefficient c, double value_si) {
  return sensor == ImuSensor::kAccelerometer ? AccelToDatasheetUnit(c, value_si)
                                             : estimators::ToDatasheetUnit(c, value_si);
}

std::string AccelerometerTermsLine() {
  std::string out = "accelerometer:";
  for (Coefficient c : estimators::kAllCoefficients) {
    out += std::string(c == Coefficient::kQ ? " " : ", ") + std::string(estimators::CoefficientId(c)) + " " +
           std::string(AccelCoefficientName(c));
  }
  return out;
}

ParameterUnit SensorParameterUnit(ImuSensor sensor, const estimators::ParameterSpec& spec) {
  if (sensor == ImuSensor::kAccelerometer && spec.si_unit == "rad/s") {
    return {std::string(AccelUnitName(AccelUnit::kMilliG)), AccelToSi(AccelUnit::kMilliG, 1.0)};
  }
  return {spec.datasheet_unit, spec.si_per_datasheet};
}

}  // namespace allanlab::app
