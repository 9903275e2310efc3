#include "app/reports/imu_report.h"
#include "common/number_text.h"

#include <string>

namespace allanlab::app {

nlohmann::ordered_json ImuAvarJson(const std::vector<AvarReport>& reports, const Provenance& provenance) {
  nlohmann::ordered_json j;
  j["provenance"] = ProvenanceJson(provenance);
  nlohmann::ordered_json columns = nlohmann::ordered_json::array();
  for (const AvarReport& r : reports) {
    nlohmann::ordered_json one = AvarJson(r);
    one.erase("provenance");
    columns.push_back(std::move(one));
  }
  j["columns"] = std::move(columns);
  return j;
}

void WriteImuAvarCsv(std::ostream& os, const std::vector<AvarReport>& reports, const Provenance& provenance) {
  os << ProvenanceCommentLines(provenance);
  os << "column,sensor,unit,m,tau_s,var,dev,terms,edf,dev_low,dev_high,alpha,alpha_identified\n";
  for (const AvarReport& r : reports) {
    const std::string prefix = r.record.column + "," + std::string(ImuSensorName(r.sensor)) + "," +
                               DeviationUnit(r) + ",";
    for (const AvarRow& row : AvarRows(r)) {
      os << prefix << row.m << "," << ShortestDecimal(row.tau_s) << "," << ShortestDecimal(row.var) << ","
         << ShortestDecimal(row.dev) << "," << row.terms << "," << ShortestDecimal(row.edf) << ","
         << (row.has_interval ? ShortestDecimal(row.dev_low) : "") << ","
         << (row.has_interval ? ShortestDecimal(row.dev_high) : "") << "," << row.alpha << ","
         << (row.alpha_identified ? 1 : 0) << "\n";
    }
  }
}

namespace {

const char* AxisColor(std::size_t axis) {
  static const char* const kAxisColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                            "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
  return kAxisColors[axis % (sizeof kAxisColors / sizeof kAxisColors[0])];
}

std::string PanelTitle(const std::string& what, const AvarReport& r) {
  return what + ": " + r.record.path + ", " + std::string(ImuSensorName(r.sensor)) + " (" +
         std::to_string(r.summary.num_samples) + " samples at " + ShortestDecimal(r.record.sample_clock.rate_hz()) + " Hz)";
}

}  // namespace

std::vector<AllanPlot> ImuFitPlots(const std::vector<ImuFitCurve>& axes, const std::string& what) {
  std::vector<AllanPlot> panels;
  for (ImuSensor sensor : {ImuSensor::kGyro, ImuSensor::kAccelerometer}) {
    AllanPlot panel;
    std::size_t count = 0;
    for (const ImuFitCurve& a : axes) {
      if (a.report->sensor != sensor) continue;
      if (count == 0) {
        panel = AvarPlot(*a.report);
        panel.series.clear();
        panel.title = PanelTitle(what, *a.report);
      }
      PlotSeries data = a.data, fitted = a.fitted_total;
      data.title = a.report->record.column;
      fitted.title = a.report->record.column + " fitted";
      data.color = fitted.color = AxisColor(count);
      panel.series.push_back(std::move(data));
      panel.series.push_back(std::move(fitted));
      ++count;
    }
    if (count > 0) panels.push_back(std::move(panel));
  }
  return panels;
}

std::vector<AllanPlot> ImuAvarPlots(const std::vector<AvarReport>& reports, const std::string& what) {
  std::vector<AllanPlot> panels;
  for (ImuSensor sensor : {ImuSensor::kGyro, ImuSensor::kAccelerometer}) {
    AllanPlot panel;
    std::size_t axes = 0;
    for (const AvarReport& r : reports) {
      if (r.sensor != sensor) continue;
      AllanPlot one = AvarPlot(r);
      if (axes == 0) {
        panel = one;
        panel.series.clear();
        panel.title = PanelTitle(what, r);
      }
      PlotSeries series = one.series.front();
      series.title = r.record.column;
      series.color = AxisColor(axes);
      panel.series.push_back(std::move(series));
      ++axes;
    }
    if (axes > 0) panels.push_back(std::move(panel));
  }
  return panels;
}

std::string DescribeColumns(const std::vector<AvarReport>& reports) {
  std::string out;
  for (const AvarReport& r : reports) {
    out += (out.empty() ? "" : ", ") + r.record.column + " " + std::string(ImuSensorName(r.sensor)) + " " +
           r.input_units + " (" + r.record.units_source + ")";
  }
  return out;
}

}  // namespace allanlab::app
