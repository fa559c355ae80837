#pragma once
// The run fields (records/run_record.hpp) as columns of the results database's `runs` table:
// their SQL types, binding and reading. Used by the results database and the merge.
#include <set>
#include <string>

#include "coverbench/run_record.hpp"
#include "coverbench/wall.hpp"
#include "sqlite_statement.hpp"

namespace coverbench {

/// The column declaration of a field (new databases; columns added to older ones are nullable).
inline const char* sqlType(const RunField& f) {
  switch (f.type) {
    case RunFieldType::Text:
    case RunFieldType::Status: return "TEXT NOT NULL";
    case RunFieldType::Bool: return "INTEGER NOT NULL";
    case RunFieldType::Integer: return "INTEGER";
    case RunFieldType::Real: return "REAL";
  }
  return "";
}

/// The run's context columns of `runs` (what it was run on, by what code), after its fields.
inline constexpr const char* kRunContextColumns[] = {"base_key",    "wall_hash", "config_id", "planner_version",
                                                     "code_sha256", "build",     "tool_width", "clearance",
                                                     "seed",        "repetitions"};
/// Every column storeRun writes, in its order: the fields, the context, when it finished; each
/// name after `prefix`.
inline std::string runColumnList(const std::string& prefix = "") {
  std::string out;
  for (const RunField& f : kRunFields) out += (out.empty() ? "" : ", ") + prefix + f.name;
  for (const char* c : kRunContextColumns) out += ", " + prefix + c;
  return out + ", " + prefix + "finished_at";
}

/// The columns of table `table` in `db`.
inline std::set<std::string> tableColumns(sqlite3* db, const std::string& table, const std::string& file) {
  std::set<std::string> columns;
  Statement s(db, "SELECT name FROM pragma_table_info(?)", file);
  s.text(1, table);
  while (s.step()) columns.insert(s.columnText(0));
  return columns;
}

/// The run fields `keep` accepts as SELECT expressions on the runs table `alias` (whose columns
/// are `columns`), in kRunFields' order, each wrapped as `wrap` says (e.g. "quote(%)"; "%": as is);
/// NULL for a field a database made before it has no column for.
template <class Keep>
std::string runFieldExpressions(const std::set<std::string>& columns, const std::string& alias, Keep&& keep,
                                const std::string& wrap = "%", const std::string& separator = ", ") {
  std::string out;
  for (const RunField& f : kRunFields) {
    if (!keep(f)) continue;
    const std::string expr = columns.count(f.name) ? alias + "." + f.name : std::string("NULL");
    std::string wrapped = wrap;
    wrapped.replace(wrapped.find('%'), 1, expr);
    out += (out.empty() ? "" : separator) + wrapped;
  }
  return out;
}

/// Binds a field's value to parameter i (NaN and infinities as NULL).
inline void bindField(Statement& s, int i, const std::string& v) { s.text(i, v); }
inline void bindField(Statement& s, int i, RunStatus v) { s.text(i, toString(v)); }
inline void bindField(Statement& s, int i, bool v) { s.integer(i, v ? 1 : 0); }
inline void bindField(Statement& s, int i, long long v) { s.integer(i, v); }
inline void bindField(Statement& s, int i, double v) { s.real(i, v); }

/// Reads a field's value from column i: NULL (or a column an older database lacks, selected as
/// NULL) reads as the field's empty value ("", 0, false, NaN); an unknown status is refused.
inline void readField(const Statement& s, int i, const std::string&, const RunField&, std::string& v) {
  v = s.columnNull(i) ? std::string() : s.columnText(i);
}
inline void readField(const Statement& s, int i, const std::string& file, const RunField& f, RunStatus& v) {
  const std::string name = s.columnText(i);
  const auto status = parseRunStatus(name);
  if (!status) throw InputError(file, std::string("runs.") + f.name, "unknown run status '" + name + "'");
  v = *status;
}
inline void readField(const Statement& s, int i, const std::string&, const RunField&, bool& v) { v = s.columnInt(i) != 0; }
inline void readField(const Statement& s, int i, const std::string&, const RunField&, long long& v) {
  v = s.columnNull(i) ? 0 : s.columnInt(i);
}
inline void readField(const Statement& s, int i, const std::string&, const RunField&, double& v) { v = s.columnReal(i); }

}  // namespace coverbench
