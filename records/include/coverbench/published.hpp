#pragma once
/// Published results: a table of values measured elsewhere (a paper's), which the report sets
/// beside this experiment's planner configurations on the same walls (docs/report.md, "Published
/// results"). The table is the user's data; CoverBench ships none.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/motion.hpp"

namespace coverbench {

/// The largest published table read, in bytes, and in rows: a paper's table has hundreds of rows;
/// 16 MiB and 100 000 rows leave room for any benchmark while a wrong file (a database, a log) is
/// refused before it is read.
inline constexpr std::size_t kMaxPublishedBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxPublishedRows = 100000;
/// The longest instance and method names, in bytes.
inline constexpr std::size_t kMaxPublishedName = 200;

/// One row of the table: `instance,method,metric,value`.
struct PublishedValue {
  std::string instance;  ///< matched to a wall's name
  std::string method;    ///< the published method (a name from the paper)
  std::string metric;    ///< a compared metric of the registry (docs/metrics.md)
  std::optional<double> value;  ///< empty: the method did not solve the instance
  int line = 0;          ///< 1-based line in the file
};

struct PublishedTable {
  std::string file;    ///< as the config or --published names it
  std::string sha256;  ///< of its bytes
  /// The time model its times (duration_s, turn_cost_s) were measured with; empty: unknown.
  std::optional<MotionLimits> clock;
  /// Whether that clock is the experiment's own (set by the report): only then are its time
  /// metrics compared.
  bool clock_matches = false;
  std::vector<PublishedValue> values;  ///< in file order
};

/// Reads and checks a published table (the format is in docs/report.md): at most
/// kMaxPublishedBytes of UTF-8 text, the header `instance,method,metric,value`, then one row per
/// line of four fields (instance and method may be quoted, "" for a quote; no line break inside),
/// at most kMaxPublishedRows rows, each (instance, method, metric) once, the metric a compared
/// quality metric of the registry, the value empty or a finite number >= 0. Throws InputError
/// (`FILE:LINE`, field, problem) at the first problem.
PublishedTable readPublishedTable(const std::string& path, std::optional<MotionLimits> clock);

/// Whether two time models give every duration the same value (every field equal).
bool sameClock(const MotionLimits& a, const MotionLimits& b);

}  // namespace coverbench
