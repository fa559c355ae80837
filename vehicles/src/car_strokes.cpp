// Strokes and painting transits (car_sweep_parts.hpp, docs/vehicles.md): what the car's sweep
// adds after its fill rounds, through what the path leaves unpainted.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>

#include "car_paint_grid.hpp"
#include "car_sweep_parts.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::vehicle_detail {
namespace {

/// The poses a path passes through, by cells `cell` wide and 15-degree headings (poseKey): a car
/// that comes back to one of them has driven a loop (it can go on forever).
class PathPoses {
 public:
  explicit PathPoses(double cell) : cell_(cell) {}
  /// Adds the poses along the path's segments from `first` on.
  void add(const Path& path, std::size_t first) {
    forEachChord(path, 0.1 * cell_, first, false, [&](Point p, Point q) {
      const double len = distance(p, q);
      if (len <= 0.0) return;
      const double heading = std::atan2(q.y - p.y, q.x - p.x);
      const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * cell_))));
      for (int i = 0; i < n; ++i) {
        const Pose at{p + (q - p) * (static_cast<double>(i) / n), heading};
        poses_.emplace(key(at), at);
      }
    });
  }
  /// A pose the path drove through in p's cell and heading, if any.
  const Pose* near(Pose p) const {
    const auto it = poses_.find(key(p));
    return it == poses_.end() ? nullptr : &it->second;
  }

 private:
  std::int64_t key(Pose p) const { return poseKey(p, cell_, 24); }
  double cell_;
  std::unordered_map<std::int64_t, Pose> poses_;
};

/// The strokes of one sweep (strokes(), below, says what they are): the path as it grows, the
/// poses it drove, and the search's budget.
class Strokes {
 public:
  Strokes(Workspace& ws, CarSweep& out, PaintGrid& grid, double spacing, double rho, const Budget& budget)
      : ws_(ws), out_(out), grid_(grid), spacing_(spacing), rho_(rho), budget_(budget), step_(spacing / 2.0),
        path_(out.ended_in_dead_end ? upTo(out.path, out.dead_end_from) : out.path), driven_(rho / 4.0) {
    if (out.ended_in_dead_end) {
      const std::size_t n = out.path.waypoints.size();
      const Point a = out.path.waypoints[n - 2], b = out.path.waypoints[n - 1];
      row_from_ = Pose{a, std::atan2(b.y - a.y, b.x - a.x)};
      grid.paint(path_);
    }
    driven_.add(path_, 0);
  }

  /// Strokes while they paint more, then the dead-end row again or a last stroke that may end in
  /// a dead end; all of it kept when worth the path it adds (`painted_before`: what out.path paints).
  void run(double painted_before) {
    for (; count_ < kStrokes && poses_ < kStrokeBudget && !expired(); ++count_) {
      Path route = findStroke();
      if (!take(route)) break;
    }
    const std::size_t before_end = path_.waypoints.size();
    if (row_from_ && !expired()) takeDeadEndRowAgain();
    if (!row_again_ && !expired()) takeLastStroke();
    if (!worthIt(grid_.painted() - painted_before, pathLength(path_) - pathLength(out_.path), spacing_)) {
      grid_.paint(out_.path);
      if (timed_out_) out_.rounds_timed_out = true;
      return;
    }
    keep(before_end);
  }

 private:
  /// Whether the car can go on from `at`: come back onto the path.
  bool goesOn(Pose at) {
    return searchCarUntil(ws_, at, rho_, kStrokeLoopExpansions, [&](Pose q, Path& last) {
      const Pose* on = driven_.near(q);
      return on && carCurveInto(q, *on, rho_, false, false, last) && pathFree(ws_, last);
    }, &poses_).segments() > 0;
  }
  bool lineFree(Point a, Point b) { return ws_.router().isFree(a, b); }
  /// The arc of radius rho from p, `length` along it (turning left when `left`; at most half a
  /// circle), as a path of one segment (tool on) in arc_, and the pose at its end.
  Pose arcTo(Pose p, bool left, double length) {
    const double k = (left ? 1.0 : -1.0) / rho_, h = p.heading + k * length;
    const Pose end{{p.at.x + (std::sin(h) - std::sin(p.heading)) / k, p.at.y - (std::cos(h) - std::cos(p.heading)) / k}, h};
    arc_ = Path{};
    arc_.moveTo(p.at, true);
    arc_.arcTo(end.at, std::tan(k * length / 4.0), true);
    return end;
  }
  /// A stroke on an arc of radius rho from p, left or else right, into `last`.
  bool arcStroke(Pose p, Path& last) {
    for (const bool left : {true, false}) {
      double length = spacing_;
      Pose end = arcTo(p, left, length);
      if (!grid_.openAlong(arc_, 0, open_share_) || !pathFree(ws_, arc_)) continue;
      for (; length + step_ <= M_PI * rho_; length += step_) {
        const Pose next = arcTo(end, left, step_);
        if (!grid_.openAlong(arc_, 0, kStrokeOpenOn) || !pathFree(ws_, arc_)) break;
        end = next;
      }
      for (; length >= spacing_ - 1e-9 && !goesOn(end); length -= step_) end = arcTo(p, left, length - step_);
      if (length < spacing_ - 1e-9) continue;
      arcTo(p, left, length);
      last = arc_;
      return true;
    }
    return false;
  }
  /// A stroke from p into `last`: straight ahead, or else on an arc (arcStroke).
  bool stroke(Pose p, Path& last) {
    const Point dir{std::cos(p.heading), std::sin(p.heading)};
    Point b = p.at + dir * spacing_;
    if (!enoughOpen(grid_.openIn(p.at, b), open_share_) || !lineFree(p.at, b)) return !dead_end_stroke_ && arcStroke(p, last);
    for (int k = 0; k < kStrokeSteps; ++k) {
      const Point c = b + dir * step_;
      if (!enoughOpen(grid_.openIn(b, c), kStrokeOpenOn) || !lineFree(b, c)) break;
      b = c;
    }
    if (!dead_end_stroke_)
      while (!goesOn({b, p.heading})) {
        b = b - dir * step_;
        if (distance(p.at, b) < spacing_ - 1e-9) return arcStroke(p, last);
      }
    last = Path{};
    last.moveTo(p.at, true);
    last.moveTo(b, true);
    return true;
  }
  /// The route to the nearest stroke and the stroke: the search at cells of R/2, and where it finds
  /// none, at cells twice and four times finer (kStrokeFinestSearch), while the budget lasts.
  Path searchStroke() {
    Path route;
    for (int fineness = 1; fineness <= kStrokeFinestSearch && route.segments() == 0 && poses_ < kStrokeBudget; fineness *= 2)
      route = searchCarUntil(ws_, endPose(path_), rho_, std::min(kStrokeExpansions, kStrokeBudget - poses_),
                             [this](Pose p, Path& last) { return stroke(p, last); }, &poses_, fineness);
    return route;
  }
  /// ...and where there is none, the nearest at kStrokeOpenLast.
  Path findStroke() {
    Path route = searchStroke();
    if (route.segments() == 0) {
      open_share_ = kStrokeOpenLast;
      route = searchStroke();
      open_share_ = kStrokeOpen;
    }
    return route;
  }
  /// Appends `route` when it paints more: its last segment (the stroke) painted, and each segment
  /// before it that passes over enough unpainted (kStrokeOpenOn). False (and the path as it was)
  /// otherwise.
  bool take(Path& route) {
    if (route.segments() == 0) return false;
    for (std::size_t k = 0; k + 1 < route.segments(); ++k) route.tool_on[k] = grid_.openAlong(route, k, kStrokeOpenOn);
    route.tool_on.back() = true;
    const double before = grid_.painted();
    const std::size_t first = path_.segments();
    append(path_, route);
    grid_.paintMore(path_, first);
    if (!(grid_.painted() > before)) {
      path_ = upTo(path_, first + 1);
      grid_.paint(path_);
      return false;
    }
    driven_.add(path_, first);
    return true;
  }
  /// The time limit ends the strokes where it is found to have passed (the plan is then partial).
  bool expired() { return timed_out_ = timed_out_ || budget_.expired(); }
  /// The dead-end row the sweep ended in, again, from where the strokes end (when a search reaches
  /// it and it paints more).
  void takeDeadEndRowAgain() {
    Path route = searchCarRoute(ws_, endPose(path_), *row_from_, rho_, false, kSearchExpansions, &poses_);
    if (route.segments() > 0) {
      route.moveTo(out_.path.waypoints.back(), true);
      row_reached_ = true;
      row_again_ = dead_end_ = take(route);  // not taken: the strokes painted all it would
    }
  }
  /// A last stroke that may end in a dead end: the one with the most unpainted reach of all the
  /// search finds (it looks at every pose it reaches), then the same search again, stopped at
  /// that stroke.
  void takeLastStroke() {
    dead_end_stroke_ = true;
    std::size_t most = 0;
    std::optional<Pose> best;
    int fineness = 1;
    for (; fineness <= kStrokeFinestSearch && poses_ < kStrokeBudget; fineness *= 2) {
      searchCarUntil(ws_, endPose(path_), rho_, std::min(kStrokeExpansions, kStrokeBudget - poses_), [&](Pose q, Path& last) {
        if (stroke(q, last)) {
          const std::size_t open_cells = grid_.openIn(last.waypoints.front(), last.waypoints.back()).first;
          if (open_cells > most) most = open_cells, best = q;
        }
        return false;
      }, &poses_, fineness);
      if (best) break;
    }
    Path route;
    if (best)
      route = searchCarUntil(ws_, endPose(path_), rho_, kStrokeExpansions, [&](Pose q, Path& last) {
        return q.at == best->at && q.heading == best->heading && stroke(q, last);
      }, &poses_, fineness);
    if (take(route)) {
      ++count_;
      dead_end_ = true;
    }
  }
  /// Makes the strokes out's path, with its counts and its dead end (`before_end`: the path's
  /// waypoints before the last stroke or the row taken again).
  void keep(std::size_t before_end) {
    if (row_from_ && !row_reached_) {
      // The dead-end row is left out: a row left out (no route reached it from the strokes' end),
      // or one fill pass fewer.
      if (out_.dead_end_fill) --out_.fill_passes;
      else ++out_.unreached;
    }
    if (dead_end_ && !row_again_) {
      const std::size_t n = path_.waypoints.size();
      out_.dead_end_row = {path_.waypoints[n - 2], path_.waypoints[n - 1], 0, false, kAnyCell};
    }
    out_.path = std::move(path_);
    out_.strokes = count_;
    out_.ended_in_dead_end = dead_end_;
    if (dead_end_) out_.dead_end_from = before_end;
    if (!row_again_) out_.dead_end_fill = false;
    if (timed_out_) out_.rounds_timed_out = true;
    checkDrivable(out_.path, ws_.vehicle(), "the car's strokes");
  }

  Workspace& ws_;
  CarSweep& out_;
  PaintGrid& grid_;
  const double spacing_, rho_;
  const Budget& budget_;
  const double step_;              // how far a stroke goes on at a time
  Path path_;                      // out.path (before its dead-end row) and the strokes so far
  std::optional<Pose> row_from_;   // the dead-end row's first pose, when the sweep ended in one
  PathPoses driven_;               // the poses path_ passes through
  std::size_t poses_ = 0;          // searched, over all strokes
  std::size_t count_ = 0;          // strokes taken
  bool dead_end_stroke_ = false;   // the stroke searched for may end in a dead end
  double open_share_ = kStrokeOpen;
  Path arc_;                       // arcTo's arc
  bool timed_out_ = false;
  bool row_reached_ = false, row_again_ = false, dead_end_ = false;
};

}  // namespace

/// Strokes (a forward-only car, after the fill rounds): passes through what the path leaves
/// unpainted, each reached from where the path ends by a search over the car's motions
/// (searchCarUntil) to the nearest pose with a spacing of mostly unpainted reach (kStrokeOpen;
/// kStrokeOpenLast where none has) ahead: straight, or else on an arc of radius rho, left or
/// right; driven on while each half spacing finds enough unpainted (kStrokeOpenOn). The route
/// there paints where it passes over enough unpainted (kStrokeOpenOn). A stroke ends where the car
/// can come back to a pose it drove (an exact curve onto it that lies in F): then it drove a loop
/// through the path, and can go on. A circle it could drive there is not enough: it may circle in
/// a pocket with no way out. A sweep that ended in a dead-end row strokes from before it and takes
/// that row again last, when a search reaches it (and it paints more; else the row is left out,
/// unless the strokes painted all it would); else the last stroke, the straight one with the most
/// unpainted reach a search finds, may end in a dead end. Each stroke is kept when it paints more,
/// and all of them when what they paint is worth the path they add (worthIt, as a fill round).
void strokes(Workspace& ws, CarSweep& out, PaintGrid& grid, double painted_before, double spacing, double rho, const Budget& budget) {
  Strokes(ws, out, grid, spacing, rho, budget).run(painted_before);
}

void paintTransits(CarSweep& out, PaintGrid& grid) {
  Path& path = out.path;
  for (std::size_t i = 0; i < path.segments(); ++i) {
    if (path.tool_on[i] || !grid.openAlong(path, i, kStrokeOpenOn)) continue;
    path.tool_on[i] = true;
    grid.paintSegment(path, i);
    ++out.painted_transits;
  }
}

}  // namespace coverbench::vehicle_detail
