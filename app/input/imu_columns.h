#pragma once
// Which columns of a record hold an IMU's gyro and accelerometer axes.
//
// A column is an accelerometer axis when a word of its name starts with "acc" (Accel_X, acc_y,
// accelerometer_z) or it is a ROS linear_acceleration; a gyro axis when a word starts with "gyr"
// (Gyro_X, gyr_y, gyroscope_z) or it is a ROS angular_velocity. `--imu` takes every such column,
// in file order; `--columns A,B,...` takes the named ones, each an accelerometer axis when its
// name says so and a gyro (rate) axis otherwise.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace allanlab::app {

enum class ImuSensor { kGyro, kAccelerometer };

// "gyro", "accelerometer": for messages and JSON.
std::string_view ImuSensorName(ImuSensor sensor);

// What the column's name says it is; nullopt when it names neither.
std::optional<ImuSensor> ImuSensorOfColumn(std::string_view name);

// A comma list of column names or 0-based indices, each trimmed; empty entries are an error.
bool ParseColumnList(std::string_view text, std::vector<std::string>* columns, std::string* why);

// The --imu choice among a header's names (`time_index` is skipped, -1 for none): every gyro and
// accelerometer column, in file order. Fails, listing the names, when there is none.
bool ChooseImuColumns(const std::vector<std::string>& names, int time_index,
                      std::vector<std::string>* columns, std::string* why);

}  // namespace allanlab::app
