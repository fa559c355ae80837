// Writing the results database: an experiment's row with its walls, datasets, planners and run
// keys; each run's record in one transaction; the experiment's end.
#include <sqlite3.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "coverbench/build_identity.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/results_db.hpp"
#include "run_columns.hpp"
#include "sqlite_statement.hpp"

namespace coverbench {
namespace {

/// The resolved parameters as a JSON object, numbers with full precision (paramsJson reads it).
std::string paramsText(const PlannerConfig& pc) {
  return paramsJson(pc.params).dump();
}

}  // namespace

long long ResultsDb::beginExperiment(const ExperimentConfig& config, const Provenance& prov,
                                     const std::vector<WallEntry>& walls, const std::vector<std::string>& run_keys,
                                     const ShardRecord* shard) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement e(db_,
                "INSERT INTO experiments (name, config_path, config_text, config_hash, baseline, command_line, "
                "git_revision, git_diff_sha256, compiler, build_type, build_flags, host, cpu, cores, os, memory_bytes, "
                "workers, started_at, runs_total) VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)",
                file_);
    e.text(1, config.name).text(2, config.path).text(3, config.text).text(4, config.hash).text(5, config.baseline);
    e.text(6, prov.command_line).text(7, prov.git_revision).text(8, prov.git_diff_sha256).text(9, prov.compiler);
    e.text(10, prov.build_type).text(11, prov.build_flags).text(12, prov.host).text(13, prov.cpu);
    e.integer(14, prov.cores).text(15, prov.os).real(16, prov.memory_bytes).integer(17, prov.workers);
    e.text(18, prov.started_at).integer(19, static_cast<long long>(run_keys.size())).run();
    const long long id = sqlite3_last_insert_rowid(db_);
    Statement w(db_, "INSERT OR IGNORE INTO walls (hash, name, content) VALUES (?,?,?)", file_);
    Statement ew(db_, "INSERT OR IGNORE INTO experiment_walls (experiment_id, wall_hash, dataset) VALUES (?,?,?)", file_);
    for (const WallEntry& wall : walls) {
      if (!shard || shard->wall_hashes.count(wall.hash)) w.text(1, wall.hash).text(2, wall.wall.name).text(3, wall.json).run();
      ew.integer(1, id).text(2, wall.hash).text(3, wall.dataset).run();
    }
    // Each dataset's identity: the SHA-256 of its walls' content hashes, in order.
    Statement ed(db_,
                 "INSERT INTO experiment_datasets (experiment_id, position, label, source, walls, sha256) VALUES "
                 "(?,?,?,?,?,?)",
                 file_);
    for (std::size_t i = 0; i < config.datasets.size(); ++i) {
      const DatasetSpec& d = config.datasets[i];
      std::string hashes;
      long long count = 0;
      for (const WallEntry& wall : walls)
        if (wall.dataset == d.label) hashes += wall.hash + "\n", ++count;
      const std::string source = d.kind == DatasetSpec::Kind::Family ? "family " + d.family + " count " +
                                                                           std::to_string(d.count) + " seed " +
                                                                           std::to_string(d.seed)
                                 : d.kind == DatasetSpec::Kind::Suite ? "suite " + d.family
                                                                      : "folder " + d.folder;
      ed.integer(1, id).integer(2, static_cast<long long>(i)).text(3, d.label).text(4, source).integer(5, count);
      ed.text(6, sha256Hex(hashes)).run();
    }
    Statement p(db_, "INSERT OR IGNORE INTO planner_configs (id, planner, params) VALUES (?,?,?)", file_);
    Statement ep(db_, "INSERT INTO experiment_planners (experiment_id, position, config_id, label) VALUES (?,?,?,?)", file_);
    for (std::size_t i = 0; i < config.planners.size(); ++i) {
      const PlannerConfig& pc = config.planners[i];
      p.text(1, pc.id).text(2, pc.planner).text(3, paramsText(pc)).run();
      ep.integer(1, id).integer(2, static_cast<long long>(i)).text(3, pc.id).text(4, pc.label).run();
    }
    Statement er(db_, "INSERT OR IGNORE INTO experiment_runs (experiment_id, run_key) VALUES (?,?)", file_);
    for (const std::string& key : run_keys) er.integer(1, id).text(2, key).run();
    if (shard) {
      Statement es(db_, "INSERT INTO experiment_shard (experiment_id, shard_index, shard_count, config_runs) VALUES (?,?,?,?)",
                   file_);
      es.integer(1, id).integer(2, shard->shard.index).integer(3, shard->shard.count);
      es.integer(4, static_cast<long long>(shard->config_runs)).run();
    }
    exec("COMMIT");
    return id;
  } catch (...) {
    rollback();
    throw;
  }
}

void ResultsDb::storeRun(const RunSpec& spec, const RunRecord& rec) {
  prepared("BEGIN IMMEDIATE").run();
  try {
    // A retried run replaces everything stored under its key.
    for (const char* table : {"run_repetitions", "metrics", "planner_stats", "planner_timings", "paths", "run_options",
                              "run_car", "run_profile", "run_profile_target", "run_profile_flow", "run_tool_shape", "run_tool_depth", "replans", "replan_figures"}) {
      Statement& d = prepared(std::string("DELETE FROM ") + table + " WHERE run_key = ?");
      d.text(1, rec.key).run();
    }
    // The run's fields (kRunFields, the key first), its context, and when it finished.
    std::string marks;
    for (std::size_t n = 0; n < kRunFieldCount + std::size(kRunContextColumns); ++n) marks += "?,";
    Statement& r = prepared("INSERT OR REPLACE INTO runs (" + runColumnList() + ") VALUES (" + marks + "?)");
    int column = 0;
    forEachRunField(rec, [&](const RunField&, const auto& value) { bindField(r, ++column, value); });
    const int c = column;  // the context's columns follow, in kRunContextColumns' order
    r.text(c + 1, spec.base_key).text(c + 2, spec.wall->hash).text(c + 3, spec.planner->id);
    r.text(c + 4, spec.planner_version).text(c + 5, spec.code_sha256).text(c + 6, buildIdentity().describe());
    r.real(c + 7, spec.tool.tool_width).real(c + 8, spec.tool.clearance).integer(c + 9, static_cast<long long>(spec.seed));
    r.integer(c + 10, spec.repetitions).text(c + 11, utcNow()).run();
    if (!spec.vehicle.isDefault() || !spec.transit.isDefault()) {
      Statement& v = prepared(
          "INSERT INTO run_options (run_key, vehicle, lift_s, lower_s, transit, transit_iterations) VALUES (?,?,?,?,?,?)");
      v.text(1, rec.key).text(2, toString(spec.vehicle.kind)).real(3, spec.vehicle.lift_s).real(4, spec.vehicle.lower_s);
      v.text(5, spec.transit.planner).integer(6, spec.transit.iterations).run();
    }
    if (spec.vehicle.isCar()) {
      Statement& car = prepared("INSERT INTO run_car (run_key, turn_radius, reverse) VALUES (?,?,?)");
      car.text(1, rec.key).real(2, spec.vehicle.turn_radius).integer(3, spec.vehicle.reverse ? 1 : 0).run();
    }
    if (const FluxProfile& p = spec.tool.profile; p.set()) {
      Statement& profile =
          prepared("INSERT INTO run_profile (run_key, kind, sigma, beta, rate, depth) VALUES (?,?,?,?,?,?)");
      profile.text(1, rec.key).text(2, toString(p.kind)).real(3, p.sigma).real(4, p.beta).real(5, p.rate).real(6, p.depth).run();
      if (p.target > 0.0) {
        Statement& target = prepared("INSERT INTO run_profile_target (run_key, target) VALUES (?,?)");
        target.text(1, rec.key).real(2, p.target).run();
      }
      if (p.flow == FluxProfile::Flow::Speed) {
        Statement& flow = prepared("INSERT INTO run_profile_flow (run_key, flow) VALUES (?,?)");
        flow.text(1, rec.key).text(2, toString(p.flow)).run();
      }
    }
    if (spec.tool.turnsWithHeading()) {
      Statement& shape = prepared("INSERT INTO run_tool_shape (run_key, shape) VALUES (?,?)");
      shape.text(1, rec.key).text(2, toString(spec.tool.shape)).run();
    }
    if (spec.tool.isRectangle()) {
      Statement& depth = prepared("INSERT INTO run_tool_depth (run_key, depth) VALUES (?,?)");
      depth.text(1, rec.key).real(2, spec.tool.depth).run();
    }
    if (!rec.replans.empty()) {
      Statement& rr = prepared(
          "INSERT INTO replans (run_key, position, fraction, repair, obstacles, requested, obstacles_json, status, "
          "reason, valid, repair_ms, path, cut_waypoint) VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?)");
      Statement& rf = prepared("INSERT INTO replan_figures (run_key, position, name, value) VALUES (?,?,?,?)");
      for (std::size_t i = 0; i < rec.replans.size(); ++i) {
        const ReplanRecord& p = rec.replans[i];
        const auto pos = static_cast<long long>(i);
        rr.text(1, rec.key).integer(2, pos).real(3, p.fraction).text(4, p.repair);
        rr.integer(5, static_cast<long long>(p.obstacles)).integer(6, static_cast<long long>(p.requested));
        rr.text(7, p.obstacles_json).text(8, p.status).text(9, p.reason).integer(10, p.valid ? 1 : 0).real(11, p.repair_ms);
        if (p.path.waypoints.empty()) rr.null(12);
        else rr.blob(12, encodePath(p.path));
        rr.integer(13, static_cast<long long>(p.cut_waypoint)).run();
        for (const auto& [name, value] : p.figures) rf.text(1, rec.key).integer(2, pos).text(3, name).real(4, value).run();
      }
    }
    Statement& rp = prepared("INSERT INTO run_repetitions (run_key, repetition, plan_time_ms) VALUES (?,?,?)");
    for (std::size_t i = 0; i < rec.plan_times_ms.size(); ++i)
      rp.text(1, rec.key).integer(2, static_cast<long long>(i)).real(3, rec.plan_times_ms[i]).run();
    Statement& m = prepared("INSERT INTO metrics (run_key, position, name, value) VALUES (?,?,?,?)");
    for (std::size_t i = 0; i < rec.metrics.size(); ++i) {
      // Every stored metric is one the registry describes (unit, direction), so reports can read it.
      const auto& [name, value] = rec.metrics[i];
      if (!findMetricSpec(name)) throw std::logic_error("metric '" + name + "' is not in the registry");
      m.text(1, rec.key).integer(2, static_cast<long long>(i)).text(3, name).real(4, value).run();
    }
    Statement& st = prepared("INSERT INTO planner_stats (run_key, name, value) VALUES (?,?,?)");
    for (const auto& [name, value] : rec.stats) st.text(1, rec.key).text(2, name).real(3, value).run();
    Statement& tm = prepared("INSERT INTO planner_timings (run_key, name, ms) VALUES (?,?,?)");
    for (const auto& [name, value] : rec.timings_ms) tm.text(1, rec.key).text(2, name).real(3, value).run();
    if (!rec.path.waypoints.empty()) {
      Statement& p = prepared("INSERT INTO paths (run_key, encoding, waypoints, data) VALUES (?,?,?,?)");
      p.text(1, rec.key).text(2, "zlib-f64le-1").integer(3, static_cast<long long>(rec.path.waypoints.size()));
      p.blob(4, rec.path_blob.empty() ? encodePath(rec.path) : rec.path_blob).run();
    }
    prepared("COMMIT").run();
  } catch (...) {
    rollback();
    throw;
  }
}

void ResultsDb::finishExperiment(long long id, std::size_t executed, std::size_t skipped, std::size_t reused,
                                 const std::string& rerun_reasons) {
  Statement s(db_,
              "UPDATE experiments SET finished_at = ?, runs_executed = ?, runs_skipped = ?, runs_reused = ?, "
              "rerun_reasons = ? WHERE id = ?",
              file_);
  s.text(1, utcNow()).integer(2, static_cast<long long>(executed)).integer(3, static_cast<long long>(skipped));
  s.integer(4, static_cast<long long>(reused)).text(5, rerun_reasons).integer(6, id).run();
}

}  // namespace coverbench
