#include "rgbdvo/io/rosbag2_sqlite.hpp"

#include <sqlite3.h>

#include <filesystem>
#include <stdexcept>

#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

std::string Text(sqlite3_stmt* statement, int column) {
  const unsigned char* text = sqlite3_column_text(statement, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

Rosbag2SqliteReader::Rosbag2SqliteReader(const std::string& path) : path_(path) {
  if (!InputFileSize(path, "rosbag2 sqlite3 file"))
    throw std::runtime_error(path + ": no such rosbag2 sqlite3 file");
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error(path + ": cannot open as an sqlite3 file (" + why + ")");
  }
  sqlite3_stmt* topics = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT id, name, type, serialization_format FROM topics ORDER BY id",
                         -1, &topics, nullptr) != SQLITE_OK)
    Fail("not a rosbag2 sqlite3 file: its topics table cannot be read");
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(topics)) == SQLITE_ROW)
    topics_.push_back(
        {sqlite3_column_int64(topics, 0), Text(topics, 1), Text(topics, 2), Text(topics, 3)});
  sqlite3_finalize(topics);
  if (step != SQLITE_DONE) Fail("reading the topics table");
  if (sqlite3_prepare_v2(db_, "SELECT topic_id, timestamp, data FROM messages ORDER BY id", -1,
                         &messages_, nullptr) != SQLITE_OK)
    Fail("not a rosbag2 sqlite3 file: its messages table cannot be read");
}

Rosbag2SqliteReader::~Rosbag2SqliteReader() {
  sqlite3_finalize(messages_);
  sqlite3_close(db_);
}

void Rosbag2SqliteReader::Fail(const std::string& what) const {
  const std::string why = sqlite3_errmsg(db_);
  sqlite3_finalize(messages_);
  sqlite3_close(db_);
  throw std::runtime_error(path_ + ": " + what + " (" + why + ")");
}

bool Rosbag2SqliteReader::Next(Rosbag2SqliteRow* row) {
  const int step = sqlite3_step(messages_);
  if (step == SQLITE_DONE) return false;
  if (step != SQLITE_ROW)
    throw std::runtime_error(path_ + ": reading the messages table (" + sqlite3_errmsg(db_) + ")");
  row->topic_id = sqlite3_column_int64(messages_, 0);
  row->timestamp_ns = sqlite3_column_int64(messages_, 1);
  const auto* data = static_cast<const uint8_t*>(sqlite3_column_blob(messages_, 2));
  const int size = sqlite3_column_bytes(messages_, 2);
  row->data.assign(data, data + (data ? size : 0));
  return true;
}

Rosbag2SqliteWriter::Rosbag2SqliteWriter(const std::string& path) : path_(path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw std::runtime_error(path + ": cannot create the sqlite3 file (" + why + ")");
  }
  // rosbag2's tables as ROS 2 Humble creates them.
  Exec(
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
      "BEGIN TRANSACTION;");
  if (sqlite3_prepare_v2(db_, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                         -1, &insert_, nullptr) != SQLITE_OK)
    Fail("preparing the messages' insert");
}

Rosbag2SqliteWriter::~Rosbag2SqliteWriter() {
  sqlite3_finalize(insert_);
  sqlite3_close(db_);
}

void Rosbag2SqliteWriter::Fail(const std::string& what) const {
  throw std::runtime_error(path_ + ": " + what + " (" + sqlite3_errmsg(db_) + ")");
}

void Rosbag2SqliteWriter::Exec(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : "unknown error";
    sqlite3_free(error);
    throw std::runtime_error(path_ + ": writing the sqlite3 file (" + why + ")");
  }
}

int64_t Rosbag2SqliteWriter::AddTopic(const std::string& name, const std::string& type,
                                      const std::string& serialization_format) {
  sqlite3_stmt* insert = nullptr;
  if (sqlite3_prepare_v2(db_,
                         "INSERT INTO topics (id, name, type, serialization_format, "
                         "offered_qos_profiles) VALUES (?, ?, ?, ?, '')",
                         -1, &insert, nullptr) != SQLITE_OK)
    Fail("preparing the topic's insert");
  const int64_t id = next_topic_++;
  sqlite3_bind_int64(insert, 1, id);
  sqlite3_bind_text(insert, 2, name.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(insert, 3, type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(insert, 4, serialization_format.c_str(), -1, SQLITE_TRANSIENT);
  const int step = sqlite3_step(insert);
  sqlite3_finalize(insert);
  if (step != SQLITE_DONE) Fail("adding topic " + name);
  return id;
}

void Rosbag2SqliteWriter::Write(int64_t topic_id, int64_t timestamp_ns,
                                const std::vector<uint8_t>& data) {
  sqlite3_reset(insert_);
  sqlite3_bind_int64(insert_, 1, topic_id);
  sqlite3_bind_int64(insert_, 2, timestamp_ns);
  sqlite3_bind_blob(insert_, 3, data.data(), static_cast<int>(data.size()), SQLITE_STATIC);
  if (sqlite3_step(insert_) != SQLITE_DONE) Fail("writing a message");
}

void Rosbag2SqliteWriter::Close() {
  if (!db_) return;
  sqlite3_finalize(insert_);
  insert_ = nullptr;
  Exec("COMMIT;");
  const bool closed = sqlite3_close(db_) == SQLITE_OK;
  db_ = nullptr;
  if (!closed) throw std::runtime_error(path_ + ": cannot close the sqlite3 file");
}

}  // namespace rgbdvo
