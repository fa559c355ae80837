#pragma once
// A prepared SQLite statement, finalised on scope exit; errors throw InputError naming the file.
// Internal to the experiments library (results_db.cpp, merge.cpp).
#include <sqlite3.h>

#include <cmath>
#include <string>

#include "coverbench/wall.hpp"

namespace coverbench {

/// A prepared statement, finalised on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const std::string& file) : db_(db), file_(file) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) fail("prepare");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement& text(int i, const std::string& v) {
    sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& real(int i, double v) {
    if (std::isfinite(v)) sqlite3_bind_double(stmt_, i, v);
    else sqlite3_bind_null(stmt_, i);  // infinities (no obstacles: min_clearance) and NaN are stored as NULL
    return *this;
  }
  Statement& integer(int i, long long v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  Statement& null(int i) {
    sqlite3_bind_null(stmt_, i);
    return *this;
  }
  /// Binds a value read from another statement's column (columnValue), as it is.
  Statement& value(int i, const sqlite3_value* v) {
    sqlite3_bind_value(stmt_, i, v);
    return *this;
  }
  Statement& blob(int i, const std::string& v) {
    sqlite3_bind_blob(stmt_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  /// Steps once; true while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail("step");
    return false;
  }
  /// Makes the statement ready to bind and step again.
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  void run() {
    step();
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::string columnText(int i) const {
    const auto* p = sqlite3_column_text(stmt_, i);
    return p ? reinterpret_cast<const char*>(p) : "";
  }
  double columnReal(int i) const { return sqlite3_column_type(stmt_, i) == SQLITE_NULL ? NAN : sqlite3_column_double(stmt_, i); }
  bool columnNull(int i) const { return sqlite3_column_type(stmt_, i) == SQLITE_NULL; }
  long long columnInt(int i) const { return sqlite3_column_int64(stmt_, i); }
  int columnCount() const { return sqlite3_column_count(stmt_); }
  /// The column's value as SQLite holds it, valid until the next step: for copying rows.
  const sqlite3_value* columnValue(int i) const { return sqlite3_column_value(stmt_, i); }
  std::string columnBlob(int i) const {
    const void* p = sqlite3_column_blob(stmt_, i);
    return p ? std::string(static_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(stmt_, i))) : "";
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw InputError(file_, "(database)", std::string(what) + ": " + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string file_;
};

}  // namespace coverbench
