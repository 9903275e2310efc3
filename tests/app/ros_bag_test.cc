// ROS bags as records: MCAP (plain, zstd and lz4 chunks), ROS 2 sqlite3 and ROS 1 (plain, bz2 and
// lz4 chunks), each written here by a minimal writer that follows the published format (mcap.dev
// spec; rosbag2's sqlite3 schema; wiki.ros.org Bags/Format/2.0) and the two wire encodings of
// sensor_msgs/Imu (CDR, ROS 1). The values read back must be the ones written, the time steps
// reported as for the same record written as CSV, and every bad bag one clear error.
#include <bzlib.h>
#include <gtest/gtest.h>
#include <lz4frame.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <sqlite3.h>
#include <stdlib.h>
#include <zlib.h>
#include <zstd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/input/record_reader.h"
#include "app/commands/subcommand.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;
using Bytes = std::string;

constexpr int kMessages = 2000;
constexpr std::int64_t kStepNs = 5000000;  // 200 Hz
constexpr std::int64_t kStartNs = 1700000000123456789;

struct Sample {
  std::int64_t stamp_ns;
  double gyro[3], accel[3];
};

// White values, and one late message (a 3-period gap) so that the time steps have something to report.
std::vector<Sample> Samples() {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<Sample> s(kMessages);
  for (int k = 0; k < kMessages; ++k) {
    s[k].stamp_ns = kStartNs + kStepNs * (k + (k >= 1000 ? 2 : 0));
    for (double& v : s[k].gyro) v = 0.01 * normal(rng);
    for (double& v : s[k].accel) v = 9.81 + 0.02 * normal(rng);
  }
  return s;
}

template <typename T>
void Put(Bytes* b, T v) {
  b->append(reinterpret_cast<const char*>(&v), sizeof v);
}
void PutString32(Bytes* b, const std::string& s) {
  Put<std::uint32_t>(b, static_cast<std::uint32_t>(s.size()));
  *b += s;
}
void PutVectors(Bytes* b, const Sample& s) {
  const double orientation_and_cov[13] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (double v : orientation_and_cov) Put(b, v);
  for (double v : s.gyro) Put(b, v);
  for (int i = 0; i < 9; ++i) Put(b, 0.0);
  for (double v : s.accel) Put(b, v);
  for (int i = 0; i < 9; ++i) Put(b, 0.0);
}

// sensor_msgs/msg/Imu in little-endian CDR: encapsulation 00 01 00 00, then fields aligned to
// their size counted from the end of the encapsulation.
Bytes Cdr(const Sample& s) {
  Bytes b("\x00\x01\x00\x00", 4);
  Put<std::int32_t>(&b, static_cast<std::int32_t>(s.stamp_ns / 1000000000));
  Put<std::uint32_t>(&b, static_cast<std::uint32_t>(s.stamp_ns % 1000000000));
  PutString32(&b, std::string("imu_link\0", 9));  // CDR strings carry their terminating NUL
  while ((b.size() - 4) % 8 != 0) b += '\0';
  PutVectors(&b, s);
  return b;
}

// sensor_msgs/Imu in the ROS 1 serialization: packed, little-endian.
Bytes Ros1(const Sample& s, std::uint32_t seq) {
  Bytes b;
  Put(&b, seq);
  Put<std::uint32_t>(&b, static_cast<std::uint32_t>(s.stamp_ns / 1000000000));
  Put<std::uint32_t>(&b, static_cast<std::uint32_t>(s.stamp_ns % 1000000000));
  PutString32(&b, "imu_link");
  PutVectors(&b, s);
  return b;
}

// --- MCAP ---
void McapRecord(Bytes* out, std::uint8_t op, const Bytes& content) {
  *out += static_cast<char>(op);
  Put<std::uint64_t>(out, content.size());
  *out += content;
}
Bytes McapSchema(std::uint16_t id, const std::string& name) {
  Bytes b;
  Put(&b, id);
  PutString32(&b, name);
  PutString32(&b, "ros2msg");
  PutString32(&b, "");
  return b;
}
Bytes McapChannel(std::uint16_t id, std::uint16_t schema, const std::string& topic) {
  Bytes b;
  Put(&b, id);
  Put(&b, schema);
  PutString32(&b, topic);
  PutString32(&b, "cdr");
  Put<std::uint32_t>(&b, 0);  // metadata: an empty map
  return b;
}
Bytes McapMessage(std::uint16_t channel, std::uint32_t sequence, const Sample& s) {
  Bytes b;
  Put(&b, channel);
  Put(&b, sequence);
  Put<std::uint64_t>(&b, s.stamp_ns);
  Put<std::uint64_t>(&b, s.stamp_ns);
  return b + Cdr(s);
}

// compression "" (messages at the top level), "none" (an uncompressed chunk), "zstd" or "lz4".
Bytes Mcap(const std::vector<Sample>& samples, const std::string& compression) {
  const Bytes magic("\x89MCAP0\r\n", 8);
  Bytes out = magic, header;
  PutString32(&header, "ros2");
  PutString32(&header, "allanlab test");
  McapRecord(&out, 0x01, header);
  Bytes records;
  McapRecord(&records, 0x03, McapSchema(1, "sensor_msgs/msg/Imu"));
  McapRecord(&records, 0x03, McapSchema(2, "std_msgs/msg/String"));
  McapRecord(&records, 0x04, McapChannel(1, 1, "/imu"));
  McapRecord(&records, 0x04, McapChannel(2, 2, "/chatter"));
  for (std::size_t k = 0; k < samples.size(); ++k) McapRecord(&records, 0x05, McapMessage(1, k, samples[k]));
  if (compression.empty()) {
    out += records;
  } else {
    Bytes stored = records;
    if (compression == "zstd") {
      stored.resize(ZSTD_compressBound(records.size()));
      stored.resize(ZSTD_compress(stored.data(), stored.size(), records.data(), records.size(), 3));
    } else if (compression == "lz4") {
      stored.resize(LZ4F_compressFrameBound(records.size(), nullptr));
      stored.resize(LZ4F_compressFrame(stored.data(), stored.size(), records.data(), records.size(), nullptr));
    }
    Bytes chunk;
    Put<std::uint64_t>(&chunk, samples.front().stamp_ns);
    Put<std::uint64_t>(&chunk, samples.back().stamp_ns);
    Put<std::uint64_t>(&chunk, records.size());
    Put<std::uint32_t>(&chunk, static_cast<std::uint32_t>(
                                   crc32(0L, reinterpret_cast<const Bytef*>(records.data()), records.size())));
    PutString32(&chunk, compression == "none" ? "" : compression);
    Put<std::uint64_t>(&chunk, stored.size());
    McapRecord(&out, 0x06, chunk + stored);
  }
  McapRecord(&out, 0x0F, Bytes(4, '\0'));  // data end
  McapRecord(&out, 0x02, Bytes(20, '\0'));  // footer: no summary
  return out + magic;
}

// --- ROS 1 ---
Bytes Ros1Field(const std::string& name, const Bytes& value) {
  Bytes b;
  PutString32(&b, name + "=" + value);
  return b;
}
template <typename T>
Bytes Raw(T v) {
  Bytes b;
  Put(&b, v);
  return b;
}
void Ros1Record(Bytes* out, const Bytes& header, const Bytes& data) {
  PutString32(out, header);
  PutString32(out, data);
}

// compression "none", "bz2" or "lz4" for the one chunk.
Bytes Ros1Bag(const std::vector<Sample>& samples, const std::string& compression) {
  Bytes out = "#ROSBAG V2.0\n";
  Ros1Record(&out, Ros1Field("op", Raw<std::uint8_t>(0x03)) + Ros1Field("index_pos", Raw<std::uint64_t>(0)) +
                       Ros1Field("conn_count", Raw<std::uint32_t>(2)) + Ros1Field("chunk_count", Raw<std::uint32_t>(1)),
             Bytes(4000, ' '));
  Bytes records;
  auto connection = [&](std::uint32_t id, const std::string& topic, const std::string& type) {
    Ros1Record(&records, Ros1Field("op", Raw<std::uint8_t>(0x07)) + Ros1Field("conn", Raw(id)) + Ros1Field("topic", topic),
               Ros1Field("topic", topic) + Ros1Field("type", type) + Ros1Field("md5sum", "*"));
  };
  connection(0, "/imu", "sensor_msgs/Imu");
  connection(1, "/chatter", "std_msgs/String");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const std::uint64_t time = (static_cast<std::uint64_t>(samples[k].stamp_ns % 1000000000) << 32) |
                               static_cast<std::uint64_t>(samples[k].stamp_ns / 1000000000);
    Ros1Record(&records, Ros1Field("op", Raw<std::uint8_t>(0x02)) + Ros1Field("conn", Raw<std::uint32_t>(0)) +
                             Ros1Field("time", Raw(time)),
               Ros1(samples[k], static_cast<std::uint32_t>(k)));
  }
  Bytes stored = records;
  if (compression == "bz2") {
    stored.resize(records.size() + records.size() / 100 + 600);
    auto size = static_cast<unsigned int>(stored.size());
    EXPECT_EQ(BZ2_bzBuffToBuffCompress(stored.data(), &size, records.data(), static_cast<unsigned int>(records.size()),
                                       9, 0, 0),
              BZ_OK);
    stored.resize(size);
  } else if (compression == "lz4") {
    stored.resize(LZ4F_compressFrameBound(records.size(), nullptr));
    stored.resize(LZ4F_compressFrame(stored.data(), stored.size(), records.data(), records.size(), nullptr));
  }
  Ros1Record(&out, Ros1Field("op", Raw<std::uint8_t>(0x05)) + Ros1Field("compression", compression) +
                       Ros1Field("size", Raw<std::uint32_t>(static_cast<std::uint32_t>(records.size()))),
             stored);
  return out;
}

class RosBagTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "ros_bag_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const Bytes& bytes) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::string Db3(const std::vector<Sample>& samples) const {
    const std::string path = (dir_ / "bag_0.db3").string();
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    const char* schema =
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
        "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
        "data BLOB NOT NULL);"
        "INSERT INTO topics VALUES (1, '/imu', 'sensor_msgs/msg/Imu', 'cdr', '');"
        "INSERT INTO topics VALUES (2, '/chatter', 'std_msgs/msg/String', 'cdr', '');"
        "BEGIN;";
    EXPECT_EQ(sqlite3_exec(db, schema, nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_stmt* insert = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES (1, ?, ?)", -1, &insert, nullptr);
    for (const Sample& s : samples) {
      const Bytes data = Cdr(s);
      sqlite3_bind_int64(insert, 1, s.stamp_ns);
      sqlite3_bind_blob(insert, 2, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
      EXPECT_EQ(sqlite3_step(insert), SQLITE_DONE);
      sqlite3_reset(insert);
    }
    sqlite3_finalize(insert);
    EXPECT_EQ(sqlite3_exec(db, "COMMIT;", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
    return path;
  }

  // The same record as CSV, as a ROS CSV export names its columns.
  std::string Csv(const std::vector<Sample>& samples) const {
    std::ostringstream os;
    os.precision(17);
    os << "time_s,angular_velocity.x,angular_velocity.y,angular_velocity.z,linear_acceleration.x,"
          "linear_acceleration.y,linear_acceleration.z\n";
    for (const Sample& s : samples) {
      os << static_cast<double>(s.stamp_ns - samples.front().stamp_ns) * 1e-9;
      for (double v : s.gyro) os << "," << v;
      for (double v : s.accel) os << "," << v;
      os << "\n";
    }
    return Write("same.csv", os.str());
  }

  struct Result {
    bool ok = false;
    std::vector<std::vector<double>> values;
    RecordInfo info;
    RecordError error;
  };
  static Result ReadImu(const std::string& path, const std::string& topic = "/imu") {
    RecordReaderOptions o;
    o.path = path;
    o.topic = topic;
    o.imu = true;
    Result r;
    r.ok = ReadRecordColumns(o, &r.values, &r.info, &r.error);
    return r;
  }

  // Every bag holds Samples(): the six axes exactly, and the time steps as the CSV reports them.
  void ExpectSamples(const std::string& path, const std::string& format) {
    const std::vector<Sample> samples = Samples();
    const Result r = ReadImu(path);
    ASSERT_TRUE(r.ok) << r.error.message;
    ASSERT_EQ(r.values.size(), 6u);
    for (int k = 0; k < kMessages; ++k) {
      for (int a = 0; a < 3; ++a) {
        ASSERT_EQ(r.values[a][k], samples[k].gyro[a]) << "message " << k;
        ASSERT_EQ(r.values[3 + a][k], samples[k].accel[a]) << "message " << k;
      }
    }
    EXPECT_EQ(r.info.columns[0].name, "angular_velocity.x");
    EXPECT_EQ(r.info.columns[0].units, "rad/s");
    EXPECT_EQ(r.info.columns[3].units, "m/s^2");
    EXPECT_EQ(r.info.sample_clock.rate_hz(), 200.0);
    EXPECT_NE(r.info.bag.find(format + " bag, topic /imu"), std::string::npos) << r.info.bag;
    RecordReaderOptions o;
    o.path = Csv(samples);
    o.imu = true;
    Result csv;
    csv.ok = ReadRecordColumns(o, &csv.values, &csv.info, &csv.error);
    ASSERT_TRUE(csv.ok) << csv.error.message;
    EXPECT_EQ(r.info.time.irregular_steps, 1);
    EXPECT_EQ(r.info.time.irregular_steps, csv.info.time.irregular_steps);
    EXPECT_EQ(r.info.time.largest_step_s, csv.info.time.largest_step_s);
    EXPECT_EQ(r.info.time.largest_step_line, 1001);  // the message after the gap, counted from 1
    EXPECT_EQ(csv.info.time.largest_step_line, 1002);  // its line in the CSV
    EXPECT_EQ(r.info.time_column, "time_s (header stamps of /imu)");
  }

  fs::path dir_;
};

TEST_F(RosBagTest, McapMessagesAtTheTopLevel) { ExpectSamples(Write("a.mcap", Mcap(Samples(), "")), "MCAP"); }
TEST_F(RosBagTest, McapUncompressedChunk) { ExpectSamples(Write("a.mcap", Mcap(Samples(), "none")), "MCAP"); }
TEST_F(RosBagTest, McapZstdChunk) { ExpectSamples(Write("a.mcap", Mcap(Samples(), "zstd")), "MCAP"); }
TEST_F(RosBagTest, McapLz4Chunk) { ExpectSamples(Write("a.mcap", Mcap(Samples(), "lz4")), "MCAP"); }
TEST_F(RosBagTest, Ros2Sqlite) { ExpectSamples(Db3(Samples()), "ROS 2 sqlite3"); }
TEST_F(RosBagTest, Ros2BagDirectory) {
  Db3(Samples());
  Write("metadata.yaml", "rosbag2_bagfile_information: {}\n");
  ExpectSamples(dir_.string(), "ROS 2 sqlite3");
}
TEST_F(RosBagTest, Ros1Uncompressed) { ExpectSamples(Write("a.bag", Ros1Bag(Samples(), "none")), "ROS 1"); }
TEST_F(RosBagTest, Ros1Bz2) { ExpectSamples(Write("a.bag", Ros1Bag(Samples(), "bz2")), "ROS 1"); }
TEST_F(RosBagTest, Ros1Lz4) { ExpectSamples(Write("a.bag", Ros1Bag(Samples(), "lz4")), "ROS 1"); }

TEST_F(RosBagTest, TheOnlyImuTopicWithoutTopic) {
  const Result r = ReadImu(Write("a.mcap", Mcap(Samples(), "zstd")), "");
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.values[0].size(), static_cast<std::size_t>(kMessages));
}

// The avar JSON names a bag's step positions for what they are: message numbers, not lines.
TEST_F(RosBagTest, JsonTimeStepsCountMessages) {
  const std::string bag = Write("a.mcap", Mcap(Samples(), "zstd"));
  const std::string json = (dir_ / "a.json").string();
  const std::string command = std::string(ALLANLAB_BINARY) + " avar '" + bag +
                              "' --column angular_velocity.x --ci none --json '" + json +
                              "' > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
  const nlohmann::json steps =
      nlohmann::json::parse(testing_support::ReadAll(json))["input"]["time_steps"];
  EXPECT_EQ(steps["largest_message"], 1001) << steps;
  EXPECT_FALSE(steps.contains("largest_line")) << steps;
  EXPECT_TRUE(steps.contains("smallest_message")) << steps;
}

TEST_F(RosBagTest, TopicErrorsListTheTopics) {
  const std::string path = Write("a.mcap", Mcap(Samples(), ""));
  Result r = ReadImu(path, "/imu0");
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, path + ": no topic /imu0 in the bag (topics: /chatter (std_msgs/msg/String), "
                                    "/imu (sensor_msgs/msg/Imu))");
  r = ReadImu(path, "/chatter");
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.message, path + ": topic /chatter holds std_msgs/msg/String, not sensor_msgs/Imu");
  r = ReadImu(Write("a.csv", "t,rate_rad_per_s\n0,1\n1,2\n2,3\n3,4\n"), "/imu");
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_NE(r.error.message.find("--topic reads a ROS bag"), std::string::npos) << r.error.message;
}

TEST_F(RosBagTest, TruncatedAndCorruptBagsFailWithOneLine) {
  const Bytes mcap = Mcap(Samples(), "zstd");
  Result r = ReadImu(Write("cut.mcap", mcap.substr(0, mcap.size() / 2)));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_NE(r.error.message.find("truncated MCAP"), std::string::npos) << r.error.message;
  Bytes corrupt = mcap;
  for (std::size_t i = 200; i < 260; ++i) corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5a);  // inside the chunk
  r = ReadImu(Write("corrupt.mcap", corrupt));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.message.find('\n'), std::string::npos);
  EXPECT_NE(r.error.message.find("CRC"), std::string::npos) << r.error.message;
  const Bytes bag = Ros1Bag(Samples(), "none");
  r = ReadImu(Write("cut.bag", bag.substr(0, bag.size() - 100)));
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.message.find("truncated ROS 1 bag"), std::string::npos) << r.error.message;
  r = ReadImu(Write("junk.db3", "SQLite format 3" + Bytes(1, '\0') + Bytes(200, 'x')));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace allanlab::app
