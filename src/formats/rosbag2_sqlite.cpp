/// @file rosbag2_sqlite.cpp
/// A rosbag2 SQLite log (see rosbag2_sqlite.hpp).

#include "rosbag2_sqlite.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "ros2_definitions.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw FileError("'" + path + "': rosbag2: " + what);
}

/// One database, read-only; statements prepared and stepped with errors naming the file.
class Database {
 public:
  explicit Database(const std::string& file) : file_(file) {
    sqlite3* raw = nullptr;
    const int status = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(raw);
    if (status != SQLITE_OK) fail(file, std::string("cannot open the database: ") + sqlite3_errstr(status));
  }
  /// Runs `sql` with `parameter` bound to its ?1 (when given), calling `row(statement)` for each row.
  template <class Row>
  void query(const std::string& sql, Row&& row, const std::string* parameter = nullptr) const {
    const auto statement = prepare(sql, parameter);
    while (step(statement.get())) row(statement.get());
  }
  /// `sql` prepared, with `parameter` bound to its ?1 (when given).
  /// @throws FileError naming the file when it does not prepare.
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> prepare(const std::string& sql, const std::string* parameter = nullptr) const {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) {
      fail(file_, std::string("not a rosbag2 database (") + sqlite3_errmsg(db_.get()) + ")");
    }
    std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> statement(raw, sqlite3_finalize);
    if (parameter != nullptr) sqlite3_bind_text(raw, 1, parameter->c_str(), static_cast<int>(parameter->size()), SQLITE_TRANSIENT);
    return statement;
  }
  /// Steps `statement`: true for a row, false at its end.
  /// @throws FileError naming the file when SQLite cannot read it.
  bool step(sqlite3_stmt* statement) const {
    const int status = sqlite3_step(statement);
    if (status == SQLITE_ROW) return true;
    if (status != SQLITE_DONE) fail(file_, std::string("cannot read the database: ") + sqlite3_errmsg(db_.get()));
    return false;
  }
  bool hasTable(const std::string& name) const {
    bool found = false;
    query("SELECT name FROM sqlite_master WHERE type = 'table' AND name = '" + name + "'", [&](sqlite3_stmt*) { found = true; });
    return found;
  }

 private:
  struct Close {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
  };
  std::string file_;
  std::unique_ptr<sqlite3, Close> db_;
};

std::string column(sqlite3_stmt* statement, int index) {
  const unsigned char* text = sqlite3_column_text(statement, index);
  return text != nullptr ? reinterpret_cast<const char*>(text) : std::string();
}

}  // namespace

bool looksLikeRosbag2Sqlite(const std::string& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(path, error)) {
      if (entry.path().extension() == ".db3") return true;
    }
    return false;
  }
  if (fs::path(path).extension() == ".db3") return true;  // whatever it holds: SQLite says what is wrong
  std::ifstream in(path, std::ios::binary);
  char magic[16] = {};
  return in.read(magic, 16) && std::memcmp(magic, "SQLite format 3", 16) == 0;
}

Rosbag2Sqlite::Rosbag2Sqlite(const std::string& path, const std::string& msg_path) : path_(path) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(path, error)) {
      if (entry.path().extension() == ".db3") files_.push_back(entry.path().string());
    }
    std::sort(files_.begin(), files_.end());
    if (files_.empty()) fail(path, "the folder holds no .db3 file");
  } else {
    files_.push_back(path);
  }
  for (const std::string& file : files_) {
    const Database db(file);
    std::vector<std::pair<std::string, std::string>> definitions;  // type, ros2msg
    if (db.hasTable("message_definitions")) {
      db.query("SELECT topic_type, encoding, encoded_message_definition FROM message_definitions", [&](sqlite3_stmt* s) {
        if (column(s, 1) == "ros2msg") definitions.emplace_back(column(s, 0), column(s, 2));
      });
    }
    db.query(
        "SELECT topics.name, topics.type, topics.serialization_format, COUNT(messages.id), MIN(messages.timestamp), "
        "MAX(messages.timestamp) FROM topics LEFT JOIN messages ON messages.topic_id = topics.id GROUP BY topics.id "
        "ORDER BY topics.id",
        [&](sqlite3_stmt* s) {
          const std::string name = column(s, 0);
          auto topic = std::find_if(topics_.begin(), topics_.end(), [&](const Topic& t) { return t.name == name; });
          if (topic == topics_.end()) {
            Topic fresh;
            fresh.name = name;
            fresh.type = column(s, 1);
            fresh.serialization_format = column(s, 2);
            for (const auto& [type, text] : definitions) {
              if (type == fresh.type) fresh.definition = text;
            }
            if (fresh.definition.empty()) {
              try {
                fresh.definition = msgPathDefinition(fresh.type, msg_path);
              } catch (const Error&) {
                // a type whose .msg files are incomplete: listed without a definition
              }
            }
            if (fresh.definition.empty()) fresh.definition = builtinRos2Definition(fresh.type);
            topics_.push_back(fresh);
            topic = topics_.end() - 1;
          }
          const auto count = static_cast<std::size_t>(sqlite3_column_int64(s, 3));
          if (count == 0) return;
          const double first_s = 1e-9 * static_cast<double>(sqlite3_column_int64(s, 4));
          const double last_s = 1e-9 * static_cast<double>(sqlite3_column_int64(s, 5));
          topic->first_s = topic->messages == 0 ? first_s : std::min(topic->first_s, first_s);
          topic->last_s = topic->messages == 0 ? last_s : std::max(topic->last_s, last_s);
          topic->messages += count;
        });
  }
}

struct Rosbag2Sqlite::Cursor::Query {
  Query(const std::string& file, const std::string& topic)
      : db(file),
        statement(db.prepare("SELECT messages.timestamp, messages.data FROM messages JOIN topics ON messages.topic_id = "
                             "topics.id WHERE topics.name = ?1 ORDER BY messages.timestamp, messages.id",
                             &topic)) {}
  Database db;
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> statement;
};

Rosbag2Sqlite::Cursor::Cursor(const Rosbag2Sqlite& log, std::string topic) : log_(&log), topic_(std::move(topic)) {}
Rosbag2Sqlite::Cursor::~Cursor() = default;
Rosbag2Sqlite::Cursor::Cursor(Cursor&&) noexcept = default;
Rosbag2Sqlite::Cursor& Rosbag2Sqlite::Cursor::operator=(Cursor&&) noexcept = default;

bool Rosbag2Sqlite::Cursor::next(std::vector<std::uint8_t>& data, double& time_s) {
  for (;;) {
    if (!query_) {
      if (file_ == log_->files_.size()) return false;
      query_ = std::make_unique<Query>(log_->files_[file_++], topic_);
    }
    sqlite3_stmt* s = query_->statement.get();
    if (!query_->db.step(s)) {
      query_.reset();
      continue;
    }
    const auto* bytes = static_cast<const std::uint8_t*>(sqlite3_column_blob(s, 1));
    const int size = sqlite3_column_bytes(s, 1);
    data.assign(bytes, bytes + (bytes != nullptr ? size : 0));
    time_s = 1e-9 * static_cast<double>(sqlite3_column_int64(s, 0));
    return true;
  }
}

void Rosbag2Sqlite::forEachMessage(const std::string& topic,
                                   const std::function<void(const std::vector<std::uint8_t>&, double)>& use) const {
  Cursor cursor(*this, topic);
  std::vector<std::uint8_t> data;
  double time_s = 0.0;
  while (cursor.next(data, time_s)) use(data, time_s);
}

}  // namespace sonarmap::detail
