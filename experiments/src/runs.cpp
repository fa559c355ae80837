// Walls of a config, run expansion and keys, executing one run, path encoding.
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <stdexcept>

#include "coverbench/build_identity.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/problem_builder.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench {

std::vector<WallEntry> loadWalls(const ExperimentConfig& config) {
  std::vector<WallEntry> out;
  std::set<std::string> seen;
  for (const DatasetSpec& spec : config.datasets) {
    std::vector<Wall> walls;
    switch (spec.kind) {
      case DatasetSpec::Kind::Family:
        walls = generateWalls(spec.family, spec.seed, spec.count);
        break;
      case DatasetSpec::Kind::Suite:
        walls = generateWalls(spec.family, 0, 0);
        break;
      case DatasetSpec::Kind::Folder:
        walls = readDataset(spec.folder).walls;
        break;
      case DatasetSpec::Kind::Import:
        walls = *spec.imported;
        break;
    }
    for (Wall& w : walls) {
      // The dataset's start and end, for walls that name none of their own.
      if (!w.start && spec.start) w.start = spec.start;
      if (!w.end && (spec.end || spec.end_at_start)) w.end = spec.end_at_start ? w.start : spec.end;
      if (spec.start || spec.end || spec.end_at_start) {
        if (spec.end_at_start && !w.start)
          throw InputError(config.path + ":" + std::to_string(spec.line), "datasets.end",
                           "is start, but wall '" + w.name + "' has no start (give start: [x, y])");
        validateWall(w, config.path + ":" + std::to_string(spec.line) + ": wall '" + w.name + "'");
      }
      WallEntry e;
      e.json = wallToJson(w);
      e.hash = sha256Hex(e.json);
      if (!seen.insert(e.hash).second) continue;
      e.wall = std::move(w);
      e.dataset = spec.label;
      out.push_back(std::move(e));
    }
  }
  return out;
}

namespace {

std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// The run's path under each surprise and repair of spec.replanning (docs/replanning.md). The
/// plan from scratch on the new wall is made once per fraction: it is the replan repair's plan and
/// the detour's yardstick.
std::vector<ReplanRecord> replanRecords(const RunSpec& spec, const PlannerInfo& info, const Problem& problem,
                                        const Path& path, const PathMetrics& original) {
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::time_point since) { return std::chrono::duration<double, std::milli>(Clock::now() - since).count(); };
  std::vector<ReplanRecord> out;
  const double original_uncovered = original.coverage.reachable_area * (1.0 - original.coverage.coverage_reachable);
  for (double fraction : spec.replanning.at) {
    const Surprise surprise = makeSurprise(spec.wall->wall, spec.tool, path, fraction, spec.replanning, spec.seed);
    const std::string obstacles = obstaclesToJson(surprise.obstacles);
    Problem changed = problem;
    changed.wall = &surprise.wall;
    const auto plan_start = Clock::now();
    const PlanResult scratch = runPlanner(info, changed, Budget(std::chrono::duration<double>(spec.time_limit_s)));
    const double plan_ms = ms(plan_start);
    std::optional<PathMetrics> scratch_metrics;
    if (scratch.hasPath()) scratch_metrics = computeMetrics(surprise.wall, spec.tool, scratch.path, spec.vehicle, spec.motion);
    for (RepairMethod method : spec.replanning.repairs) {
      ReplanRecord rec;
      rec.fraction = fraction;
      rec.repair = toString(method);
      rec.obstacles = surprise.obstacles.size();
      rec.requested = surprise.requested;
      rec.obstacles_json = obstacles;
      for (const char* name : kReplanFigures) rec.figures[name] = NAN;
      rec.figures["executed_m"] = surprise.cut.length;
      if (scratch_metrics) {
        rec.figures["scratch_coverage_reachable"] = scratch_metrics->coverage.coverage_reachable;
        rec.figures["scratch_length_m"] = scratch_metrics->lengths.total;
      }
      Repair repair;
      if (method == RepairMethod::Replan) {
        if (!scratch.hasPath()) {
          rec.status = "failed";
          rec.reason = "the new plan failed (" + toString(scratch.status) + "): " + scratch.reason;
          rec.repair_ms = plan_ms;
          out.push_back(std::move(rec));
          continue;
        }
        const auto start = Clock::now();
        repair = repairFromPlan(surprise, changed, scratch.path);
        rec.repair_ms = plan_ms + ms(start);
        if (scratch.status == PlanStatus::Partial)
          repair.reason += std::string(repair.reason.empty() ? "" : "; ") + "the new plan is partial: " + scratch.reason;
      } else {
        const auto start = Clock::now();
        repair = repairByDetour(surprise, changed);
        rec.repair_ms = ms(start);
      }
      rec.figures["kept_moves"] = static_cast<double>(repair.kept_moves);
      rec.figures["dropped_moves"] = static_cast<double>(repair.dropped_moves);
      rec.figures["unreachable_moves"] = static_cast<double>(repair.unreachable_moves);
      rec.figures["transits"] = static_cast<double>(repair.transits);
      rec.figures["blocked_m"] = repair.blocked_m;
      if (!repair.ok) {
        rec.status = "failed";
        rec.reason = "nothing was left to repair";
        out.push_back(std::move(rec));
        continue;
      }
      // The executed part was driven before the obstacles appeared: it is judged on the old wall,
      // the repaired part on the new one; coverage and lengths are of the whole path on the new wall.
      const PathMetrics m = computeMetrics(surprise.wall, spec.tool, repair.path, spec.vehicle, spec.motion);
      const Path repaired = repair.repairedPart();
      const Validity before = checkValidity(spec.wall->wall, spec.tool, surprise.cut.executed, spec.vehicle);
      const Validity after = checkValidity(surprise.wall, spec.tool, repaired, spec.vehicle);
      rec.valid = before.valid && after.valid;
      if (rec.valid && spec.exact_judge)
        rec.valid = judge::judgeValidity(spec.wall->wall, spec.tool, surprise.cut.executed, spec.vehicle).valid &&
                    judge::judgeValidity(surprise.wall, spec.tool, repaired, spec.vehicle).valid;
      rec.figures["added_length_m"] = m.lengths.total - original.lengths.total;
      rec.figures["added_duration_s"] = m.motion.duration_s - original.motion.duration_s;
      rec.figures["coverage_reachable"] = m.coverage.coverage_reachable;
      rec.figures["uncovered_added_m2"] = m.coverage.reachable_area * (1.0 - m.coverage.coverage_reachable) - original_uncovered;
      const bool left_out = repair.leftOut() || (method == RepairMethod::Replan && scratch.status == PlanStatus::Partial);
      rec.status = !rec.valid ? "invalid_output" : left_out ? "partial" : "ok";
      rec.reason = rec.valid ? repair.reason
                             : std::to_string(before.violations) + " executed segments violate the wall, " +
                                   std::to_string(after.violations) + " repaired segments the new wall (or the exact judge finds one)" +
                                   (before.valid ? "" : "; executed: " + describeViolations(before, spec.tool.clearance)) +
                                   (after.valid ? "" : "; repaired: " + describeViolations(after, spec.tool.clearance));
      rec.cut_waypoint = repair.cut_waypoint;
      rec.path = std::move(repair.path);
      out.push_back(std::move(rec));
    }
  }
  return out;
}

}  // namespace

std::string runBaseKey(const RunSpec& spec) {
  std::string text = "coverbench-run/1\nwall=" + spec.wall->hash + "\nplanner=" + spec.planner->planner;
  text += paramsIdentity(spec.planner->params, "param.");
  text += "\ntool_width=" + exact(spec.tool.tool_width) + "\nclearance=" + exact(spec.tool.clearance) +
          "\nseed=" + std::to_string(spec.seed);
  if (const FluxProfile& p = spec.tool.profile; p.set())  // a tool without one keeps its old keys
    text += "\nprofile=" + toString(p.kind) + "\nprofile.sigma=" + exact(p.sigma) + "\nprofile.beta=" + exact(p.beta) +
            "\nprofile.rate=" + exact(p.rate) + "\nprofile.depth=" + exact(p.depthFor(spec.tool.tool_width));  // 0 is s/10
  if (const FluxProfile& p = spec.tool.profile; p.target > 0.0)  // a profile without one keeps its old keys
    text += "\nprofile.target=" + exact(p.target);
  if (spec.tool.profile.flow == FluxProfile::Flow::Speed) text += "\nprofile.flow=speed";  // a constant flow keeps its keys
  if (spec.tool.turnsWithHeading()) text += "\ntool_shape=" + toString(spec.tool.shape);  // a disk keeps its old keys
  if (spec.tool.isRectangle()) text += "\ntool_depth=" + exact(spec.tool.depth);
  if (spec.exact_judge) text += "\njudge=exact";
  if (spec.vehicle.isCar())
    text += "\nvehicle=car\nturn_radius=" + exact(spec.vehicle.turn_radius) + "\nreverse=" + (spec.vehicle.reverse ? "1" : "0");
  else if (!spec.vehicle.isDefault())
    text += "\nvehicle=" + toString(spec.vehicle.kind) + "\nlift_s=" + exact(spec.vehicle.lift_s) +
            "\nlower_s=" + exact(spec.vehicle.lower_s);
  if (!spec.transit.isDefault())
    text += "\ntransit=" + spec.transit.planner + "\ntransit_iterations=" + std::to_string(spec.transit.iterations);
  if (spec.replanning.enabled()) text += "\nreplanning=" + spec.replanning.describe();
  if (!spec.motion.isDefault())
    text += "\nmotion.speed=" + exact(spec.motion.speed) + "\nmotion.acceleration=" + exact(spec.motion.acceleration) +
            "\nmotion.stops=" + (spec.motion.stops == MotionLimits::Stops::Waypoints ? "waypoints" : "turns") +
            "\nmotion.stop_angle=" + exact(spec.motion.stop_angle_deg) + "\nmotion.turn_cost_s=" + exact(spec.motion.turn_cost_s) +
            (spec.motion.rotates() ? "\nmotion.rotation_speed=" + exact(spec.motion.rotation_speed) : std::string());
  return sha256Hex(text);
}

std::string runKey(const RunSpec& spec) {
  return sha256Hex("coverbench-run/2\nbase=" + runBaseKey(spec) + "\nversion=" + spec.planner_version +
                   "\ncode=" + spec.code_sha256);
}

std::size_t runsPerWall(const ExperimentConfig& config) {
  return config.planners.size() * config.tools.size() * config.transits.size();
}

std::vector<RunSpec> expandRuns(const ExperimentConfig& config, const std::vector<WallEntry>& walls,
                                const std::function<bool(const RunSpec&)>& keep, std::size_t* expanded) {
  // Every axis of a run but the wall, as one index: planner configuration, then tool, then
  // transit planner. runsPerWall is the only count of them, so a shard's count of the config's
  // runs is the number this loop expands.
  const std::size_t per_wall = runsPerWall(config);
  const std::size_t transits = config.transits.size(), tools = config.tools.size();
  std::vector<RunSpec> runs;
  if (!keep) runs.reserve(walls.size() * per_wall);
  std::size_t count = 0;
  for (const WallEntry& wall : walls)
    for (std::size_t axis = 0; axis < per_wall; ++axis, ++count) {
      const PlannerConfig& planner = config.planners[axis / (tools * transits)];
      RunSpec spec;
      spec.wall = &wall;
      spec.planner = &planner;
      spec.tool = config.tools[(axis / transits) % tools];
      spec.vehicle = config.vehicle;
      spec.motion = config.motion;
      spec.transit = config.transits[axis % transits];
      spec.replanning = config.replanning;
      spec.repetitions = config.repetitions;
      spec.seed = config.seed;
      spec.time_limit_s = config.time_limit_s;
      spec.memory_limit_bytes = static_cast<std::size_t>(config.memory_limit_mb * 1024.0 * 1024.0);
      spec.exact_judge = config.exact_judge;
      const PlannerInfo& info = findPlanner(planner.planner);
      spec.planner_version = info.version;
      std::vector<std::string> folders = info.code_folders;
      if (spec.exact_judge) folders.push_back(kJudgeCodeFolder);  // the judge's code is in what it computes
      spec.code_sha256 = buildIdentity().plannerCode(folders);
      if (!info.code_sha256.empty())  // a planner outside the tree: its manifest and files too
        spec.code_sha256 = sha256Hex(spec.code_sha256 + "\nexternal=" + info.code_sha256);
      spec.base_key = runBaseKey(spec);
      if (keep && !keep(spec)) continue;  // a shard holds only its own runs, even while expanding
      spec.key = runKey(spec);
      runs.push_back(std::move(spec));
    }
  if (expanded) *expanded = count;
  return runs;
}

RunRecord executeRun(const RunSpec& spec) {
  RunRecord rec;
  rec.key = spec.key;
  const PlannerInfo& info = findPlanner(spec.planner->planner);
  ProblemInputs inputs;
  inputs.wall = &spec.wall->wall;
  inputs.tool = spec.tool;
  inputs.vehicle = spec.vehicle;
  inputs.motion = spec.motion;
  inputs.transit = spec.transit;
  inputs.params = spec.planner->params;
  inputs.seed = spec.seed;
  inputs.memory_limit_bytes = spec.memory_limit_bytes;
  const Problem problem = buildProblem(info, std::move(inputs), "run " + spec.key);
  PlanResult result;
  // A planner outside the tree: its own processes' CPU time (summed over the repetitions) and peak
  // memory (the largest), not the worker's (measuredRun keeps these).
  double process_cpu_s = NAN, process_peak_bytes = NAN;
  for (int rep = 0; rep < std::max(1, spec.repetitions); ++rep) {
    PlanResult again = runPlanner(info, problem, Budget(std::chrono::duration<double>(spec.time_limit_s)));
    rec.plan_times_ms.push_back(again.plan_time_ms);
    if (std::isfinite(again.process_cpu_s))
      process_cpu_s = (std::isfinite(process_cpu_s) ? process_cpu_s : 0.0) + again.process_cpu_s;
    if (std::isfinite(again.process_peak_bytes))
      process_peak_bytes = std::isfinite(process_peak_bytes) ? std::max(process_peak_bytes, again.process_peak_bytes)
                                                             : again.process_peak_bytes;
    if (rep == 0) result = std::move(again);
  }
  rec.cpu_time_s = process_cpu_s;
  rec.peak_rss_bytes = rec.peak_memory_bytes = process_peak_bytes;
  std::vector<double> sorted = rec.plan_times_ms;
  std::sort(sorted.begin(), sorted.end());
  rec.plan_time_ms = sorted[sorted.size() / 2];
  rec.stats = result.stats;
  rec.timings_ms = result.timings_ms;
  rec.status = runStatusOf(result.status);
  rec.reason = result.reason;
  if (result.hasPath()) {
    std::optional<PathMetrics> original;
    try {
      const PathMetrics m = computeMetrics(spec.wall->wall, spec.tool, result.path, spec.vehicle, spec.motion);
      original = m;
      rec.valid = m.validity.valid;
      for (const NamedMetric& metric : flatten(m)) rec.metrics.emplace_back(metric.name, metric.value);
      rec.uncovered_reachable_m2 = m.coverage.reachable_area * (1.0 - m.coverage.coverage_reachable);
      if (!rec.valid) {  // the planner's claim does not survive the check
        rec.status = RunStatus::InvalidOutput;
        rec.reason = describeViolations(m.validity, spec.tool.clearance) +
                     (result.reason.empty() ? "" : "; the planner said: " + result.reason);
      }
      if (spec.exact_judge) {
        const judge::Judgement j = judge::judgePath(spec.wall->wall, spec.tool, result.path, spec.vehicle);
        const double exact_figures[] = {
            j.validity.valid ? 1.0 : 0.0, static_cast<double>(j.validity.violations),
            j.coverage.coverage_reachable.lower, j.coverage.coverage_reachable.upper,
            j.coverage.coverage_wall.lower, j.coverage.coverage_wall.upper};
        for (std::size_t i = 0; i < std::size(kExactJudgeMetrics); ++i)
          rec.metrics.push_back({std::string(kExactJudgeMetrics[i]), exact_figures[i]});
        if (rec.valid && !j.validity.valid) {
          rec.valid = false;
          rec.status = RunStatus::InvalidOutput;
          std::string first;
          for (std::size_t i = 0; i < std::min<std::size_t>(j.validity.violating.size(), kDescribedViolations); ++i)
            first += (i == 0 ? ": segment " : ", ") + std::to_string(j.validity.violating[i]);
          rec.reason = "the exact judge finds " + std::to_string(j.validity.violations) +
                       " segments that violate the wall or the clearance (the fast engine, with its 1e-9 m tolerance, "
                       "finds none)" + first + (result.reason.empty() ? "" : "; the planner said: " + result.reason);
        }
      }
      rec.reason = withNote(rec.reason, coatNotScoredNote(m));
      rec.reason = withNote(rec.reason, toolShapeNote(info, spec.tool, result));
    } catch (const std::exception& e) {  // a path beyond the scoring limits, or a bug in the judge
      rec.status = RunStatus::MetricsError;
      rec.reason = std::string("the path could not be scored: ") + e.what();
    }
    // Surprises only for a valid, scored path (an invalid one has nothing to repair honestly).
    if (spec.replanning.enabled() && rec.valid && original) {
      try {
        rec.replans = replanRecords(spec, info, problem, result.path, *original);
      } catch (const std::exception& e) {
        rec.status = RunStatus::MetricsError;
        rec.reason = std::string("replanning could not be scored: ") + e.what();
        rec.replans.clear();
      }
    }
    rec.path = std::move(result.path);
  }
  // The end of an external planner's stderr, kept with a run that failed in a way it may explain.
  if (rec.status == RunStatus::Crash || rec.status == RunStatus::Error || rec.status == RunStatus::InvalidOutput)
    rec.stderr_tail = result.stderr_tail;
  return rec;
}

std::string encodePath(const Path& path) {
  // u32 waypoint count, then x, y per waypoint (IEEE 754 little-endian), then one byte per segment.
  std::string raw;
  const auto n = static_cast<std::uint32_t>(path.waypoints.size());
  for (int b = 0; b < 4; ++b) raw.push_back(static_cast<char>((n >> (8 * b)) & 0xff));
  auto put = [&](double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, 8);
    for (int b = 0; b < 8; ++b) raw.push_back(static_cast<char>((bits >> (8 * b)) & 0xff));
  };
  for (const Point& p : path.waypoints) put(p.x), put(p.y);
  for (bool on : path.tool_on) raw.push_back(on ? 1 : 0);
  if (path.hasArcs())  // then one bulge per segment (a car's arcs); paths without arcs keep their bytes
    for (double b : path.bulge) put(b);
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string out(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw std::runtime_error("zlib compress failed");
  out.resize(size);
  // Prefix the raw length so decoding knows the buffer size.
  std::string framed;
  const auto len = static_cast<std::uint32_t>(raw.size());
  for (int b = 0; b < 4; ++b) framed.push_back(static_cast<char>((len >> (8 * b)) & 0xff));
  return framed + out;
}

Path decodePath(const std::string& blob) {
  auto corrupt = [](const std::string& why) { return InputError("path blob", "data", "is corrupt: " + why); };
  auto u32 = [](const std::string& s, std::size_t at) {
    std::uint32_t v = 0;
    for (int b = 0; b < 4; ++b) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + b])) << (8 * b);
    return v;
  };
  if (blob.size() < 4) throw corrupt("shorter than its 4-byte length prefix");
  // zlib expands by at most 1032:1, so a larger claimed size is corrupt: refused before allocating.
  const std::uint64_t claimed = u32(blob, 0);
  if (claimed < 4 || claimed > 1032ULL * (blob.size() - 4) + 64)
    throw corrupt("claims " + std::to_string(claimed) + " bytes from " + std::to_string(blob.size() - 4) + " compressed");
  std::string raw(claimed, '\0');
  uLongf size = static_cast<uLongf>(raw.size());
  if (uncompress(reinterpret_cast<Bytef*>(raw.data()), &size, reinterpret_cast<const Bytef*>(blob.data() + 4),
                 static_cast<uLong>(blob.size() - 4)) != Z_OK ||
      size != raw.size())
    throw corrupt("zlib data does not decompress to the stated size");
  const std::uint64_t n = u32(raw, 0);
  const std::uint64_t segments = n ? n - 1 : 0;
  const bool arcs = raw.size() == 4 + 16ULL * n + 9 * segments && segments > 0;
  if (raw.size() != 4 + 16ULL * n + segments && !arcs) throw corrupt("wrong size for its waypoint count");
  Path path;
  auto get = [&](std::size_t at) {
    std::uint64_t bits = 0;
    for (int b = 0; b < 8; ++b) bits |= static_cast<std::uint64_t>(static_cast<unsigned char>(raw[at + b])) << (8 * b);
    double v;
    std::memcpy(&v, &bits, 8);
    return v;
  };
  for (std::uint64_t i = 0; i < n; ++i) {
    const Point p{get(4 + 16 * i), get(12 + 16 * i)};
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw corrupt("waypoint " + std::to_string(i) + " is not finite");
    path.waypoints.push_back(p);
  }
  for (std::uint64_t i = 0; i + 1 < n; ++i) path.tool_on.push_back(raw[4 + 16 * n + i] != 0);
  if (arcs)
    for (std::uint64_t i = 0; i < segments; ++i) {
      const double b = get(4 + 16 * n + segments + 8 * i);
      if (!std::isfinite(b) || std::fabs(b) > 1.0) throw corrupt("bulge " + std::to_string(i) + " is not in [-1, 1]");
      path.bulge.push_back(effectiveBulge(path.waypoints[i], path.waypoints[i + 1], b));
    }
  return path;
}

}  // namespace coverbench
