// Turns and duration under a time model.
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "coverbench/motion.hpp"

namespace coverbench {
namespace {

// "More than" a threshold: a change within 1e-9 rad of it (an exact 30 degrees computed through
// rounding) does not count, so translating or reversing a path cannot flip the verdict.
constexpr double kAngleTie = 1e-9;
constexpr double kTurnThreshold = M_PI / 180.0 + kAngleTie;  // 1 degree
constexpr double kThirtyDegrees = M_PI / 6.0 + kAngleTie;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// Time to drive a straight run of `length` from standstill to standstill with a trapezoidal
/// (or, when too short to reach v, triangular) speed profile.
double runTime(double length, const MotionLimits& m) {
  if (length <= 0.0) return 0.0;
  const double v = m.speed, a = m.acceleration;
  if (std::isinf(a)) return length / v;  // no ramp
  if (length >= v * v / a) return length / v + v / a;
  return 2.0 * std::sqrt(length / a);
}

/// The speed profile of pieces of (length, speed cap) driven from standstill to standstill,
/// accelerating and braking at a, never faster than a piece's cap (the time-optimal profile: the
/// speed at each junction is the largest both neighbours allow and braking distance permits,
/// found forward then backward; within a piece it rises to min(cap, what the two ends allow) and
/// falls). With no ramp every piece is driven at its cap.
std::vector<SegmentSpeed> profileSpeeds(const std::vector<std::pair<double, double>>& pieces, const MotionLimits& m) {
  const double a = m.acceleration;
  const std::size_t n = pieces.size();
  std::vector<SegmentSpeed> speeds(n);
  if (n == 0) return speeds;
  if (std::isinf(a)) {  // no ramp: every piece at its cap
    for (std::size_t k = 0; k < n; ++k) speeds[k] = {pieces[k].first, pieces[k].second, pieces[k].second, pieces[k].second, a};
    return speeds;
  }
  std::vector<double> u(n + 1, 0.0);  // speed at junction k (before piece k)
  for (std::size_t k = 1; k < n; ++k)
    u[k] = std::fmin(std::fmin(pieces[k - 1].second, pieces[k].second), std::sqrt(u[k - 1] * u[k - 1] + 2.0 * a * pieces[k - 1].first));
  for (std::size_t k = n - 1; k >= 1; --k) u[k] = std::fmin(u[k], std::sqrt(u[k + 1] * u[k + 1] + 2.0 * a * pieces[k].first));
  for (std::size_t k = 0; k < n; ++k) {
    const double len = pieces[k].first, cap = pieces[k].second, v0 = u[k], v1 = u[k + 1];
    const double peak = len > 0.0 ? std::fmin(cap, std::sqrt((2.0 * a * len + v0 * v0 + v1 * v1) / 2.0)) : 0.0;
    speeds[k] = {len, v0, peak, v1, a};
  }
  return speeds;
}

/// The time of each piece under profileSpeeds.
std::vector<double> profileTimes(const std::vector<std::pair<double, double>>& pieces, const MotionLimits& m) {
  std::vector<double> times(pieces.size(), 0.0);
  const std::vector<SegmentSpeed> speeds = profileSpeeds(pieces, m);
  for (std::size_t k = 0; k < pieces.size(); ++k) times[k] = speeds[k].duration();
  return times;
}

double profileTime(const std::vector<std::pair<double, double>>& pieces, const MotionLimits& m) {
  double t = 0.0;
  for (double piece : profileTimes(pieces, m)) t += piece;
  return t;
}

/// What the time model makes of each segment, for the timeline: the run it is driven in (runs go
/// from standstill to standstill), its piece (length, speed cap) and the wait before it.
struct Trace {
  std::vector<std::size_t> run;
  std::vector<std::pair<double, double>> piece;
  std::vector<double> wait_s;
  double final_wait_s = 0.0;
};

Motion analyse(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle, Trace* trace) {
  Motion m;
  double run = 0.0;
  // With arcs (a car's path), a run is pieces of (length, speed cap): sqrt(a R) on an arc of
  // radius R. Paths without arcs keep the single-number run (and their durations to the bit).
  const bool arcs = path.hasArcs();
  std::vector<std::pair<double, double>> pieces;
  std::size_t run_index = 0;
  auto endRun = [&] {
    m.duration_s += arcs ? profileTime(pieces, limits) : runTime(run, limits);
    run = 0.0;
    pieces.clear();
    ++run_index;
  };
  if (trace) {
    trace->run.assign(path.segments(), 0);
    trace->piece.assign(path.segments(), {0.0, limits.speed});
    trace->wait_s.assign(path.segments(), 0.0);
  }
  bool have_heading = false;
  double heading = 0.0;
  const bool lifts = vehicle.liftsTool();
  const bool stop_everywhere = limits.stops == MotionLimits::Stops::Waypoints;
  const double stop_threshold = limits.stop_angle_deg * M_PI / 180.0 + kAngleTie;
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    // A gantry stops to lower its tool before each run of tool-on segments and to lift it after.
    if (lifts && path.tool_on[i] && (i == 0 || !path.tool_on[i - 1])) {
      ++m.lifts;
      m.duration_s += vehicle.lower_s + vehicle.lift_s;
      if (trace) trace->wait_s[i] += vehicle.lower_s;
    }
    if (lifts && trace && !path.tool_on[i] && i > 0 && path.tool_on[i - 1]) trace->wait_s[i] += vehicle.lift_s;
    if (lifts && i > 0 && path.tool_on[i] != path.tool_on[i - 1]) endRun();
    if (trace) trace->run[i] = run_index;
    const Point d = path.waypoints[i + 1] - path.waypoints[i];
    const double len = norm(d);
    if (len == 0.0) continue;  // zero-length segments have no heading
    const double h = std::atan2(d.y, d.x);
    // An arc starts turned back by half its sweep from its chord and ends turned on by as much.
    const double bulge = arcs ? path.bulge[i] : 0.0;
    const double half = bulge == 0.0 ? 0.0 : 2.0 * std::atan(bulge);
    if (have_heading) {
      const double change = std::fabs(std::remainder(h - half - heading, 2.0 * M_PI));
      m.turning_angle += change;
      if (change > kTurnThreshold) ++m.turns;
      if (change > kThirtyDegrees) ++m.turns_30;
      const bool rotate = limits.rotates() && change > kAngleTie;
      if (stop_everywhere || change > stop_threshold || rotate) {
        endRun();
        if (trace) trace->run[i] = run_index;
      }
      if (rotate) {  // in place, standing: θ / ω
        m.duration_s += rotationTime(change, limits);
        if (trace) trace->wait_s[i] += rotationTime(change, limits);
      }
    }
    heading = h + half;
    have_heading = true;
    if (bulge == 0.0) {
      run += len;
      if (arcs) pieces.emplace_back(len, limits.speed);
      if (trace) trace->piece[i] = {len, limits.speed};
    } else {
      const ArcGeometry g = arcGeometry(path.waypoints[i], path.waypoints[i + 1], bulge);
      m.turning_angle += std::fabs(g.sweep);
      pieces.emplace_back(g.radius * std::fabs(g.sweep), std::fmin(limits.speed, std::sqrt(limits.acceleration * g.radius)));
      // (With no ramp, sqrt(inf R) is inf: the arc is driven at v.)
      if (trace) trace->piece[i] = pieces.back();
    }
  }
  endRun();
  if (trace && lifts && !path.tool_on.empty() && path.tool_on.back()) trace->final_wait_s = vehicle.lift_s;
  if (limits.turn_cost_s > 0.0) m.turn_cost_s = static_cast<double>(m.turns) * limits.turn_cost_s;
  return m;
}

}  // namespace

double straightRunTime(double length, const MotionLimits& limits) { return runTime(length, limits); }

std::string MotionLimits::describe() const {
  std::string out = "v " + number(speed) + " m/s, " + (std::isinf(acceleration) ? std::string("no ramp") : "a " + number(acceleration) + " m/s2") + ", " +
                    (stops == Stops::Waypoints ? std::string("stops at every waypoint")
                                               : "stops at turns over " + number(stop_angle_deg) + " degrees");
  if (turn_cost_s > 0.0) out += ", " + number(turn_cost_s) + " s per turn (turn_cost_s)";
  if (rotates()) out += ", rotates in place at " + number(rotation_speed) + " rad/s";
  return out;
}

void MotionLimits::check() const {
  if (!(speed >= kMinMotion && speed <= kMaxMotion)) throw std::invalid_argument("speed: must be in [1e-06, 1000] m/s");
  if (!((acceleration >= kMinMotion && acceleration <= kMaxMotion) || acceleration == HUGE_VAL))
    throw std::invalid_argument("acceleration: must be in [1e-06, 1000] m/s2, or inf (no ramp)");
  if (!(stop_angle_deg > 0.0) || !(stop_angle_deg < 180.0)) throw std::invalid_argument("stop_angle: must be in (0, 180) degrees");
  if (!(turn_cost_s >= 0.0) || !std::isfinite(turn_cost_s) || turn_cost_s > 3600.0)
    throw std::invalid_argument("turn_cost_s: must be in [0, 3600] s");
  if (!(rotation_speed >= 0.0) || !std::isfinite(rotation_speed) || rotation_speed > 100.0)
    throw std::invalid_argument("rotation_speed: must be in [0, 100] rad/s (0: no rotation in place)");
}

Motion motion(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle) {
  return analyse(path, limits, vehicle, nullptr);
}

double SegmentSpeed::duration() const {
  if (length <= 0.0) return 0.0;
  if (std::isinf(acceleration)) return length / peak;
  const double a = acceleration;
  const double accel = (peak * peak - v0 * v0) / (2.0 * a), brake = (peak * peak - v1 * v1) / (2.0 * a);
  return (peak - v0) / a + (peak - v1) / a + std::fmax(0.0, length - accel - brake) / peak;
}

double SegmentSpeed::timeAt(double s) const {
  if (!(s > 0.0) || length <= 0.0) return 0.0;
  if (s >= length) return duration();
  if (std::isinf(acceleration)) return s / peak;
  const double a = acceleration;
  const double accel = (peak * peak - v0 * v0) / (2.0 * a), brake = (peak * peak - v1 * v1) / (2.0 * a);
  if (s <= accel) return (std::sqrt(v0 * v0 + 2.0 * a * s) - v0) / a;  // accelerating
  const double cruise_end = std::fmax(accel, length - brake);
  if (s <= cruise_end) return (peak - v0) / a + (s - accel) / peak;  // at the peak
  return duration() - (std::sqrt(v1 * v1 + 2.0 * a * (length - s)) - v1) / a;  // braking: the time left
}

double SegmentSpeed::speedAt(double s) const {
  if (length <= 0.0) return 0.0;
  s = std::fmin(std::fmax(s, 0.0), length);
  if (std::isinf(acceleration)) return peak;
  const double a = acceleration;
  return std::fmin(peak, std::fmin(std::sqrt(v0 * v0 + 2.0 * a * s), std::sqrt(v1 * v1 + 2.0 * a * (length - s))));
}

std::vector<SegmentSpeed> segmentSpeeds(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle) {
  Trace trace;
  analyse(path, limits, vehicle, &trace);
  std::vector<SegmentSpeed> out(path.segments());
  for (std::size_t first = 0; first < path.segments();) {  // each run's pieces, profiled together
    std::size_t last = first;
    while (last < path.segments() && trace.run[last] == trace.run[first]) ++last;
    const std::vector<std::pair<double, double>> pieces(trace.piece.begin() + static_cast<std::ptrdiff_t>(first),
                                                        trace.piece.begin() + static_cast<std::ptrdiff_t>(last));
    const std::vector<SegmentSpeed> speeds = profileSpeeds(pieces, limits);
    std::copy(speeds.begin(), speeds.end(), out.begin() + static_cast<std::ptrdiff_t>(first));
    first = last;
  }
  return out;
}

Timeline timeline(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle) {
  Trace trace;
  analyse(path, limits, vehicle, &trace);
  Timeline t;
  t.wait_s = trace.wait_s;
  t.arrive_s.assign(path.waypoints.size(), 0.0);
  std::vector<double> segment_s(path.segments(), 0.0);
  for (std::size_t first = 0; first < path.segments();) {  // each run's pieces, profiled together
    std::size_t last = first;
    while (last < path.segments() && trace.run[last] == trace.run[first]) ++last;
    const std::vector<std::pair<double, double>> pieces(trace.piece.begin() + static_cast<std::ptrdiff_t>(first),
                                                        trace.piece.begin() + static_cast<std::ptrdiff_t>(last));
    const std::vector<double> times = profileTimes(pieces, limits);
    std::copy(times.begin(), times.end(), segment_s.begin() + static_cast<std::ptrdiff_t>(first));
    first = last;
  }
  for (std::size_t i = 0; i < path.segments(); ++i) t.arrive_s[i + 1] = t.arrive_s[i] + t.wait_s[i] + segment_s[i];
  t.end_s = (path.waypoints.empty() ? 0.0 : t.arrive_s.back()) + trace.final_wait_s;
  return t;
}

}  // namespace coverbench
