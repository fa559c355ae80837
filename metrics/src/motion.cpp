// Turns and duration.
#include <cmath>

#include "coverbench/metrics.hpp"

namespace coverbench {
namespace {

// "More than" a threshold: a change within 1e-9 rad of it (an exact 30 degrees computed through
// rounding) does not count, so translating or reversing a path cannot flip the verdict.
constexpr double kAngleTie = 1e-9;
constexpr double kTurnThreshold = M_PI / 180.0 + kAngleTie;  // 1 degree
constexpr double kStopThreshold = M_PI / 6.0 + kAngleTie;    // 30 degrees

/// Time to drive a straight run of `length` from standstill to standstill with a trapezoidal
/// (or, when too short to reach v, triangular) speed profile.
double runTime(double length, const MotionLimits& m) {
  if (length <= 0.0) return 0.0;
  const double v = m.speed, a = m.acceleration;
  if (length >= v * v / a) return length / v + v / a;
  return 2.0 * std::sqrt(length / a);
}

}  // namespace

Motion motion(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle) {
  Motion m;
  double run = 0.0;
  bool have_heading = false;
  double heading = 0.0;
  const bool lifts = vehicle.liftsTool();
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    // A gantry stops to lower its tool before each run of tool-on segments and to lift it after.
    if (lifts && path.tool_on[i] && (i == 0 || !path.tool_on[i - 1])) {
      ++m.lifts;
      m.duration_s += vehicle.lower_s + vehicle.lift_s;
    }
    if (lifts && i > 0 && path.tool_on[i] != path.tool_on[i - 1]) {
      m.duration_s += runTime(run, limits);
      run = 0.0;
    }
    const Point d = path.waypoints[i + 1] - path.waypoints[i];
    const double len = norm(d);
    if (len == 0.0) continue;  // zero-length segments have no heading
    const double h = std::atan2(d.y, d.x);
    if (have_heading) {
      const double change = std::fabs(std::remainder(h - heading, 2.0 * M_PI));
      m.turning_angle += change;
      if (change > kTurnThreshold) ++m.turns;
      if (change > kStopThreshold) {
        ++m.turns_30;
        m.duration_s += runTime(run, limits);
        run = 0.0;
      }
    }
    heading = h;
    have_heading = true;
    run += len;
  }
  m.duration_s += runTime(run, limits);
  return m;
}

}  // namespace coverbench
