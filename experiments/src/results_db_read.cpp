// Reading the results database: the stored run keys, an experiment's runs as a result set, the
// explorer's summaries and metric columns, an experiment's record, and one stored run or repair.
#include <sqlite3.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>
#include <stdexcept>

#include "coverbench/param_codec.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/wall_file.hpp"
#include "run_columns.hpp"
#include "sqlite_statement.hpp"

namespace coverbench {
namespace {

/// The columns of run_options a LEFT JOIN selects (alias o), in the order storedOptions reads.
constexpr const char* kOptionColumns =
    "o.vehicle, o.lift_s, o.lower_s, o.transit, o.transit_iterations, car.turn_radius, car.reverse";
/// The joins kOptionColumns needs (after the runs table, alias r).
constexpr const char* kOptionJoins = " LEFT JOIN run_options o ON o.run_key = r.key LEFT JOIN run_car car ON car.run_key = r.key ";
/// The vehicle and transit planner in columns i .. i + 4 (kOptionColumns): holonomic and
/// visibility when the run has no row in run_options.
void storedOptions(const Statement& s, int i, VehicleModel& vehicle, TransitSpec& transit) {
  vehicle = VehicleModel{};
  transit = TransitSpec{};
  if (s.columnNull(i)) return;
  if (!parseVehicleKind(s.columnText(i), vehicle.kind)) throw std::runtime_error("run_options: unknown vehicle " + s.columnText(i));
  vehicle.lift_s = s.columnReal(i + 1);
  vehicle.lower_s = s.columnReal(i + 2);
  transit.planner = s.columnText(i + 3);
  transit.iterations = s.columnInt(i + 4);
  if (!s.columnNull(i + 5)) {
    vehicle.turn_radius = s.columnReal(i + 5);
    vehicle.reverse = s.columnInt(i + 6) != 0;
  }
}

/// A stored name as a message shows it: its first 40 bytes, odd bytes as \xHH.
std::string storedName(const std::string& name) {
  return "'" + shownBytes(name.substr(0, 40)) + (name.size() > 40 ? "...'" : "'");
}

/// The profile in columns i .. i + 6 (profileColumns: the target and the flow last): none when the
/// run has no row in run_profile. A kind or a flow this build does not know is an InputError naming
/// the database `file` and the table.
FluxProfile storedProfile(const Statement& s, int i, const std::string& file) {
  FluxProfile p;
  if (s.columnNull(i)) return p;
  if (!parseFluxProfileKind(s.columnText(i), p.kind) || !p.set())
    throw InputError(file, "run_profile.kind", "must be uniform, gaussian or beta, got " + storedName(s.columnText(i)));
  p.sigma = s.columnReal(i + 1);
  p.beta = s.columnReal(i + 2);
  p.rate = s.columnReal(i + 3);
  p.depth = s.columnReal(i + 4);
  if (!s.columnNull(i + 5)) p.target = s.columnReal(i + 5);
  if (!s.columnNull(i + 6) && !parseFlow(s.columnText(i + 6), p.flow))
    throw InputError(file, "run_profile_flow.flow", "must be constant or speed, got " + storedName(s.columnText(i + 6)));
  return p;
}

/// Whether the database has the table `name` (one opened read-only may predate it).
bool hasTable(sqlite3* db, const std::string& file, const std::string& name) {
  Statement t(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?", file);
  t.text(1, name);
  return t.step();
}

/// The tool's shape in column i (run_tool_shape, alias ts) and a rectangle's depth in column i + 1
/// (run_tool_depth, alias td), into `tool`: a disk when the run has no row.
void storedShape(const Statement& s, int i, ToolParams& tool) {
  tool.shape = ToolShape::Disk;
  if (!s.columnNull(i) && !parseToolShape(s.columnText(i), tool.shape)) throw std::runtime_error("run_tool_shape: unknown shape " + s.columnText(i));
  tool.depth = tool.isRectangle() && !s.columnNull(i + 1) ? s.columnReal(i + 1) : 0.0;
  if (tool.isRectangle() && !(tool.depth > 0.0)) throw std::runtime_error("run_tool_depth: a rectangle tool's run has no depth");
}

/// The two columns storedShape reads and their joins on the run key `key` ("r.key"), NULL where
/// the database predates their tables.
std::pair<std::string, std::string> shapeColumns(sqlite3* db, const std::string& file, const std::string& key) {
  const bool shapes = hasTable(db, file, "run_tool_shape"), depths = hasTable(db, file, "run_tool_depth");
  return {std::string(shapes ? "ts.shape" : "NULL") + ", " + (depths ? "td.depth" : "NULL"),
          (shapes ? "LEFT JOIN run_tool_shape ts ON ts.run_key = " + key + " " : std::string()) +
              (depths ? "LEFT JOIN run_tool_depth td ON td.run_key = " + key + " " : std::string())};
}

/// The seven columns storedProfile reads (run_profile, run_profile_target, run_profile_flow) and
/// their joins on the run key `key`, NULL where a database made before a table lacks it (its runs:
/// no profile, no target, a constant flow).
std::pair<std::string, std::string> profileColumns(sqlite3* db, const std::string& file, const std::string& key) {
  const bool profiles = hasTable(db, file, "run_profile"), targets = hasTable(db, file, "run_profile_target"),
             flows = hasTable(db, file, "run_profile_flow");
  return {std::string(profiles ? "pr.kind, pr.sigma, pr.beta, pr.rate, pr.depth" : "NULL, NULL, NULL, NULL, NULL") + ", " +
              (targets ? "pt.target" : "NULL") + ", " + (flows ? "pf.flow" : "NULL"),
          (profiles ? "LEFT JOIN run_profile pr ON pr.run_key = " + key + " " : std::string()) +
              (targets ? "LEFT JOIN run_profile_target pt ON pt.run_key = " + key + " " : std::string()) +
              (flows ? "LEFT JOIN run_profile_flow pf ON pf.run_key = " + key + " " : std::string())};
}

/// Each tool configuration is its own group: with several, every column is "label @ tool" (a
/// line tool's label names its shape: never pooled with the disk of its width).
void labelTools(ResultSet& rs) {
  std::set<std::tuple<double, double, ToolShape, double>> tools;
  for (const ResultRow& r : rs.runs) tools.insert({r.tool.tool_width, r.tool.clearance, r.tool.shape, r.tool.depth});
  if (tools.size() <= 1) return;
  auto suffix = [](double w, double c, ToolShape shape, double depth) {
    ToolParams t{w, c};
    t.shape = shape;
    t.depth = depth;
    return " @ " + toolLabel(t);
  };
  std::vector<std::string> columns;
  for (const std::string& label : rs.planners)
    for (const auto& [w, c, shape, depth] : tools) columns.push_back(label + suffix(w, c, shape, depth));
  rs.planners = columns;
  for (ResultRow& r : rs.runs) r.planner = r.config + suffix(r.tool.tool_width, r.tool.clearance, r.tool.shape, r.tool.depth);
}

/// A byte count in GiB, with one decimal ("1.5 GiB").
std::string gibibytes(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / (1024.0 * 1024 * 1024));
  return buf;
}

/// The experiment's row (the latest when none is named) into `rs`; its id.
long long loadExperimentRow(sqlite3* db, const std::string& file, std::optional<long long> experiment, ResultSet& rs) {
  Statement s(db,
              experiment ? "SELECT id, name, config_hash, baseline FROM experiments WHERE id = ?"
                         : "SELECT id, name, config_hash, baseline FROM experiments ORDER BY id DESC LIMIT 1",
              file);
  if (experiment) s.integer(1, *experiment);
  if (!s.step()) throw InputError(file, "experiments", experiment ? "has no experiment " + std::to_string(*experiment) : "is empty");
  rs.experiment = s.columnText(1);
  rs.config_hash = s.columnText(2);
  rs.baseline = s.columnText(3);
  return s.columnInt(0);
}

}  // namespace

std::vector<ResultsDb::StoredKey> ResultsDb::storedKeys() {
  std::vector<StoredKey> out;
  Statement s(db_, "SELECT key, base_key, planner_version, code_sha256, status FROM runs", file_);
  while (s.step()) {
    StoredKey k{s.columnText(0), s.columnText(1), s.columnText(2), s.columnText(3)};
    readField(s, 4, file_, kRunFields[1], k.status);
    out.push_back(std::move(k));
  }
  return out;
}

ResultSet ResultsDb::load(std::optional<long long> experiment) {
  ResultSet rs;
  const long long id = loadExperimentRow(db_, file_, experiment, rs);
  std::map<std::string, std::string> label_of, params_of;
  {
    Statement s(db_,
                "SELECT e.config_id, e.label, p.params FROM experiment_planners e JOIN planner_configs p ON p.id = e.config_id "
                "WHERE e.experiment_id = ? ORDER BY e.position",
                file_);
    s.integer(1, id);
    while (s.step()) {
      label_of[s.columnText(0)] = s.columnText(1);
      params_of[s.columnText(0)] = s.columnText(2);
      rs.planners.push_back(s.columnText(1));
    }
  }
  {
    // Metric order: as the engine lists them (position), then the run figures.
    Statement s(db_,
                "SELECT name FROM metrics m JOIN experiment_runs e ON e.run_key = m.run_key WHERE e.experiment_id = ? "
                "GROUP BY name ORDER BY MIN(position), name",
                file_);
    s.integer(1, id);
    while (s.step()) rs.metric_order.push_back(s.columnText(0));
    rs.metric_order.push_back("plan_time_ms");
    rs.metric_order.push_back("peak_memory_bytes");
  }
  std::map<std::string, std::size_t> index;
  {
    // The context (columns 0 .. 7), the options (8 .. 14), the profile (15 .. 21), the tool's
    // shape and depth (22, 23), then the run's fields (24 ..).
    const auto [profile_columns, profile_joins] = profileColumns(db_, file_, "r.key");
    const auto [shape_columns, shape_joins] = shapeColumns(db_, file_, "r.key");
    Statement s(db_,
                "SELECT r.config_id, w.dataset, r.wall_hash, r.tool_width, r.clearance, r.seed, ws.name, r.planner_version, " +
                    std::string(kOptionColumns) + ", " + profile_columns + ", " + shape_columns + ", " +
                    runFieldSelect("r") + " FROM runs r "
                "JOIN experiment_runs e ON e.run_key = r.key AND e.experiment_id = ?1 "
                "JOIN experiment_walls w ON w.wall_hash = r.wall_hash AND w.experiment_id = ?1 "
                "JOIN walls ws ON ws.hash = r.wall_hash" + std::string(kOptionJoins) + profile_joins +
                    shape_joins + "ORDER BY r.key",
                file_);
    s.integer(1, id);
    while (s.step()) {
      ResultRow row;
      row.planner = label_of[s.columnText(0)];
      row.params = params_of[s.columnText(0)];
      row.dataset = s.columnText(1);
      row.wall = s.columnText(2);
      char pairing[160];
      std::snprintf(pairing, sizeof pairing, "%s/%.17g/%.17g/%lld", row.wall.c_str(), s.columnReal(3), s.columnReal(4),
                    s.columnInt(5));
      row.pairing = pairing;
      row.config = row.planner;
      row.wall_name = s.columnText(6);
      row.planner_version = s.columnText(7);
      row.tool = ToolParams{s.columnReal(3), s.columnReal(4), storedProfile(s, 15, file_)};
      storedShape(s, 22, row.tool);
      if (row.tool.isLine()) row.pairing += "/line";  // runs pair only with the same tool
      if (row.tool.isRectangle()) row.pairing += "/rectangle/" + shortNumber(row.tool.depth);
      storedOptions(s, 8, row.vehicle, row.transit);
      int i = 24;
      forEachRunField(static_cast<RunFields&>(row), [&](const RunField& f, auto& value) { readField(s, i++, file_, f, value); });
      // The measured fields the metric registry lists are the tables' metrics too.
      row.metrics["plan_time_ms"] = row.plan_time_ms;
      if (std::isfinite(row.peak_memory_bytes)) row.metrics["peak_memory_bytes"] = row.peak_memory_bytes;
      index[row.key] = rs.runs.size();
      rs.runs.push_back(std::move(row));
    }
  }
  labelTools(rs);
  // So is each transit planner: with several, every column also gets "@ transit=NAME" (in the
  // registry's order), and runs differing only in it pair up on the same walls.
  std::set<std::string> used;
  for (const ResultRow& r : rs.runs) used.insert(r.transit.planner);
  if (used.size() > 1) {
    std::vector<std::string> columns;
    for (const std::string& label : rs.planners)
      for (const TransitPlannerInfo& t : transitPlanners())
        if (used.count(t.name)) columns.push_back(label + " @ transit=" + t.name);
    rs.planners = columns;
    for (ResultRow& r : rs.runs) r.planner += " @ transit=" + r.transit.planner;
  }
  // Rows (run key, name, value) of the experiment's runs into a map of each run. NULL is how
  // infinities are stored (min_clearance with no obstacles): kept out of statistics.
  auto named = [&](const std::string& sql, std::map<std::string, double> ResultRow::*into) {
    Statement s(db_, sql, file_);
    s.integer(1, id);
    while (s.step()) {
      const auto it = index.find(s.columnText(0));
      if (it != index.end() && !s.columnNull(2)) (rs.runs[it->second].*into)[s.columnText(1)] = s.columnReal(2);
    }
  };
  named("SELECT m.run_key, m.name, m.value FROM metrics m JOIN experiment_runs e ON e.run_key = m.run_key "
        "WHERE e.experiment_id = ?1",
        &ResultRow::metrics);
  if (used.size() > 1 || (used.size() == 1 && *used.begin() != TransitSpec{}.planner))
    named("SELECT t.run_key, t.name, t.value FROM planner_stats t JOIN experiment_runs e ON e.run_key = t.run_key "
          "WHERE e.experiment_id = ?1 AND t.name LIKE 'transit\\_%' ESCAPE '\\' "
          "UNION ALL SELECT t.run_key, 'transit_ms', t.ms FROM planner_timings t JOIN experiment_runs e "
          "ON e.run_key = t.run_key WHERE e.experiment_id = ?1 AND t.name = 'transit'",
          &ResultRow::transit_figures);
  {
    Statement s(db_,
                "SELECT p.run_key, p.position, p.fraction, p.repair, p.obstacles, p.requested, p.status, p.valid, p.repair_ms "
                "FROM replans p JOIN experiment_runs e ON e.run_key = p.run_key WHERE e.experiment_id = ?1 "
                "ORDER BY p.run_key, p.position",
                file_);
    s.integer(1, id);
    while (s.step()) {
      const auto it = index.find(s.columnText(0));
      if (it == index.end()) continue;
      ReplanRow p;
      p.fraction = s.columnReal(2);
      p.repair = s.columnText(3);
      p.obstacles = static_cast<std::size_t>(s.columnInt(4));
      p.requested = static_cast<std::size_t>(s.columnInt(5));
      p.status = s.columnText(6);
      p.valid = s.columnInt(7) != 0;
      p.repair_ms = s.columnNull(8) ? NAN : s.columnReal(8);
      rs.runs[it->second].replans.push_back(std::move(p));
    }
    Statement f(db_,
                "SELECT f.run_key, f.position, f.name, f.value FROM replan_figures f JOIN experiment_runs e "
                "ON e.run_key = f.run_key WHERE e.experiment_id = ?1",
                file_);
    f.integer(1, id);
    while (f.step()) {
      const auto it = index.find(f.columnText(0));
      if (it == index.end() || f.columnNull(3)) continue;
      auto& replans = rs.runs[it->second].replans;
      const auto pos = static_cast<std::size_t>(f.columnInt(1));
      if (pos < replans.size()) replans[pos].figures[f.columnText(2)] = f.columnReal(3);
    }
  }
  return rs;
}

std::vector<ResultsDb::ExperimentEntry> ResultsDb::experiments() {
  std::vector<ExperimentEntry> out;
  Statement s(db_,
              "SELECT e.id, e.name, (SELECT COUNT(*) FROM experiment_runs r WHERE r.experiment_id = e.id) "
              "FROM experiments e ORDER BY e.id",
              file_);
  while (s.step()) out.push_back({s.columnInt(0), s.columnText(1), s.columnInt(2)});
  return out;
}

std::vector<ResultsDb::RunSummary> ResultsDb::runSummaries(long long experiment) {
  {
    Statement s(db_, "SELECT 1 FROM experiments WHERE id = ?", file_);
    s.integer(1, experiment);
    if (!s.step()) throw InputError(file_, "experiments", "has no experiment " + std::to_string(experiment));
  }
  std::map<std::string, std::string> label_of;
  {
    Statement s(db_, "SELECT config_id, label FROM experiment_planners WHERE experiment_id = ? ORDER BY position", file_);
    s.integer(1, experiment);
    while (s.step()) label_of.emplace(s.columnText(0), s.columnText(1));
  }
  const std::set<std::string> columns = runColumns();
  auto column = [&](const char* name) { return columns.count(name) ? std::string("r.") + name : std::string("NULL"); };
  // The tool's profile (columns 11 .. 17), shape and depth (18, 19), as load() reads them: a line,
  // a rectangle or a profile is another tool than the plain disk of its width.
  const auto [profile_columns, profile_joins] = profileColumns(db_, file_, "e.run_key");
  const auto [shape_columns, shape_joins] = shapeColumns(db_, file_, "e.run_key");
  Statement s(db_,
              "SELECT e.run_key, r.config_id, w.dataset, r.wall_hash, ws.name, r.status, r.tool_width, r.clearance, " +
                  column("plan_time_ms") + ", " + column("peak_memory_bytes") + ", COALESCE(o.transit, ''), " +
                  profile_columns + ", " + shape_columns +
                  " FROM experiment_runs e JOIN runs r ON r.key = e.run_key "
                  "JOIN experiment_walls w ON w.experiment_id = ?1 AND w.wall_hash = r.wall_hash "
                  "JOIN walls ws ON ws.hash = r.wall_hash LEFT JOIN run_options o ON o.run_key = e.run_key " +
                  profile_joins + shape_joins + "WHERE e.experiment_id = ?1 ORDER BY e.run_key",
              file_);
  s.integer(1, experiment);
  std::vector<RunSummary> out;
  std::vector<std::string> transits;
  std::set<std::string> used;
  while (s.step()) {
    RunSummary r;
    r.key = s.columnText(0);
    r.planner = label_of[s.columnText(1)];
    r.dataset = s.columnText(2);
    r.wall = s.columnText(3);
    r.wall_name = s.columnText(4);
    readField(s, 5, file_, kRunFields[1], r.status);
    r.tool = ToolParams{s.columnReal(6), s.columnReal(7), storedProfile(s, 11, file_)};
    storedShape(s, 18, r.tool);
    r.plan_time_ms = s.columnReal(8);
    r.peak_memory_bytes = s.columnReal(9);
    transits.push_back(s.columnText(10).empty() ? TransitSpec{}.planner : s.columnText(10));
    used.insert(transits.back());
    out.push_back(std::move(r));
  }
  // Runs that differ only in their transit planner are different configurations (as in load()).
  if (used.size() > 1)
    for (std::size_t i = 0; i < out.size(); ++i) out[i].planner += " @ transit=" + transits[i];
  return out;
}

std::vector<std::string> ResultsDb::metricNames(long long experiment) {
  std::vector<std::string> names;
  // The metrics a run has are the engine's (and the exact judge's, the same for every run of an
  // experiment): one build stores the same names for every scored run. So the names of one scored
  // run per build are all of them, read without scanning every metric of 10^5 runs.
  Statement s(db_,
              "SELECT name FROM metrics WHERE run_key IN (SELECT MIN(r.key) FROM experiment_runs e JOIN runs r ON r.key = e.run_key "
              "WHERE e.experiment_id = ?1 AND EXISTS (SELECT 1 FROM metrics x WHERE x.run_key = r.key) GROUP BY r.build) "
              "GROUP BY name ORDER BY MIN(position), name",
              file_);
  s.integer(1, experiment);
  while (s.step()) names.push_back(s.columnText(0));
  names.push_back("plan_time_ms");
  names.push_back("peak_memory_bytes");
  return names;
}

std::vector<double> ResultsDb::metricColumn(long long experiment, const std::string& metric) {
  std::vector<double> out;
  Statement s(db_,
              "SELECT m.value FROM experiment_runs e LEFT JOIN metrics m ON m.run_key = e.run_key AND m.name = ?2 "
              "WHERE e.experiment_id = ?1 ORDER BY e.run_key",
              file_);
  s.integer(1, experiment).text(2, metric);
  while (s.step()) out.push_back(s.columnReal(0));
  return out;
}

std::map<std::string, std::map<std::string, double>> ResultsDb::metricsOf(const std::vector<std::string>& run_keys) {
  std::map<std::string, std::map<std::string, double>> out;
  const std::set<std::string> columns = runColumns();
  const std::string peak = columns.count("peak_memory_bytes") ? "peak_memory_bytes" : "NULL";
  Statement m(db_, "SELECT name, value FROM metrics WHERE run_key = ?", file_);
  Statement r(db_, "SELECT plan_time_ms, " + peak + " FROM runs WHERE key = ?", file_);
  for (const std::string& key : run_keys) {
    auto& into = out[key];
    m.text(1, key);
    while (m.step())
      if (!m.columnNull(1)) into[m.columnText(0)] = m.columnReal(1);
    m.reset();
    r.text(1, key);
    if (r.step()) {
      into["plan_time_ms"] = r.columnReal(0);
      if (!r.columnNull(1)) into["peak_memory_bytes"] = r.columnReal(1);
    }
    r.reset();
  }
  return out;
}

ExperimentRecord ResultsDb::record(std::optional<long long> experiment) {
  ExperimentRecord r;
  {
    Statement s(db_,
                std::string("SELECT id, name, COALESCE(config_path, ''), config_text, config_hash, baseline, command_line, "
                            "git_revision, git_diff_sha256, compiler, build_type, build_flags, host, cpu, cores, os, "
                            "memory_bytes, workers, started_at, COALESCE(finished_at, ''), runs_total, runs_executed, "
                            "runs_skipped, runs_reused, COALESCE(rerun_reasons, '') FROM experiments ") +
                    (experiment ? "WHERE id = ?" : "ORDER BY id DESC LIMIT 1"),
                file_);
    if (experiment) s.integer(1, *experiment);
    if (!s.step())
      throw InputError(file_, "experiments", experiment ? "has no experiment " + std::to_string(*experiment) : "is empty");
    r.id = s.columnInt(0);
    r.name = s.columnText(1);
    r.config_path = s.columnText(2);
    r.config_text = s.columnText(3);
    r.config_hash = s.columnText(4);
    r.baseline = s.columnText(5);
    r.motion = configMotion(r.config_text, file_ + ": experiments.config_text").describe();
    auto count = [&](int column) { return s.columnNull(column) ? std::string("-") : std::to_string(s.columnInt(column)); };
    const std::string revision = s.columnText(7), diff = s.columnText(8);
    r.facts = {{"command line", s.columnText(6)},
               {"git revision", revision + (diff.empty() ? "" : " with uncommitted changes (diff sha256 " + diff + ")")},
               {"compiler", s.columnText(9)},
               {"build type", s.columnText(10)},
               {"build flags", s.columnText(11)},
               {"host", s.columnText(12)},
               {"CPU", s.columnText(13)},
               {"cores", std::to_string(s.columnInt(14))},
               {"OS", s.columnText(15)},
               {"memory", s.columnNull(16) ? "-" : gibibytes(s.columnReal(16))},
               {"worker processes", std::to_string(s.columnInt(17))},
               {"started (UTC)", s.columnText(18)},
               {"finished (UTC)", s.columnText(19).empty() ? "not finished" : s.columnText(19)},
               {"runs", count(20) + " (" + count(21) + " executed, " + count(22) + " already stored, " + count(23) +
                            " reused from other builds)"},
               {"run again because", s.columnText(24).empty() ? "-" : s.columnText(24)}};
  }
  {
    // A shard, or a merge of shards: say so next to the run counts.
    Statement sh(db_, "SELECT shard_index, shard_count, config_runs FROM experiment_shard WHERE experiment_id = ?", file_);
    sh.integer(1, r.id);
    if (sh.step())
      r.facts.push_back({"shard", std::to_string(sh.columnInt(0)) + "/" + std::to_string(sh.columnInt(1)) + " (" +
                                      std::to_string(sh.columnInt(2)) + " runs in the whole config)"});
    Statement m(db_,
                "SELECT COUNT(DISTINCT shard_index), MAX(shard_count), COUNT(DISTINCT host), SUM(runs) FROM merged_shards "
                "WHERE experiment_id = ?",
                file_);
    m.integer(1, r.id);
    if (m.step() && m.columnInt(0) > 0)
      r.facts.push_back({"merged from", std::to_string(m.columnInt(0)) + " shards of " + std::to_string(m.columnInt(1)) +
                                            " run on " + std::to_string(m.columnInt(2)) + " host(s) (table merged_shards)"});
  }
  {
    Statement s(db_,
                "SELECT label, source, walls, sha256 FROM experiment_datasets WHERE experiment_id = ? ORDER BY position",
                file_);
    s.integer(1, r.id);
    while (s.step()) r.datasets.push_back({s.columnText(0), s.columnText(1), s.columnText(3), s.columnInt(2)});
  }
  {
    Statement s(db_,
                "SELECT e.label, p.planner, p.params FROM experiment_planners e JOIN planner_configs p ON p.id = e.config_id "
                "WHERE e.experiment_id = ? ORDER BY e.position",
                file_);
    s.integer(1, r.id);
    while (s.step()) r.planners.push_back({s.columnText(0), s.columnText(1), s.columnText(2)});
  }
  {
    Statement s(db_,
                "SELECT w.hash, w.name, w.content FROM walls w JOIN experiment_walls e ON e.wall_hash = w.hash "
                "WHERE e.experiment_id = ? ORDER BY w.hash",
                file_);
    s.integer(1, r.id);
    while (s.step()) {
      const Wall wall = parseWallJson(s.columnText(2), file_ + " (wall " + s.columnText(1) + ")");
      r.walls.push_back({s.columnText(0), s.columnText(1), wall.obstacles.size(), std::fabs(signedArea(wall.boundary))});
    }
  }
  return r;
}

std::optional<Path> ResultsDb::path(const std::string& run_key) {
  Statement s(db_, "SELECT data FROM paths WHERE run_key = ?", file_);
  s.text(1, run_key);
  if (!s.step()) return std::nullopt;
  try {
    return decodePath(s.columnBlob(0));
  } catch (const InputError& e) {
    throw InputError(file_, "paths[" + run_key + "]", e.problem());
  }
}

ResultsDb::StoredRun ResultsDb::storedRun(const std::string& key_prefix) {
  if (key_prefix.size() < 6 || key_prefix.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw InputError("--run", "run", "must be at least 6 lowercase hex digits of a run key");
  Statement s(db_,
              "SELECT r.key, w.content, w.name, p.planner, p.params, r.tool_width, r.clearance, r.status, r.reason, " +
                  std::string(kOptionColumns) + ", " +
                  (runColumns().count("stderr_tail") ? "r.stderr_tail" : "''") +
                  " FROM runs r JOIN walls w ON w.hash = r.wall_hash JOIN planner_configs p ON p.id = r.config_id" +
                  std::string(kOptionJoins) +
              "WHERE r.key >= ?1 AND r.key < ?1 || 'g' ORDER BY r.key LIMIT 2",
              file_);
  s.text(1, key_prefix);
  if (!s.step()) throw InputError(file_, "runs", "no run key starts with " + key_prefix);
  StoredRun run;
  run.key = s.columnText(0);
  run.wall = parseWallJson(s.columnText(1), file_ + " (wall " + s.columnText(2) + ")");
  const std::string params = storedParamsLine(s.columnText(4));
  run.planner = s.columnText(3) + (params.empty() ? "" : " (" + params + ")");
  run.planner_name = s.columnText(3);
  run.params_json = s.columnText(4);
  run.tool = ToolParams{s.columnReal(5), s.columnReal(6)};
  run.status = s.columnText(7);
  run.reason = s.columnText(8);
  TransitSpec transit;
  storedOptions(s, 9, run.vehicle, transit);
  run.stderr_tail = s.columnText(16);  // after the 7 option columns
  if (s.step()) throw InputError(file_, "runs", "several run keys start with " + key_prefix + ": give more digits");
  if (std::optional<Path> p = path(run.key)) run.path = std::move(*p);
  {
    const auto [shape_columns, shape_joins] = shapeColumns(db_, file_, "r.key");
    Statement shape(db_, "SELECT " + shape_columns + " FROM runs r " + shape_joins + "WHERE r.key = ?", file_);
    shape.text(1, run.key);
    try {
      if (shape.step()) storedShape(shape, 0, run.tool);
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      throw InputError(file_, what.substr(0, what.find(':')), what.substr(what.find(':') + 2));
    }
  }
  // The tool's flux profile and the time model: the config's (the run key holds them).
  Statement c(db_,
              "SELECT e.config_text FROM experiments e JOIN experiment_runs x ON x.experiment_id = e.id WHERE x.run_key = ? "
              "ORDER BY e.id DESC LIMIT 1",
              file_);
  c.text(1, run.key);
  if (c.step()) {
    const std::string source = file_ + ": experiments.config_text";
    run.motion = configMotion(c.columnText(0), source);
    run.tool.profile = configProfile(c.columnText(0), source, run.tool.tool_width);
  }
  return run;
}

ResultsDb::StoredRun ResultsDb::storedReplan(const std::string& key_prefix, std::size_t position) {
  StoredRun run = storedRun(key_prefix);
  Statement s(db_,
              "SELECT fraction, repair, obstacles_json, status, reason, path, cut_waypoint FROM replans WHERE run_key = ? AND position = ?",
              file_);
  s.text(1, run.key).integer(2, static_cast<long long>(position));
  if (!s.step()) {
    Statement n(db_, "SELECT COUNT(*) FROM replans WHERE run_key = ?", file_);
    n.text(1, run.key);
    n.step();
    const long long count = n.columnInt(0);
    throw InputError("--replan", "replan",
                     "run " + run.key.substr(0, 12) + " has " +
                         (count ? std::to_string(count) + " repairs (numbers 0 to " + std::to_string(count - 1) + ")"
                                : std::string("no repairs (its experiment had no replanning: section)")) +
                         ", not number " + std::to_string(position));
  }
  char what[96];
  std::snprintf(what, sizeof what, ", obstacles at %g, repaired by %s", s.columnReal(0), s.columnText(1).c_str());
  run.planner += what;
  for (Obstacle& o : parseObstaclesJson(s.columnText(2), file_ + " (replans of " + run.key.substr(0, 12) + ")"))
    run.wall.obstacles.push_back(std::move(o));
  run.status = s.columnText(3);
  run.reason = s.columnText(4);
  run.path = s.columnNull(5) ? Path{} : decodePath(s.columnBlob(5));
  run.first_judged_segment = static_cast<std::size_t>(s.columnInt(6));
  return run;
}

}  // namespace coverbench
