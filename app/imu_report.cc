#include "app/imu_report.h"

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

std::vector<AllanPlot> ImuAvarPlots(const std::vector<AvarReport>& reports, const std::string& what) {
  static const char* const kAxisColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                            "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
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
        panel.title = what + ": " + r.record.path + ", " + std::string(ImuSensorName(sensor)) + " (" +
                      std::to_string(r.summary.num_samples) + " samples at " +
                      ShortestDecimal(r.record.sample_rate_hz) + " Hz)";
      }
      PlotSeries series = one.series.front();
      series.title = r.record.column;
      series.color = kAxisColors[axes % (sizeof kAxisColors / sizeof kAxisColors[0])];
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
