#pragma once
// What `allanlab avar` prints and writes: the same rows as a text table (people), CSV and JSON
// (machines, with provenance) and a log-log Allan diagram with confidence bars. Everything is
// converted here, once, from the estimator's SI values to the user's output unit.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "app/input/accel_units.h"
#include "app/reports/allan_plot.h"
#include "app/input/imu_columns.h"
#include "app/reports/provenance.h"
#include "app/input/rate_units.h"
#include "app/input/record_reader.h"
#include "estimators/avar_summary.h"

namespace allanlab::app {

struct AvarReport {
  // Values in (rad/s)^2, or rad^2 for Statistic::kTime; intervals for the variance.
  estimators::AvarSummary summary;
  RecordInfo record;
  std::string input_units;  // as read (record.units_source says where), e.g. "deg/s" or "deg"
  RateUnit output_unit = RateUnit::kDegPerHour;
  // An accelerometer axis: summary values in (m/s^2)^2 (m^2/s^2 for Statistic::kTime), printed
  // in accel_output_unit (m/s for kTime).
  ImuSensor sensor = ImuSensor::kGyro;
  AccelUnit accel_output_unit = AccelUnit::kMilliG;
  std::string taus_text;  // --taus as given
  bool streamed = false;
  // --stream only, one per point: overlapping starts every stride samples (1 = every start).
  std::vector<std::int64_t> overlap_stride;
  std::int64_t stream_exact_max_m = 0;
  Provenance provenance;
};

// One output row, in the output unit: the variance, its deviation and the interval as deviations.
struct AvarRow {
  std::int64_t m = 0;
  double tau_s = 0.0;
  double var = 0.0;
  double dev = 0.0;
  std::int64_t terms = 0;
  double edf = 0.0;
  bool has_interval = false;
  double dev_low = 0.0, dev_high = 0.0;
  int alpha = 0;
  bool alpha_identified = false;
  bool edf_from_record = false;  // the EDF was measured on the record (--ci auto)
  bool ci_from_distribution = false;  // the interval from the estimate's distribution (--ci auto)
};
std::vector<AvarRow> AvarRows(const AvarReport& report);

// "AVAR"/"ADEV", "MVAR"/"MDEV", ...: the statistic's short names, for column headings.
std::string VarianceName(estimators::Statistic s);
std::string DeviationName(estimators::Statistic s);
// The unit of the deviation: the output rate unit, or deg/rad for TDEV (an accelerometer's:
// its output unit, or m/s for TDEV) ...
std::string DeviationUnit(const AvarReport& report);
// ... and the factor from the estimator's SI deviation to it.
double DeviationFactor(const AvarReport& report);

// '#' description lines, the aligned table, then '#' lines for dropped taus and notes.
void WriteAvarTable(std::ostream& os, const AvarReport& report);
// '#' provenance lines, a header with units in the column names, one row per tau.
void WriteAvarCsv(std::ostream& os, const AvarReport& report);
// {"provenance", "input", "estimator", "units", "points", "dropped", "message"}.
nlohmann::ordered_json AvarJson(const AvarReport& report);
// The deviation with its interval as error bars; slope guides -1, -1/2, 0, +1/2, +1.
AllanPlot AvarPlot(const AvarReport& report);

}  // namespace allanlab::app
