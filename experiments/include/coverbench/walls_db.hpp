#pragma once
/// A walls database (SQLite): walls saved by name from the explorer's workbench, each with the
/// wall file's text (wallToJson), its SHA-256 and when it was saved. Schema: docs/file_formats.md.
#include <string>
#include <vector>

#include "coverbench/wall.hpp"

struct sqlite3;

namespace coverbench {

class WallsDb {
 public:
  /// Opens the file, creating it when absent or empty. An existing file must be a walls database
  /// (its application_id); anything else is refused with InputError naming the file, untouched.
  explicit WallsDb(const std::string& path);
  ~WallsDb();
  WallsDb(const WallsDb&) = delete;
  WallsDb& operator=(const WallsDb&) = delete;

  struct Entry {
    std::string name, sha256, saved_at;  ///< saved_at: UTC, ISO 8601
  };
  /// Every wall, by name.
  std::vector<Entry> list();
  /// The wall file text saved under `name`; InputError when there is none.
  std::string content(const std::string& name);
  /// Saves the wall under its name (replacing a wall of that name) in one transaction; returns
  /// what was stored.
  Entry save(const Wall& wall);
  const std::string& file() const { return file_; }

 private:
  sqlite3* db_ = nullptr;
  std::string file_;
};

}  // namespace coverbench
