// A planner's path made drivable by a car: fillets, Dubins / Reeds-Shepp turns, skips
// (docs/vehicles.md). Every piece is checked against the free region before it is used.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include "coverbench/car.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

struct Segment {
  Point a, b;
  bool tool = false;
  double length = 0.0;
  Point dir;  ///< unit
  double heading = 0.0;
};

/// The turn from heading `from` to heading `to` (wrapAngle).
double angleBetween(double from, double to) { return wrapAngle(to - from); }

/// A curve that turns more than a quarter circle beyond what its two poses differ by is a loop (a
/// Dubins car circling round to line up with a pose just beside it): painted, it scribbles
/// circles over the wall; such a curve is not taken.
bool loops(const Path& curve, Pose from, Pose to) {
  double turning = 0.0;
  for (std::size_t k = 0; k < curve.segments(); ++k) turning += std::fabs(4.0 * std::atan(curve.bulgeOf(k)));
  return turning > std::fabs(angleBetween(from.heading, to.heading)) + M_PI / 2.0 + 1e-9;
}

/// Where a turn may start and end, in turn radii back before and on after a corner: fewest first.
const std::vector<std::pair<double, double>>& turnShifts() {
  static const std::vector<std::pair<double, double>> shifts = [] {
    const double steps[] = {0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0};
    std::vector<std::pair<double, double>> out;
    for (double back : steps)
      for (double on : steps) out.emplace_back(back, on);
    std::stable_sort(out.begin(), out.end(), [](const auto& u, const auto& v) {
      return u.first + u.second < v.first + v.second || (u.first + u.second == v.first + v.second && u.first < v.first);
    });
    return out;
  }();
  return shifts;
}
/// Where a skip may enter a later segment, in turn radii from its start, nearest first: on the
/// corner's own next segment and the next few (further on, only the start is tried).
constexpr double kSkipInto[] = {0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
constexpr std::size_t kSkipIntoSegments = 8;
/// The sharpest turn a car that reverses rounds; sharper corners it drives into and backs out of.
constexpr double kCornerManoeuvre = M_PI / 3.0;
/// A skip that leaves more painting than this (m) is searched for a shorter way first: at most
/// kSkipSearches routes of kSkipSearchExpansions poses each, and kSmoothingSearchBudget poses over
/// the whole path (about 2 us each).
constexpr double kSearchSkip = 1.0;
constexpr std::size_t kSkipSearches = 2, kSkipSearchExpansions = 600, kSmoothingSearchBudget = 6000;

/// The corner the smoothing is at: the vertex between segments s and t, at arc length `at`,
/// turning by theta.
struct Corner {
  std::size_t index;  // of segment t
  double at;
  const Segment& s;
  const Segment& t;
  double theta;
};

/// A skip (step 3 of smoothForCar): tool off from arc length `from` to `to` on segment j, along
/// `curve`.
struct Skip {
  double from, to;
  std::size_t j;
  Path curve;
  bool searched = false;
};

/// smoothForCar's work on one path: the path by arc length, where the car is on it, and what it
/// drove (`out`). Each corner is taken by the first of its steps that works (run()).
class CarSmoother {
 public:
  CarSmoother(const Workspace& ws, CarSmoothing& out)
      : ws_(ws), car_(ws.vehicle()), rho_(car_.turn_radius * (1.0 + kCarRadiusSlack)), out_(out) {}

  /// The path's segments by arc length (segment k starts at along_[k]), those of no length left
  /// out, and a forward-only car's spurs dropped. Whether any is left.
  bool load(const Path& in) {
    for (std::size_t i = 0; i < in.segments(); ++i) {
      Segment sg{in.waypoints[i], in.waypoints[i + 1], in.tool_on[i]};
      sg.length = distance(sg.a, sg.b);
      if (sg.length == 0.0) continue;
      sg.dir = (sg.b - sg.a) * (1.0 / sg.length);
      sg.heading = std::atan2(sg.dir.y, sg.dir.x);
      segs_.push_back(sg);
      along_.push_back(total_);
      total_ += sg.length;
    }
    if (!car_.reverse) dropSpurs();
    m_ = segs_.size();
    return m_ > 0;
  }

  /// Drives the path corner by corner: 0. a reversing car's manoeuvre into a sharp corner, 1. a
  /// fillet, 2. a curve past the corner (2b. after backing out of it), 3. a skip to a later segment,
  /// 4. a skip from where the car was some steps ago; else the path stops at the corner.
  void run() {
    while (true) {
      if (checkpoints_.empty() || checkpoints_.back().x < x_) checkpoints_.push_back({out_.path.waypoints.size(), x_});
      // A vertex whose segments' headings differ by less than the car's rules notice is no corner:
      // a fillet of it (a few picometres) would be a chord whose heading is rounding noise.
      while (corner_ < m_ && (along_[corner_] <= x_ ||
                              std::fabs(angleBetween(segs_[corner_ - 1].heading, segs_[corner_].heading)) <= kCarHeadingTolerance / 4.0))
        ++corner_;
      if (corner_ >= m_) {
        driveToEnd();
        break;
      }
      const Segment &s = segs_[corner_ - 1], &t = segs_[corner_];
      const Corner c{corner_, along_[corner_], s, t, angleBetween(s.heading, t.heading)};
      if (car_.reverse && cornerManoeuvre(c)) continue;
      if (fillet(c) || turnPast(c)) continue;
      if (car_.reverse && backOutAndTurn(c)) continue;
      if (skipAhead(c) || backOff(c)) continue;
      stop(c);
      break;
    }
  }

 private:
  // --- The path by arc length.

  /// A forward-only car cannot drive a spur (out and straight back the same way, as the spiral's
  /// corners have): its painting is left out and the path closes over it.
  void dropSpurs() {
    std::vector<Segment> kept;
    for (const Segment& sg : segs_) {
      if (!kept.empty() && sg.a == kept.back().b && sg.b == kept.back().a) {
        if (kept.back().tool) out_.cut_m += kept.back().length;
        if (sg.tool) out_.cut_m += sg.length;
        out_.skipped += 2;
        kept.pop_back();
        continue;
      }
      kept.push_back(sg);
    }
    segs_ = std::move(kept);
    along_.clear();
    total_ = 0.0;
    for (const Segment& sg : segs_) {
      along_.push_back(total_);
      total_ += sg.length;
    }
  }
  /// The segment holding arc length x (the later one at a vertex).
  std::size_t segmentAt(double x) const {
    const auto it = std::upper_bound(along_.begin(), along_.end(), x);
    return static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - along_.begin()) - 1));
  }
  /// The pose at arc length x: heading as the car arrives there (at a vertex: the segment before
  /// it) or as it leaves (the segment after it).
  Pose poseAt(double x, bool arriving) const {
    std::size_t k = segmentAt(x);
    if (arriving && k > 0 && x <= along_[k]) --k;
    const double into = std::clamp(x - along_[k], 0.0, segs_[k].length);
    return Pose{into >= segs_[k].length ? segs_[k].b : segs_[k].a + segs_[k].dir * into, segs_[k].heading};
  }
  /// Painted all along [x0, x1].
  bool paintedThrough(double x0, double x1) const {
    for (std::size_t k = segmentAt(x0); k < m_ && along_[k] < x1; ++k)
      if (!segs_[k].tool) return false;
    return true;
  }
  /// The painted length within [x0, x1] (what a turn leaves undriven).
  double paintedLength(double x0, double x1) const {
    double sum = 0.0;
    for (std::size_t k = segmentAt(x0); k < m_ && along_[k] < x1; ++k)
      if (segs_[k].tool) sum += std::max(0.0, std::min(x1, along_[k] + segs_[k].length) - std::max(x0, along_[k]));
    return sum;
  }
  /// The painted pieces of [x0, x1] (what a skip or a stop leaves undriven), for a planner to
  /// cover otherwise.
  void recordUndriven(double x0, double x1) {
    for (std::size_t k = segmentAt(x0); k < m_ && along_[k] < x1; ++k) {
      const double lo = std::max(x0, along_[k]), hi = std::min(x1, along_[k] + segs_[k].length);
      if (segs_[k].tool && hi - lo > 1e-9)
        out_.undriven.emplace_back(segs_[k].a + segs_[k].dir * (lo - along_[k]), segs_[k].a + segs_[k].dir * (hi - along_[k]));
    }
  }

  // --- Driving.

  /// Appends `piece` (which starts where the output ends) to the output.
  void append(const Path& piece) {
    for (std::size_t k = 0; k < piece.segments(); ++k) out_.path.arcTo(piece.waypoints[k + 1], piece.bulgeOf(k), piece.tool_on[k]);
  }
  /// Drives the path straight from x to the point at y (no corner between them), tool as the segment.
  void driveTo(double y) {
    const std::size_t k = segmentAt(y);
    const Point target = poseAt(y, true).at;
    // Where the car already is, but for rounding: a segment of 1e-14 m has no heading to keep.
    if (distance(out_.path.waypoints.back(), target) <= 1e-9) return;
    out_.path.moveTo(target, segs_[k > 0 && y <= along_[k] ? k - 1 : k].tool);
  }
  /// The pose a curve starts from after driveTo(y): where the car already is when that is within
  /// rounding of y (driveTo then stays; a curve from the rounded point would start off its end,
  /// and its first piece, when tiny, in a direction that means nothing).
  Pose startPose(double y) const {
    Pose p = poseAt(y, true);
    if (distance(out_.path.waypoints.back(), p.at) <= 1e-9) p.at = out_.path.waypoints.back();
    return p;
  }
  /// Drives `curve` (from where the output ends), which leaves the path's painting `cut` m
  /// undriven and `skipped` segments out, to arc length `to`.
  void take(const Path& curve, double to, double cut, std::size_t skipped) {
    append(curve);
    ++out_.turns;
    out_.cusps += cusps(curve);
    out_.cut_m += cut;
    out_.skipped += skipped;
    x_ = to;
  }
  /// A car that reverses drives into the corner (painting it), backs straight out to `from` over
  /// what it just painted, and takes `curve` from there (steps 0 and 2b).
  void backOutAndTake(const Corner& c, Point from, const Path& curve, double to, double cut, std::size_t skipped) {
    driveTo(c.at);
    out_.path.moveTo(from, false);
    take(curve, to, cut, skipped);
  }
  /// No corner left: drive to the end, from where the car is (a turn may end there already: a
  /// segment of no length has no heading to keep).
  void driveToEnd() {
    for (std::size_t k = segmentAt(x_); k < m_; ++k)
      if (distance(out_.path.waypoints.back(), segs_[k].b) > 1e-9) out_.path.moveTo(segs_[k].b, segs_[k].tool);
  }

  // --- The steps at a corner; each returns whether it took the corner.

  /// 0. A car that reverses paints a sharp corner whole: it drives into it, backs out along the
  ///    segment it came by, and comes back into the corner along the next one (reversing), then
  ///    drives on from it. A fillet or a curve would leave the corner's tip unpainted: on F's
  ///    edge (rho + r)^2 (1 - pi / 4) at a right angle, far more than the tool's own corner
  ///    loss; on the rings inside, the slivers between their fillets, which no other pass
  ///    paints (on a 6 m x 4 m rectangle 0.9917 of R covered with fillets, 0.9995 without).
  bool cornerManoeuvre(const Corner& c) {
    const double theta = c.theta;
    if (!(std::fabs(theta) >= kCornerManoeuvre && std::fabs(theta) < M_PI - 1e-9 && c.s.tool && c.t.tool)) return false;
    // Backing out by the fillet's tangent length, the fillet, and straight back into the
    // corner along the next segment: every piece on the path's segments or the fillet.
    const double d = rho_ * std::tan(std::fabs(theta) / 2.0);
    if (d <= c.at - along_[c.index - 1] && d <= c.t.length) {
      const Point p = c.s.b - c.s.dir * d, q = c.t.a + c.t.dir * d;
      const double bulge = std::tan(theta / 4.0);
      if (arcFree(ws_, p, q, bulge)) {
        driveTo(c.at);
        out_.path.moveTo(p, false);
        out_.path.arcTo(q, bulge, false);
        out_.path.moveTo(c.t.a, false);
        ++out_.turns;
        out_.cusps += 2;
        x_ = c.at;
        return true;
      }
    }
    const Pose corner_pose{c.t.a, c.t.heading};
    for (double back : {0.5, 1.0, 1.5, 2.0, 3.0}) {
      const double from = c.at - back * rho_;
      if (from < along_[c.index - 1]) break;
      const Pose p = poseAt(from, true);
      const Path curve = carCurve(p, corner_pose, rho_, true, false);
      if (curve.waypoints.empty() || !pathFree(ws_, curve)) continue;
      backOutAndTake(c, p.at, curve, c.at, 0.0, 0);
      return true;
    }
    return false;
  }

  /// 1. A fillet of the turn radius, tangent to both segments, where both are long enough.
  bool fillet(const Corner& c) {
    const double theta = c.theta;
    const double d = std::fabs(theta) < M_PI - 1e-9 ? rho_ * std::tan(std::fabs(theta) / 2.0) : INFINITY;
    if (!(d <= c.at - x_ && d <= c.at - along_[c.index - 1] && d <= c.t.length)) return false;
    const Point p = c.s.b - c.s.dir * d, q = c.t.a + c.t.dir * d;
    const double bulge = std::tan(theta / 4.0);
    if (!arcFree(ws_, p, q, bulge)) return false;
    driveTo(c.at - d);
    out_.path.arcTo(q, bulge, c.s.tool && c.t.tool);
    ++out_.fillets;
    out_.cut_m += paintedLength(c.at - d, c.at + d);
    x_ = c.at + d;
    return true;
  }

  /// 2. A Dubins / Reeds-Shepp curve from a point moved back before the corner to a point moved
  ///    on after it (in turn radii; fewest first), past any corners in between.
  bool turnPast(const Corner& c) {
    for (const auto& [back, on] : turnShifts()) {
      const double from = c.at - back * rho_, to = c.at + on * rho_;
      if (from < x_ || to > total_) continue;
      const Pose p = startPose(from), q = poseAt(to, false);
      const Path curve = carCurve(p, q, rho_, car_.reverse, paintedThrough(from, to));
      if (curve.waypoints.empty() || loops(curve, p, q) || !pathFree(ws_, curve)) continue;
      driveTo(from);
      const std::size_t s0 = segmentAt(from), s1 = segmentAt(to);
      take(curve, to, paintedLength(from, to), s1 - s0 > 1 ? s1 - s0 - 1 : 0);
      return true;
    }
    return false;
  }

  /// 2b. A car that reverses drives into the corner (painting it), backs straight out along the
  ///     segment it came by, and turns from there: the shortest curve from the corner itself
  ///     often swings out of F where a short reversal first leaves it room.
  bool backOutAndTurn(const Corner& c) {
    for (const auto& [back, on] : turnShifts()) {
      const double from = c.at - back * rho_, to = c.at + on * rho_;
      if (back == 0.0 || from < along_[c.index - 1] || to > total_) continue;
      const Pose p = poseAt(from, true), q = poseAt(to, false);
      const Path curve = carCurve(p, q, rho_, true, paintedThrough(c.at, to));
      if (curve.waypoints.empty() || loops(curve, p, q) || !pathFree(ws_, curve)) continue;
      const std::size_t s0 = segmentAt(c.at), s1 = segmentAt(to);
      backOutAndTake(c, p.at, curve, to, paintedLength(c.at, to), s1 - s0 > 1 ? s1 - s0 - 1 : 0);
      return true;
    }
    return false;
  }

  /// 3. Skip, tool off, to a later segment (nearestSkip; else, or where that leaves too much
  ///    painting, searchedSkip).
  bool skipAhead(const Corner& c) {
    std::optional<Skip> skip = nearestSkip(c);
    searchedSkip(c, skip);
    if (!skip) return false;
    driveTo(skip->from);
    take(skip->curve, skip->to, paintedLength(skip->from, skip->to), skip->j - c.index);  // segment j is entered, not skipped
    recordUndriven(skip->from, skip->to);
    out_.searched += skip->searched;
    return true;
  }
  /// From the corner, or a point further back (a forward-only car facing a wall needs room to
  /// turn), to the nearest point along the path a free curve reaches on a later segment: its
  /// start, or up to kSkipInto turn radii into it (a long segment whose start lies in a corner the
  /// car cannot turn into is entered a little further on, not skipped whole). Ties go to the point
  /// moved back least.
  std::optional<Skip> nearestSkip(const Corner& c) const {
    std::optional<Skip> skip;
    for (double back : {0.0, 1.0, 2.0, 4.0, 8.0}) {
      const double from = c.at - back * rho_;
      if (from < x_) continue;
      const Pose p = startPose(from);
      bool found = false;
      for (std::size_t j = c.index; j < m_ && !found && !(skip && along_[j] >= skip->to); ++j)
        for (double into : kSkipInto) {
          const double to = along_[j] + into * rho_;
          if (j == c.index && into == 0.0) continue;
          if ((into > 0.0 && (into * rho_ >= segs_[j].length - 1e-9 || j >= c.index + kSkipIntoSegments)) || (skip && to >= skip->to)) break;
          Path curve = carCurve(p, {segs_[j].a + segs_[j].dir * (into * rho_), segs_[j].heading}, rho_, car_.reverse, false);
          if (curve.waypoints.empty() || !pathFree(ws_, curve)) continue;
          skip = Skip{from, to, j, std::move(curve)};
          found = true;
          break;
        }
    }
    return skip;
  }
  /// 3b. No curve reaches the path again within kSearchSkip of painting (a corner of a stair,
  ///     from which every curve to what follows crosses the steps): a route searched over the
  ///     car's own motions (searchCarRoute) to the next long segments, a turn radius into each,
  ///     replaces `skip` when it gets nearer.
  void searchedSkip(const Corner& c, std::optional<Skip>& skip) {
    const double search_from = std::max(x_, c.at - rho_);
    // Where the car is, as it heads (not as the path arrives there: x may be a vertex the car
    // reached along the next segment), or the point ahead it drives to first.
    const Pose search_start = search_from <= x_ && out_.path.segments() > 0 ? endPose(out_.path) : startPose(search_from);
    if (!((!skip || paintedLength(skip->from, skip->to) > kSearchSkip) && searched_ < kSmoothingSearchBudget)) return;
    std::size_t tries = 0;
    for (std::size_t j = c.index; j < m_ && tries < kSkipSearches && searched_ < kSmoothingSearchBudget; ++j) {
      const double to = along_[j] + rho_;
      if (skip && to >= skip->to) break;
      if (segs_[j].length < 2.0 * rho_) continue;
      ++tries;
      const Pose target{segs_[j].a + segs_[j].dir * rho_, segs_[j].heading};
      Path route = searchCarRoute(ws_, search_start, target, rho_, car_.reverse,
                                  std::min(kSkipSearchExpansions, kSmoothingSearchBudget - searched_), &searched_);
      if (route.segments() == 0) continue;
      skip = Skip{search_from, to, j, std::move(route), true};
      break;
    }
  }

  /// 4. Stuck (a forward-only car that drove into a passage too narrow to turn in): go back to
  ///    where it was some steps ago, drop what it drove since, and skip from there to a segment
  ///    beyond this corner.
  bool backOff(const Corner& c) {
    bool done = false;
    for (std::size_t steps = 1; steps <= checkpoints_.size() && !done; steps *= 2) {
      const Checkpoint& back = checkpoints_[checkpoints_.size() - steps];
      const Pose p = poseAt(back.x, false);
      for (std::size_t j = c.index + 1; j < m_ && !done; ++j) {
        const Path curve = carCurve(p, {segs_[j].a, segs_[j].heading}, rho_, car_.reverse, false);
        if (curve.waypoints.empty() || !pathFree(ws_, curve)) continue;
        out_.path.waypoints.resize(back.waypoints);
        out_.path.tool_on.resize(back.waypoints - 1);
        if (!out_.path.bulge.empty()) out_.path.bulge.resize(back.waypoints - 1);
        take(curve, along_[j], paintedLength(back.x, along_[j]), j - segmentAt(back.x));  // what it painted since is dropped too
        recordUndriven(back.x, along_[j]);
        checkpoints_.resize(checkpoints_.size() - steps);
        done = true;
      }
    }
    return done;
  }

  /// Nothing took the corner: the path ends there (`stopped`).
  void stop(const Corner& c) {
    driveTo(c.at);
    out_.stopped = true;
    out_.cut_m += paintedLength(c.at, total_);
    recordUndriven(c.at, total_);
    out_.skipped += m_ - c.index;
  }

  /// Where the car was after each step (the output's waypoints then, its arc length), to go back to.
  struct Checkpoint {
    std::size_t waypoints;
    double x;
  };

  const Workspace& ws_;
  const VehicleModel& car_;
  const double rho_;
  CarSmoothing& out_;
  std::vector<Segment> segs_;
  std::vector<double> along_;
  double total_ = 0.0;                  // the path's length
  std::size_t m_ = 0;                   // segments
  std::vector<Checkpoint> checkpoints_;
  double x_ = 0.0;                      // the car is at arc length x, on the path, heading along it
  std::size_t searched_ = 0;            // poses searched (searchCarRoute) over the whole path
  std::size_t corner_ = 1;              // the next vertex that may be a corner
};

}  // namespace

CarSmoothing smoothForCar(const Workspace& ws, const Path& in) {
  CarSmoothing out;
  if (in.waypoints.empty()) return out;
  out.path.moveTo(in.waypoints.front(), false);
  CarSmoother smoother(ws, out);
  if (!smoother.load(in)) return out;
  smoother.run();
  // The car's rules, checked on what was built (the judges check again): a slip here is a bug,
  // and the plan fails with it rather than hand over a path the car cannot drive.
  checkDrivable(out.path, ws.vehicle(), "car smoothing");
  char buf[200];
  if (out.stopped || out.skipped) {
    std::snprintf(buf, sizeof buf, "the car skips %zu segments%s", out.skipped,
                  out.stopped ? " and stops where no curve it can drive reaches further" : "");
    out.reason = buf;
  }
  return out;
}

}  // namespace coverbench
