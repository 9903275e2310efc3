#pragma once
// What `allanlab avar` writes for several columns of one record (an IMU's axes): one JSON with an
// entry per column, one long-format CSV (a row per column and tau, the unit in its own column),
// and one PNG with every axis: a panel for the gyro axes and one for the accelerometer axes when
// both are present, since their units differ.
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "app/reports/allan_plot.h"
#include "app/reports/avar_report.h"
#include "app/reports/provenance.h"

namespace allanlab::app {

// {"provenance", "columns": [AvarJson of each column without its provenance]}.
nlohmann::ordered_json ImuAvarJson(const std::vector<AvarReport>& reports, const Provenance& provenance);

// '#' provenance lines, then column,sensor,unit,m,tau_s,var,dev,terms,edf,dev_low,dev_high,alpha,
// alpha_identified (var in unit^2, deviations in unit).
void WriteImuAvarCsv(std::ostream& os, const std::vector<AvarReport>& reports, const Provenance& provenance);

// One panel per sensor present (gyro first), each axis a series of its own colour with its
// interval bars; `what` heads the titles ("allanlab avar").
std::vector<AllanPlot> ImuAvarPlots(const std::vector<AvarReport>& reports, const std::string& what);

// A fitted axis as `allanlab fit` draws it: its curve with intervals and the fitted total.
struct ImuFitCurve {
  const AvarReport* report = nullptr;
  PlotSeries data;
  PlotSeries fitted_total;
};
// One panel per sensor present, each axis in its own colour: data points and the fitted line.
std::vector<AllanPlot> ImuFitPlots(const std::vector<ImuFitCurve>& axes, const std::string& what);

// The provenance line naming every column with its sensor and units ("Gyro_X gyro deg/s (--units),
// Accel_X accelerometer g (--accel-units)").
std::string DescribeColumns(const std::vector<AvarReport>& reports);

}  // namespace allanlab::app
