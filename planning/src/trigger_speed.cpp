// trigger_speed: the spray switched off where the tool is slow next to a stop (docs/deposition.md).
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/headland.hpp"

namespace coverbench {
namespace {

/// The stretches of one segment to switch off, in metres from its start: [0, front] and
/// [length - back, length] (0: none).
struct Cuts {
  double front = 0.0, back = 0.0;
};

/// How far from the segment's start the speed stays under `speed` (accelerating from v0), and how
/// far before its end (braking to v1); the whole length when it never reaches `speed`.
std::pair<double, double> slowEnds(const SegmentSpeed& sp, double speed) {
  if (!(sp.peak >= speed)) return {sp.length, sp.length};
  const double a = sp.acceleration;
  const double front = sp.v0 < speed ? (speed * speed - sp.v0 * sp.v0) / (2.0 * a) : 0.0;
  const double back = sp.v1 < speed ? (speed * speed - sp.v1 * sp.v1) / (2.0 * a) : 0.0;
  return {std::fmin(front, sp.length), std::fmin(back, sp.length)};
}

/// Per segment, what to switch off: a forward pass from every stop (a segment starting at
/// standstill) while the speed stays under `speed`, and a backward pass from every stop likewise.
std::vector<Cuts> slowStretches(const std::vector<SegmentSpeed>& speeds, double speed) {
  std::vector<Cuts> cuts(speeds.size());
  bool from_stop = false;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    const SegmentSpeed& sp = speeds[i];
    if (!(sp.length > 0.0)) continue;  // no time on it: the stretch goes on through it
    if (sp.v0 == 0.0) from_stop = true;
    if (!from_stop) continue;
    const auto [front, back] = slowEnds(sp, speed);
    cuts[i].front = front;
    from_stop = front >= sp.length;
  }
  bool to_stop = false;
  for (std::size_t i = speeds.size(); i-- > 0;) {
    const SegmentSpeed& sp = speeds[i];
    if (!(sp.length > 0.0)) continue;
    if (sp.v1 == 0.0) to_stop = true;
    if (!to_stop) continue;
    const auto [front, back] = slowEnds(sp, speed);
    cuts[i].back = back;
    to_stop = back >= sp.length;
  }
  return cuts;
}

/// Appends to `out` the piece of segment i of `path` from t0 to t1 (fractions of its length) with
/// the given tool state: the same line, or the same circle.
void appendPiece(Path& out, const Path& path, std::size_t i, double t0, double t1, bool tool) {
  const Point a = path.waypoints[i], b = path.waypoints[i + 1];
  const double bulge = path.bulgeOf(i);
  Point to = b;
  double piece_bulge = bulge;
  if (t1 < 1.0 || t0 > 0.0) {
    if (bulge == 0.0) {
      to = t1 < 1.0 ? a + (b - a) * t1 : b;
    } else {
      const ArcGeometry g = arcGeometry(a, b, bulge);
      const double start = std::atan2(a.y - g.centre.y, a.x - g.centre.x), angle = start + g.sweep * t1;
      if (t1 < 1.0) to = {g.centre.x + g.radius * std::cos(angle), g.centre.y + g.radius * std::sin(angle)};
      piece_bulge = effectiveBulge(out.waypoints.back(), to, std::tan(g.sweep * (t1 - t0) / 4.0));
    }
  }
  out.waypoints.push_back(to);
  out.tool_on.push_back(tool);
  if (!path.bulge.empty()) out.bulge.push_back(piece_bulge);
}

}  // namespace

ParamSpec triggerSpeedParam() {
  return {"trigger_speed", ParamType::Number, 0.0, 0.0, 0.99, {}, "",
          "0: the spray is on wherever the path paints; else a fraction of the time model's speed under which "
          "it is off while the tool accelerates out of or brakes into a stop (row ends, corners): no coat built "
          "up where the tool is slow, less covered there (docs/deposition.md)"};
}

std::string triggerSpeedCheck(const Problem& problem, double trigger_speed) {
  if (!(trigger_speed > 0.0)) return "";
  if (problem.vehicle.liftsTool())
    return "trigger_speed is not for a gantry: it stops to lower or lift its tool at every change of tool state, "
           "so the spray cannot switch at speed";
  if (problem.motion.stops == MotionLimits::Stops::Waypoints)
    return "trigger_speed needs a time model that does not stop at every waypoint (stops: waypoints stops where "
           "the spray switches)";
  if (problem.straight_segments_only)
    return "trigger_speed does not take a path smoothed for a car after planning (car_plan: smoothed): the car "
           "stops elsewhere; use car_plan: headland";
  return "";
}

Path switchOffWhileSlow(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle, double speed,
                        double* off_m) {
  if (off_m) *off_m = 0.0;
  if (path.waypoints.size() < 2 || !(speed > 0.0)) return path;
  const std::vector<Cuts> cuts = slowStretches(segmentSpeeds(path, limits, vehicle), speed);
  Path out;
  out.waypoints.push_back(path.waypoints.front());
  for (std::size_t i = 0; i < path.segments(); ++i) {
    const double length = segmentLength(path, i);
    double front = cuts[i].front, back = cuts[i].back;
    // A piece under kMinArcChord joins its neighbour: no split that short.
    if (front < kMinArcChord) front = 0.0;
    if (back < kMinArcChord) back = 0.0;
    if (!path.tool_on[i] || (front == 0.0 && back == 0.0)) {
      appendPiece(out, path, i, 0.0, 1.0, path.tool_on[i]);
      continue;
    }
    if (front + back > length - kMinArcChord) {  // slow all along
      appendPiece(out, path, i, 0.0, 1.0, false);
      if (off_m) *off_m += length;
      continue;
    }
    const double t_front = front / length, t_back = 1.0 - back / length;
    if (front > 0.0) appendPiece(out, path, i, 0.0, t_front, false);
    appendPiece(out, path, i, t_front, back > 0.0 ? t_back : 1.0, true);
    if (back > 0.0) appendPiece(out, path, i, t_back, 1.0, false);
    if (off_m) *off_m += front + back;
  }
  return out;
}

void applyTriggerSpeed(const Problem& problem, double trigger_speed, PlanResult& result) {
  if (!(trigger_speed > 0.0) || !result.hasPath()) return;
  double off_m = 0.0;
  result.path = switchOffWhileSlow(result.path, problem.motion, problem.vehicle, trigger_speed * problem.motion.speed, &off_m);
  result.stats["trigger_off_m"] = off_m;
}

PlanResult planRows(const Problem& problem, double coat_ripple, double& overlap, double trigger_speed,
                    const SweepDirection& sweep, const Budget& budget, const std::function<PlanResult(double)>& plan_at) {
  if (std::string why = evenCoatOverlap(problem.tool, coat_ripple, overlap); !why.empty())
    return PlanResult::failure(PlanStatus::InvalidInput, std::move(why));
  if (std::string why = triggerSpeedCheck(problem, trigger_speed); !why.empty())
    return PlanResult::failure(PlanStatus::InvalidInput, std::move(why));
  PlanResult result = planSweep(problem, sweep, budget, plan_at);
  applyTriggerSpeed(problem, trigger_speed, result);
  return result;
}

}  // namespace coverbench
