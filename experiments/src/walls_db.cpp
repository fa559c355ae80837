#include "coverbench/walls_db.hpp"

#include <sqlite3.h>

#include <filesystem>

#include "coverbench/hash.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/wall_file.hpp"
#include "sqlite_statement.hpp"

namespace coverbench {
namespace {

constexpr long long kWallsApplicationId = 0x4376574c;  // "CvWL"

}  // namespace

WallsDb::WallsDb(const std::string& path) : file_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path, "(database)", "is a folder, not a walls database file");
  // A FIFO or a device would hang the first read, or be written to (a link the user names is
  // followed, as for every file on the command line; what it leads to must be a file).
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    throw InputError(path, "(database)", "is not a regular file (a FIFO, a device or a socket cannot be a walls database)");
  const bool empty = !fs::exists(path, ec) || fs::file_size(path, ec) == 0;
  // SQLite makes -wal and -shm files beside a WAL database it reads: a refused file keeps only
  // what it had beside it.
  const bool had_wal = fs::exists(path + "-wal", ec), had_shm = fs::exists(path + "-shm", ec);
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw InputError(path, "(database)", "cannot be opened: " + why);
  }
  sqlite3_busy_timeout(db_, 10000);
  try {
    if (!empty) {
      long long id = 0;
      try {
        Statement a(db_, "PRAGMA application_id", file_);
        if (a.step()) id = a.columnInt(0);
      } catch (const InputError& e) {
        throw InputError(file_, "(database)", "is not a CoverBench walls database (" + e.problem() + ")");
      }
      if (id != kWallsApplicationId) throw InputError(file_, "(database)", "is not a CoverBench walls database (its application_id)");
    }
    char* error = nullptr;
    const std::string sql =
        "BEGIN IMMEDIATE; CREATE TABLE IF NOT EXISTS walls (name TEXT PRIMARY KEY, content TEXT NOT NULL, "
        "sha256 TEXT NOT NULL, saved_at TEXT NOT NULL); PRAGMA application_id = " +
        std::to_string(kWallsApplicationId) + "; COMMIT;";
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string why = error ? error : "unknown error";
      sqlite3_free(error);
      sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
      throw InputError(file_, "(database)", "cannot be written: " + why);
    }
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    if (!had_wal) fs::remove(path + "-wal", ec);
    if (!had_shm) fs::remove(path + "-shm", ec);
    throw;
  }
}

WallsDb::~WallsDb() { sqlite3_close(db_); }

std::vector<WallsDb::Entry> WallsDb::list() {
  std::vector<Entry> out;
  Statement s(db_, "SELECT name, sha256, saved_at FROM walls ORDER BY name", file_);
  while (s.step()) out.push_back({s.columnText(0), s.columnText(1), s.columnText(2)});
  return out;
}

std::string WallsDb::content(const std::string& name) {
  Statement s(db_, "SELECT content FROM walls WHERE name = ?", file_);
  s.text(1, name);
  if (!s.step()) throw InputError(file_, "walls", "has no wall named '" + name + "'");
  return s.columnText(0);
}

WallsDb::Entry WallsDb::save(const Wall& wall) {
  const std::string text = wallToJson(wall);
  Entry e{wall.name, sha256Hex(text), utcNow()};
  Statement s(db_, "INSERT OR REPLACE INTO walls (name, content, sha256, saved_at) VALUES (?, ?, ?, ?)", file_);
  s.text(1, e.name).text(2, text).text(3, e.sha256).text(4, e.saved_at);
  s.run();
  return e;
}

}  // namespace coverbench
