#include "app/input/ros2_sqlite_bag.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <sqlite3.h>

namespace allanlab::app {
namespace {

struct CloseDb {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct Finalize {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Statement = std::unique_ptr<sqlite3_stmt, Finalize>;

bool Prepare(sqlite3* db, const char* sql, Statement* statement, std::string* why) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &s, nullptr) != SQLITE_OK) {
    *why = std::string("not a ROS 2 bag (") + sqlite3_errmsg(db) + ")";
    return false;
  }
  statement->reset(s);
  return true;
}

std::string Text(sqlite3_stmt* s, int column) {
  const unsigned char* t = sqlite3_column_text(s, column);
  return t ? reinterpret_cast<const char*>(t) : "";
}

}  // namespace

bool ReadRos2SqliteBag(const std::string& path, const std::string& topic, BagContents* contents, std::string* why) {
  sqlite3* raw = nullptr;
  const int opened = sqlite3_open_v2(path.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  std::unique_ptr<sqlite3, CloseDb> db(raw);
  if (opened != SQLITE_OK) {
    *why = std::string("cannot open as sqlite: ") + (raw ? sqlite3_errmsg(raw) : "out of memory");
    return false;
  }
  Statement topics;
  if (!Prepare(db.get(), "SELECT id, name, type, serialization_format FROM topics", &topics, why)) return false;
  std::vector<std::int64_t> ids;
  std::vector<std::string> names;
  int rc = 0;
  while ((rc = sqlite3_step(topics.get())) == SQLITE_ROW) {
    const std::string name = Text(topics.get(), 1), type = Text(topics.get(), 2);
    contents->topics[name] = type;
    if (!IsImuType(type) || !(topic.empty() || topic == name)) continue;
    if (Text(topics.get(), 3) != "cdr") {
      *why = "topic " + name + ": serialization format '" + Text(topics.get(), 3) + "' (expected cdr)";
      return false;
    }
    ids.push_back(sqlite3_column_int64(topics.get(), 0));
    names.push_back(name);
    contents->imu[name];
  }
  if (rc != SQLITE_DONE) {
    *why = std::string("damaged bag (") + sqlite3_errmsg(db.get()) + ")";
    return false;
  }
  Statement messages;
  if (!Prepare(db.get(), "SELECT data FROM messages WHERE topic_id = ? ORDER BY timestamp, id", &messages, why)) {
    return false;
  }
  for (std::size_t k = 0; k < ids.size(); ++k) {
    sqlite3_reset(messages.get());
    sqlite3_bind_int64(messages.get(), 1, ids[k]);
    std::vector<ImuMessage>& list = contents->imu[names[k]];
    while ((rc = sqlite3_step(messages.get())) == SQLITE_ROW) {
      const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages.get(), 0));
      const auto size = static_cast<std::size_t>(sqlite3_column_bytes(messages.get(), 0));
      ImuMessage m;
      std::string bad;
      if (!DecodeImuCdr(std::span<const std::uint8_t>(data, size), &m, &bad)) {
        *why = "topic " + names[k] + ": message " + std::to_string(list.size() + 1) + ": " + bad;
        return false;
      }
      list.push_back(m);
    }
    if (rc != SQLITE_DONE) {
      *why = std::string("damaged bag (") + sqlite3_errmsg(db.get()) + ")";
      return false;
    }
  }
  return true;
}

}  // namespace allanlab::app
