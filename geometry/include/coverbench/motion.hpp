#pragma once
/// Turns and the time to drive a path under a time model (docs/metrics.md#time-models). In the
/// geometry layer because a time model is a definition, like the free region's: the metrics
/// engine reports it, and planners that plan for the clock minimise it.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/path.hpp"

namespace coverbench {

/// The time model of duration_s: a trapezoidal speed profile (accelerate at a up to v, brake at a)
/// that comes to a stop at every waypoint, or only at heading changes over `stop_angle_deg`. On
/// an arc of radius R the speed is at most sqrt(a R) (the lateral acceleration a) in either
/// model. A fixed cost per turn is reported apart, as turn_cost_s. With a rotation speed ω the
/// clock turns: the vehicle stops at every heading change θ at a waypoint and rotates in place for
/// θ / ω (a robot with a differential drive; Bormann et al., ICRA 2018 time their robot so, with
/// v 0.3 m/s, ω 0.52 rad/s and no ramp). An acceleration of infinity is no ramp: every run takes
/// its length / v, and arcs are driven at v.
/// The bounds every reader puts on a speed (m/s) and an acceleration (m/s^2, or infinity): below a
/// micrometre a second, a duration or a constant gun's coat may pass what a double holds.
inline constexpr double kMinMotion = 1e-6, kMaxMotion = 1000.0;

struct MotionLimits {
  enum class Stops { Turns, Waypoints };
  double speed = 0.3;         ///< v, m/s
  double acceleration = 0.5;  ///< a, m/s^2; infinity: no ramp
  Stops stops = Stops::Turns;
  double stop_angle_deg = 30.0;  ///< with Stops::Turns: stop where the heading changes by more
  double turn_cost_s = 0.0;      ///< seconds per turn (heading change over 1 degree); 0: not reported
  double rotation_speed = 0.0;   ///< ω, rad/s: rotations in place at every heading change; 0: none

  bool isDefault() const {
    return speed == 0.3 && acceleration == 0.5 && stops == Stops::Turns && stop_angle_deg == 30.0 && turn_cost_s == 0.0 &&
           rotation_speed == 0.0;
  }
  bool rotates() const { return rotation_speed > 0.0; }
  /// "v 0.3 m/s, a 0.5 m/s2, stops at turns over 30 degrees" (", 2 s per turn" and ", rotates in
  /// place at 0.52 rad/s" when set; "no ramp" for an infinite acceleration).
  std::string describe() const;
  /// Throws std::invalid_argument naming the first value out of range (field names as in configs).
  void check() const;
};

/// Turns and the time to drive the path.
struct Motion {
  std::size_t turns = 0;     ///< heading changes > 1 degree at interior waypoints (arcs turn smoothly: not counted)
  std::size_t turns_30 = 0;  ///< heading changes > 30 degrees
  double turning_angle = 0.0;  ///< sum of |heading change|, radians (at waypoints and along arcs)
  /// The time model's time (MotionLimits); a reversing car's cusp is always a stop. For a gantry
  /// also a stop at every change of tool state, plus lower_s + lift_s for every run of tool-on
  /// segments.
  double duration_s = 0.0;
  std::size_t lifts = 0;  ///< runs of tool-on segments of a gantry (each lowered, then lifted); 0 otherwise
  /// turns * MotionLimits::turn_cost_s, when that cost is set.
  std::optional<double> turn_cost_s;
};

Motion motion(const Path& path, const MotionLimits& limits = {}, const VehicleModel& vehicle = {});

/// What a turn by `angle` radians at a waypoint adds to the clock besides its stop: a rotation in
/// place, angle / ω, when the time model rotates; else 0 (for planners' estimates of the clock).
inline double rotationTime(double angle, const MotionLimits& limits) {
  return limits.rotates() ? angle / limits.rotation_speed : 0.0;
}

/// When the time model has the tool where: the schedule a playback follows. Every run (standstill
/// to standstill) is profiled as pieces, one per segment, so the time of a run of straight
/// segments agrees with duration_s to rounding, not to the bit.
struct Timeline {
  std::vector<double> arrive_s;  ///< per waypoint: when the tool reaches it (the first: 0)
  std::vector<double> wait_s;    ///< per segment: the wait at its start (a gantry lowering or lifting its tool)
  double end_s = 0.0;            ///< when the path is done (after a gantry's last lift): duration_s
};
Timeline timeline(const Path& path, const MotionLimits& limits = {}, const VehicleModel& vehicle = {});

/// How the time model drives one segment (its piece of a run): from v0 it accelerates at a up to
/// `peak`, keeps it, and brakes at a to v1 at the segment's end (with no ramp, a infinite: `peak`
/// throughout). Distances s are measured along the segment from its start (an arc's arc length).
/// The same profile timeline() and duration_s follow (one time model, not a second one).
struct SegmentSpeed {
  double length = 0.0;  ///< m
  double v0 = 0.0, peak = 0.0, v1 = 0.0;  ///< m/s: at the start, the most, at the end
  double acceleration = 0.0;  ///< a, m/s^2 (infinity: no ramp)
  double duration() const;  ///< s, the time on the segment
  double timeAt(double s) const;   ///< s: when the tool is s metres along (0 before, duration() after)
  double speedAt(double s) const;  ///< m/s at s metres along
};
/// Per segment, how the time model drives it (waits and rotations in place are not in it: see
/// Timeline::wait_s). A zero-length segment has length 0 and takes no time.
std::vector<SegmentSpeed> segmentSpeeds(const Path& path, const MotionLimits& limits = {}, const VehicleModel& vehicle = {});

/// The time to drive a straight run of `length` from standstill to standstill: length / v + v / a,
/// or 2 sqrt(length / a) when length < v^2 / a.
double straightRunTime(double length, const MotionLimits& limits);

}  // namespace coverbench
