#pragma once
// A prepared SQLite statement that finalizes itself, for the fleet's SQLite store: binds
// optional text and numbers (null when absent), reads columns by index.

#include <sqlite3.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace wavebench::fleet {

class SqliteStatement {
 public:
  SqliteStatement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string("sqlite results store: ") + sqlite3_errmsg(db));
    }
  }
  ~SqliteStatement() { sqlite3_finalize(stmt_); }
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  void bind(int i, const std::optional<std::string>& text) {
    if (!text) {
      sqlite3_bind_null(stmt_, i);
      return;
    }
    sqlite3_bind_text(stmt_, i, text->c_str(), static_cast<int>(text->size()), SQLITE_TRANSIENT);
  }
  void bind_number(int i, std::optional<double> value) {
    if (value) {
      sqlite3_bind_double(stmt_, i, *value);
    } else {
      sqlite3_bind_null(stmt_, i);
    }
  }
  void bind_bool(int i, std::optional<bool> value) {
    if (value) {
      sqlite3_bind_int(stmt_, i, *value ? 1 : 0);
    } else {
      sqlite3_bind_null(stmt_, i);
    }
  }
  // Whether a row is ready; false when done.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("sqlite results store: ") + sqlite3_errmsg(db_));
  }
  std::string text(int col) const {
    const auto* p = sqlite3_column_text(stmt_, col);
    return p ? reinterpret_cast<const char*>(p) : "";
  }
  std::optional<double> number(int col) const {
    if (sqlite3_column_type(stmt_, col) == SQLITE_NULL) return std::nullopt;
    return sqlite3_column_double(stmt_, col);
  }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace wavebench::fleet
