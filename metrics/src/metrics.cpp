// All metrics of one path, and their flat, ordered form.
#include "coverbench/metrics.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace coverbench {

void checkScorable(const Path& path, const std::string& source) {
  if (path.waypoints.size() > kMaxScoredWaypoints)
    throw InputError(source, "waypoints",
                     "has " + std::to_string(path.waypoints.size()) + " waypoints; scoring is limited to " +
                         std::to_string(kMaxScoredWaypoints));
  for (std::size_t i = 0; i < path.waypoints.size(); ++i) {
    const Point p = path.waypoints[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::fabs(p.x) > kMaxPathCoordinate ||
        std::fabs(p.y) > kMaxPathCoordinate)
      throw InputError(source, "waypoints[" + std::to_string(i) + "]",
                       "coordinate beyond 100 km (or not finite): no wall reaches there");
  }
  for (std::size_t i = 0; i < path.segments(); ++i) {
    const double bulge = path.bulgeOf(i);
    if (bulge == 0.0) continue;
    const ArcGeometry arc = arcGeometry(path.waypoints[i], path.waypoints[i + 1], bulge);
    const double chords = arcChords(arc, kArcCheckSagitta);
    if (!(chords <= static_cast<double>(kMaxArcChords))) {
      char problem[256];
      std::snprintf(problem, sizeof problem,
                    "an arc of radius %.6g m needs %.3g chords of %g m to be checked, at most %zu (a half circle of "
                    "about 800 m radius)",
                    arc.radius, chords, kArcCheckSagitta,
                    kMaxArcChords);
      throw InputError(source, "bulge[" + std::to_string(i) + "]", problem);
    }
  }
}


void checkLineScorable(const Path& path, const ToolParams& tool, const VehicleModel& vehicle, const std::string& source) {
  const std::string shape = toString(tool.shape);
  if (vehicle.isCar())
    throw InputError(source, "tool.shape", "a " + shape + " tool on a car is not scored yet (its arcs' swept shapes): use a disk");
  for (std::size_t i = 0; i < path.segments(); ++i)
    if (path.bulgeOf(i) != 0.0)
      throw InputError(source, "bulge[" + std::to_string(i) + "]", "a " + shape + " tool's path is scored on straight moves only, and this one is an arc");
}

PathMetrics computeMetrics(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle,
                           const MotionLimits& limits, Coat* coat, std::size_t block_cells) {
  checkScorable(path, "path");
  if (tool.turnsWithHeading()) checkLineScorable(path, tool, vehicle, "path");
  PathMetrics m;
  m.validity = checkValidity(wall, tool, path, vehicle);
  m.lengths = pathLengths(path);
  // The pass counts take arcs as arcs; an invalid path's coverage polygons take them as chords.
  m.passes = passes(path, tool);
  m.coverage = coverage(wall, tool, path, m.validity, m.passes.swept_area);
  m.motion = motion(path, limits, vehicle);
  m.waypoints = path.waypoints.size();
  const double ideal = m.coverage.reachable_area / tool.tool_width;
  m.length_ratio = ideal > 0.0 ? m.lengths.total / ideal : 0.0;
  if (tool.profile.set()) {
    try {
      Coat scored = coverbench::coat(wall, tool, path, tool.profile, limits, vehicle, coat ? block_cells : 0);
      m.deposition = scored.stats;
      if (coat) *coat = std::move(scored);
    } catch (const InputError& e) {  // the raster cap: the coat alone is not scored
      if (e.source() != "deposition") throw;
      m.coat_not_scored = e.what();
    }
  }
  return m;
}

std::string coatNotScoredNote(const PathMetrics& m) {
  return m.coat_not_scored.empty() ? "" : "the coat's metrics are not scored (the others are): " + m.coat_not_scored;
}

std::string withNote(const std::string& reason, const std::string& note) {
  if (note.empty()) return reason;
  return reason.empty() ? note : reason + "; " + note;
}

std::vector<NamedMetric> flatten(const PathMetrics& m) {
  std::vector<NamedMetric> out = {
      {"valid", m.validity.valid ? 1.0 : 0.0},
      {"violations", static_cast<double>(m.validity.violations)},
      {"outside_boundary", static_cast<double>(m.validity.outside_boundary)},
      {"too_close", static_cast<double>(m.validity.too_close)},
      {"min_clearance", m.validity.min_clearance},
      {"min_boundary_gap", m.validity.min_boundary_gap},
      {"coverage_reachable", m.coverage.coverage_reachable},
      {"coverage_wall", m.coverage.coverage_wall},
      {"reachable_area", m.coverage.reachable_area},
      {"paintable_area", m.coverage.paintable_area},
      {"swept_area", m.coverage.swept_area},
      {"overlap", m.passes.overlap},
  };
  for (std::size_t k = 0; k < m.passes.histogram.size(); ++k) {
    const bool last = k + 1 == m.passes.histogram.size();
    out.push_back({"passes_" + std::to_string(k + 1) + (last ? "_or_more" : ""), m.passes.histogram[k]});
  }
  const std::vector<NamedMetric> rest = {
      {"length_total", m.lengths.total},
      {"length_cover", m.lengths.cover},
      {"length_transit", m.lengths.transit},
      {"length_ratio", m.length_ratio},
      {"turns", static_cast<double>(m.motion.turns)},
      {"turns_30", static_cast<double>(m.motion.turns_30)},
      {"turning_angle", m.motion.turning_angle},
      {"duration_s", m.motion.duration_s},
      {"waypoints", static_cast<double>(m.waypoints)},
  };
  out.insert(out.end(), rest.begin(), rest.end());
  if (m.motion.turn_cost_s) out.push_back({"turn_cost_s", *m.motion.turn_cost_s});
  if (m.deposition) {
    const Deposition& d = *m.deposition;
    const std::vector<NamedMetric> coat = {{"thickness_mean", d.mean_um},     {"thickness_cv", d.cv},
                                           {"even_share", d.even_share},      {"thin_share", d.thin_share},
                                           {"thick_share", d.thick_share}};
    out.insert(out.end(), coat.begin(), coat.end());
  } else if (!m.coat_not_scored.empty()) {  // named, with no value: the coat was asked for, not scored
    for (const char* name : {"thickness_mean", "thickness_cv", "even_share", "thin_share", "thick_share"})
      out.push_back({name, NAN});
  }
  return out;
}

}  // namespace coverbench
