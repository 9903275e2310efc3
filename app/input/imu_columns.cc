#include "app/input/imu_columns.h"

#include "app/input/stated_units.h"

namespace allanlab::app {
namespace {

bool StartsWith(const std::string& word, std::string_view prefix) {
  return word.compare(0, prefix.size(), prefix) == 0;
}

std::string_view TrimBlanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view ImuSensorName(ImuSensor sensor) {
  return sensor == ImuSensor::kGyro ? "gyro" : "accelerometer";
}

std::optional<ImuSensor> ImuSensorOfColumn(std::string_view name) {
  const std::vector<std::string> words = UnitTokens(name);
  for (std::size_t i = 0; i < words.size(); ++i) {
    const bool next_is = i + 1 < words.size();
    if (StartsWith(words[i], "acc")) return ImuSensor::kAccelerometer;
    if (words[i] == "linear" && next_is && words[i + 1] == "acceleration") return ImuSensor::kAccelerometer;
    if (StartsWith(words[i], "gyr")) return ImuSensor::kGyro;
    if (words[i] == "angular" && next_is && words[i + 1] == "velocity") return ImuSensor::kGyro;
  }
  return std::nullopt;
}

bool ParseColumnList(std::string_view text, std::vector<std::string>* columns, std::string* why) {
  columns->clear();
  const std::string whole(text);
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view entry = TrimBlanks(text.substr(0, comma));
    if (entry.empty()) {
      *why = "empty column name in '" + whole + "' (expected a comma list such as Gyro_X,Gyro_Y,Gyro_Z)";
      return false;
    }
    columns->emplace_back(entry);
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return true;
}

bool ChooseImuColumns(const std::vector<std::string>& names, int time_index,
                      std::vector<std::string>* columns, std::string* why) {
  columns->clear();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (static_cast<int>(i) != time_index && ImuSensorOfColumn(names[i])) columns->push_back(names[i]);
  }
  if (!columns->empty()) return true;
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  *why = "--imu: no gyro or accelerometer column in the header (" + list +
         "; recognised: names with a word starting gyr or acc, ROS angular_velocity and "
         "linear_acceleration): name them with --columns";
  return false;
}

}  // namespace allanlab::app
