// Replanning around surprises: cutting a path, drawing the obstacles that appear, and the two
// repairs (docs/replanning.md).
#include "coverbench/replanning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "coverbench/metrics.hpp"
#include "coverbench/rng.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

double mm(double v) { return std::round(v * 1000.0) / 1000.0; }

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

/// The point at `along` metres of the tool-on segments of `path` (all segments when none is
/// tool-on; the first waypoint when the path has no length).
Point pointAlong(const Path& path, double along, bool tool_on_only) {
  for (std::size_t i = 0; i < path.segments(); ++i) {
    if (tool_on_only && !path.tool_on[i]) continue;
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    const double len = distance(a, b);
    if (along <= len && len > 0.0) return a + (b - a) * (along / len);
    along -= len;
  }
  return path.waypoints.empty() ? Point{} : path.waypoints.back();
}

double lengthOf(const Path& path, bool tool_on_only) {
  double total = 0.0;
  for (std::size_t i = 0; i < path.segments(); ++i)
    if (!tool_on_only || path.tool_on[i]) total += distance(path.waypoints[i], path.waypoints[i + 1]);
  return total;
}

/// Width and height of one obstacle of `kind` on a wall whose bounding box is w x h. Draws happen
/// in statement order (rng.hpp).
Point drawSize(SurpriseKind kind, Rng& rng, double w, double h) {
  switch (kind) {
    case SurpriseKind::Scaffolding: {
      const double sw = rng.uniform(1.0, 2.5);
      const double sh = rng.uniform(1.0, 2.0);
      return {std::min(sw, 0.3 * w), std::min(sh, 0.3 * h)};
    }
    case SurpriseKind::Ladder: {
      const double lw = rng.uniform(0.4, 0.6);
      const double lh = rng.uniform(2.0, 4.0);
      return {std::min(lw, 0.15 * w), std::min(lh, 0.6 * h)};
    }
    case SurpriseKind::Duct: {
      const double length = rng.uniform(1.5, 4.0);
      const double thickness = rng.uniform(0.06, 0.12);
      const bool vertical = rng.chance(0.5);
      return vertical ? Point{std::min(thickness, 0.1 * w), std::min(length, 0.6 * h)}
                      : Point{std::min(length, 0.6 * w), std::min(thickness, 0.1 * h)};
    }
  }
  return {0.0, 0.0};
}

/// The straight stretches of [a, b] along which the tool keeps the clearance (TransitRouter::isFree),
/// in order from a. Samples at most every r / 2 find the free runs; their ends are found by
/// bisection to a micrometre; a run is split where a straight move between its samples is not free.
std::vector<std::pair<Point, Point>> freeStretches(const TransitRouter& router, Point a, Point b, double r) {
  if (router.isFree(a, b)) return {{a, b}};
  const double len = distance(a, b);
  const std::size_t n = std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(len / (0.5 * r))), 1, 8192);
  auto at = [&](double t) { return a + (b - a) * t; };
  auto pointFree = [&](double t) { return router.isFree(at(t), at(t)); };
  std::vector<char> free(n + 1);
  for (std::size_t k = 0; k <= n; ++k) free[k] = pointFree(static_cast<double>(k) / static_cast<double>(n)) ? 1 : 0;
  // The free end of the boundary between a blocked and a free parameter.
  auto edge = [&](double blocked, double open) {
    for (int it = 0; it < 60 && std::abs(open - blocked) * len > 1e-6; ++it) {
      const double mid = 0.5 * (blocked + open);
      (pointFree(mid) ? open : blocked) = mid;
    }
    return open;
  };
  std::vector<std::pair<Point, Point>> out;
  std::size_t k = 0;
  while (k <= n) {
    if (!free[k]) {
      ++k;
      continue;
    }
    std::size_t j = k;
    while (j + 1 <= n && free[j + 1]) ++j;
    const double step = 1.0 / static_cast<double>(n);
    std::vector<Point> pts;
    pts.push_back(k == 0 ? a : at(edge(static_cast<double>(k - 1) * step, static_cast<double>(k) * step)));
    for (std::size_t s = k + 1; s < j; ++s) pts.push_back(at(static_cast<double>(s) * step));
    if (j > k) pts.push_back(at(static_cast<double>(j) * step));
    if (j < n) pts.push_back(at(edge(static_cast<double>(j + 1) * step, static_cast<double>(j) * step)));
    // Greedy: the longest free straight move from each stretch start through the samples.
    std::size_t from = 0;
    while (from + 1 < pts.size()) {
      std::size_t to = from;
      while (to + 1 < pts.size() && router.isFree(pts[from], pts[to + 1])) ++to;
      if (to > from) out.emplace_back(pts[from], pts[to]);
      from = std::max(to, from + 1);
    }
    k = j + 1;
  }
  return out;
}

/// Cells of side `cell` over a box; a cell counts as painted by a move when its centre lies within
/// r of the move (the capsule a disk of radius r sweeps along it).
class PaintRaster {
 public:
  PaintRaster(const Box& box, double tool_width) : box_(box) {
    // s / 4, coarser on huge walls: at most about 4 million cells.
    cell_ = std::max(tool_width / 4.0, std::sqrt(std::max(box.width() * box.height(), 1e-12) / 4e6));
    nx_ = static_cast<long>(std::ceil(box.width() / cell_)) + 1;
    ny_ = static_cast<long>(std::ceil(box.height() / cell_)) + 1;
    cells_.assign(static_cast<std::size_t>(nx_ * ny_), 0);
  }
  void paint(Point a, Point b, double r) {
    visit(a, b, r, [&](std::size_t i) { cells_[i] = 1; });
  }
  /// Of the cells within r of [a, b], the share painted already (1 when there are none).
  double paintedShare(Point a, Point b, double r) const {
    std::size_t total = 0, painted = 0;
    visit(a, b, r, [&](std::size_t i) {
      ++total;
      painted += static_cast<std::size_t>(cells_[i]);
    });
    return total == 0 ? 1.0 : static_cast<double>(painted) / static_cast<double>(total);
  }

 private:
  /// Calls f for every cell whose centre lies within r of [a, b]: per row of centres, the capsule
  /// (convex) meets the row's line in one interval, the hull of where the two end disks and the
  /// band between them meet it.
  template <class F>
  void visit(Point a, Point b, double r, F&& f) const {
    const Point d = b - a;
    const double len2 = dot(d, d), len = std::sqrt(len2);
    const long y0 = std::max(0L, static_cast<long>(std::ceil((std::min(a.y, b.y) - r - box_.min_y) / cell_ - 0.5)));
    const long y1 = std::min(ny_ - 1, static_cast<long>(std::floor((std::max(a.y, b.y) + r - box_.min_y) / cell_ - 0.5)));
    for (long y = y0; y <= y1; ++y) {
      const double cy = box_.min_y + (static_cast<double>(y) + 0.5) * cell_;
      double lo = INFINITY, hi = -INFINITY;
      auto take = [&](double l, double h) {
        if (l > h) return;
        lo = std::min(lo, l);
        hi = std::max(hi, h);
      };
      for (const Point& e : {a, b}) {
        const double dy = cy - e.y;
        if (std::abs(dy) <= r) {
          const double half = std::sqrt(r * r - dy * dy);
          take(e.x - half, e.x + half);
        }
      }
      if (len2 > 0.0) {
        // Distance to the line at most r, and the projection within the segment.
        double l1 = -INFINITY, h1 = INFINITY, l2 = -INFINITY, h2 = INFINITY;
        const double ry = cy - a.y;
        if (d.y != 0.0) {
          const double u = a.x + (d.x * ry - r * len) / d.y, v = a.x + (d.x * ry + r * len) / d.y;
          l1 = std::min(u, v), h1 = std::max(u, v);
        } else if (std::abs(ry) > r) {
          l1 = 1.0, h1 = 0.0;
        }
        if (d.x != 0.0) {
          const double u = a.x - d.y * ry / d.x, v = a.x + (len2 - d.y * ry) / d.x;
          l2 = std::min(u, v), h2 = std::max(u, v);
        } else if (d.y * ry < 0.0 || d.y * ry > len2) {
          l2 = 1.0, h2 = 0.0;
        }
        take(std::max(l1, l2), std::min(h1, h2));
      }
      if (!(lo <= hi)) continue;
      const long x0 = std::max(0L, static_cast<long>(std::ceil((lo - box_.min_x) / cell_ - 0.5)));
      const long x1 = std::min(nx_ - 1, static_cast<long>(std::floor((hi - box_.min_x) / cell_ - 0.5)));
      for (long x = x0; x <= x1; ++x) f(static_cast<std::size_t>(y * nx_ + x));
    }
  }

  Box box_;
  double cell_ = 1.0;
  long nx_ = 1, ny_ = 1;
  std::vector<char> cells_;
};

/// The executed part followed by the builder's moves (its first point is the cut point).
void join(Repair& repair, const PathCut& cut, const Path& repaired) {
  repair.path = cut.executed;
  repair.cut_waypoint = repair.path.waypoints.empty() ? 0 : repair.path.waypoints.size() - 1;
  if (repair.path.waypoints.empty()) {
    repair.path = repaired;
    return;
  }
  for (std::size_t i = 0; i < repaired.segments(); ++i) repair.path.moveTo(repaired.waypoints[i + 1], repaired.tool_on[i]);
}

void describeLeftOut(Repair& repair) {
  std::vector<std::string> parts;
  if (repair.blocked_m > 0.0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f m of painting the obstacles block", repair.blocked_m);
    parts.push_back(buf);
  }
  if (repair.unreachable_moves) parts.push_back(std::to_string(repair.unreachable_moves) + " moves no transit reached");
  if (!parts.empty()) repair.reason = "left out " + joinNames(parts);
}

}  // namespace

Path Repair::repairedPart() const {
  Path part;
  for (std::size_t i = cut_waypoint; i < path.waypoints.size(); ++i)
    part.moveTo(path.waypoints[i], i == cut_waypoint ? false : path.tool_on[i - 1]);
  return part;
}

std::string toString(SurpriseKind kind) {
  switch (kind) {
    case SurpriseKind::Scaffolding: return "scaffolding";
    case SurpriseKind::Ladder: return "ladder";
    case SurpriseKind::Duct: return "duct";
  }
  return "scaffolding";
}

const std::vector<SurpriseKind>& allSurpriseKinds() {
  static const std::vector<SurpriseKind> kinds{SurpriseKind::Scaffolding, SurpriseKind::Ladder, SurpriseKind::Duct};
  return kinds;
}

bool parseSurpriseKind(const std::string& name, SurpriseKind& kind) {
  for (SurpriseKind k : allSurpriseKinds())
    if (toString(k) == name) {
      kind = k;
      return true;
    }
  return false;
}

std::string toString(RepairMethod method) { return method == RepairMethod::Replan ? "replan" : "detour"; }

bool parseRepairMethod(const std::string& name, RepairMethod& method) {
  for (RepairMethod m : {RepairMethod::Replan, RepairMethod::Detour})
    if (toString(m) == name) {
      method = m;
      return true;
    }
  return false;
}

std::string ReplanningSpec::describe() const {
  std::vector<std::string> fractions, kind_names, repair_names;
  for (double f : at) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", f);
    fractions.push_back(buf);
  }
  for (SurpriseKind k : kinds) kind_names.push_back(toString(k));
  for (RepairMethod m : repairs) repair_names.push_back(toString(m));
  return "at=" + joinNames(fractions) + " obstacles=" + std::to_string(obstacles) + " kinds=" + joinNames(kind_names) +
         " repairs=" + joinNames(repair_names);
}

Path straightenedForReplanning(const Path& path) { return chordalPath(path, kReplanChordSagitta); }

PathCut cutPath(const Path& in, double fraction) {
  const Path path = straightenedForReplanning(in);
  PathCut cut;
  if (path.waypoints.empty()) return cut;
  const double target = std::clamp(fraction, 0.0, 1.0) * lengthOf(path, false);
  double along = 0.0;
  std::size_t i = 0;
  cut.executed.moveTo(path.waypoints[0], false);
  cut.position = path.waypoints[0];
  for (; i < path.segments(); ++i) {
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    const double len = distance(a, b);
    if (along + len >= target) {
      const double t = len > 0.0 ? std::clamp((target - along) / len, 0.0, 1.0) : 1.0;
      cut.position = t >= 1.0 ? b : a + (b - a) * t;
      cut.executed.moveTo(cut.position, path.tool_on[i]);
      break;
    }
    along += len;
    cut.executed.moveTo(b, path.tool_on[i]);
    cut.position = b;
  }
  cut.length = lengthOf(cut.executed, false);
  cut.remainder.moveTo(cut.position, false);
  for (; i < path.segments(); ++i) cut.remainder.moveTo(path.waypoints[i + 1], path.tool_on[i]);
  return cut;
}

Surprise makeSurprise(const Wall& wall, const ToolParams& tool, const Path& in, double fraction,
                      const ReplanningSpec& spec, std::uint64_t seed) {
  const Path path = straightenedForReplanning(in);
  Surprise s;
  s.fraction = fraction;
  s.cut = cutPath(path, fraction);
  s.wall = wall;
  s.requested = static_cast<std::size_t>(std::max(0, spec.obstacles));
  if (spec.kinds.empty() || s.cut.remainder.waypoints.empty()) return s;
  std::uint64_t bits;
  std::memcpy(&bits, &fraction, sizeof bits);
  std::uint64_t mix = seed ^ 0x7265706c616e21ULL;  // "replan!"
  mix = Rng::splitmix(mix) ^ bits;
  Rng rng(Rng::splitmix(mix));

  const Box box = boundingBox(wall.boundary);
  const bool painted_ahead = lengthOf(s.cut.remainder, true) > 0.0;
  const double ahead = lengthOf(s.cut.remainder, painted_ahead);
  const double keep = tool.radius() + tool.clearance + 1e-6;  // from the robot
  for (std::size_t k = 0; k < s.requested; ++k) {
    const SurpriseKind kind = spec.kinds[static_cast<std::size_t>(rng.integer(0, static_cast<int>(spec.kinds.size()) - 1))];
    for (int attempt = 0; attempt < 200; ++attempt) {
      const Point size = drawSize(kind, rng, box.width(), box.height());
      const double along = rng.uniform(0.0, ahead);
      const double jx = rng.uniform(-0.25, 0.25);
      const double jy = rng.uniform(-0.25, 0.25);
      const Point centre = pointAlong(s.cut.remainder, along, painted_ahead);
      const double x0 = mm(std::max(box.min_x, centre.x + jx * size.x - 0.5 * size.x));
      const double y0 = mm(std::max(box.min_y, centre.y + jy * size.y - 0.5 * size.y));
      const double x1 = mm(std::min(box.max_x, centre.x + jx * size.x + 0.5 * size.x));
      const double y1 = mm(std::min(box.max_y, centre.y + jy * size.y + 0.5 * size.y));
      if (x1 - x0 < 0.005 || y1 - y0 < 0.005) continue;
      Obstacle o;
      o.type = ObstacleType::Rect;
      o.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
      o.label = "surprise: " + toString(kind);
      if (distanceSegmentFilledRing(s.cut.position, s.cut.position, o.polygon) <= keep) continue;
      Wall candidate = s.wall;
      candidate.obstacles.push_back(o);
      try {
        validateWall(candidate, "surprise");
      } catch (const InputError&) {
        continue;  // outside the wall, or nothing left to cover
      }
      s.wall = std::move(candidate);
      s.obstacles.push_back(std::move(o));
      break;
    }
  }
  return s;
}

Repair repairByDetour(const Surprise& surprise, const Problem& problem) {
  Workspace ws(surprise.wall, problem);
  PathBuilder b(ws);
  Repair repair;
  const Path& rem = surprise.cut.remainder;
  if (rem.waypoints.empty()) return repair;
  b.start(surprise.cut.position);
  const double r = problem.tool.radius();
  for (std::size_t i = 0; i < rem.segments(); ++i) {
    const Point a = rem.waypoints[i], c = rem.waypoints[i + 1];
    if (!rem.tool_on[i]) {
      // A move to where an obstacle now stands is skipped: the next move starts from here.
      if (!ws.router().isFree(c, c) && !problem.vehicle.liftsTool()) continue;
      if (!b.moveTo(c, false)) ++repair.unreachable_moves;
      continue;
    }
    const auto stretches = freeStretches(ws.router(), a, c, r);
    if (stretches.empty()) ++repair.dropped_moves;
    else ++repair.kept_moves;
    double free_length = 0.0;
    for (const auto& [p, q] : stretches) free_length += distance(p, q);
    repair.blocked_m += std::max(0.0, distance(a, c) - free_length);
    for (const auto& [p, q] : stretches) {
      if (!b.moveTo(p, false)) {
        ++repair.unreachable_moves;
        continue;
      }
      b.moveTo(q, true);
    }
  }
  repair.transits = b.transits();
  join(repair, surprise.cut, b.path());
  repair.ok = true;
  describeLeftOut(repair);
  return repair;
}

Repair repairFromPlan(const Surprise& surprise, const Problem& problem, const Path& in) {
  const Path plan = straightenedForReplanning(in);
  Workspace ws(surprise.wall, problem);
  Repair repair;
  if (surprise.cut.remainder.waypoints.empty()) return repair;
  const double r = problem.tool.radius();
  Box box = boundingBox(surprise.wall.boundary);
  box.add({box.min_x - r, box.min_y - r});
  box.add({box.max_x + r, box.max_y + r});
  PaintRaster raster(box, problem.tool.tool_width);
  const Path& done = surprise.cut.executed;
  for (std::size_t i = 0; i < done.segments(); ++i)
    if (done.tool_on[i]) raster.paint(done.waypoints[i], done.waypoints[i + 1], r);
  PathBuilder b(ws);
  b.start(surprise.cut.position);
  for (std::size_t i = 0; i < plan.segments(); ++i) {
    if (!plan.tool_on[i]) continue;
    const Point a = plan.waypoints[i], c = plan.waypoints[i + 1];
    if (raster.paintedShare(a, c, r) >= 1.0) {
      ++repair.dropped_moves;
      continue;
    }
    if (!b.moveTo(a, false)) {
      ++repair.unreachable_moves;
      continue;
    }
    b.moveTo(c, true);
    ++repair.kept_moves;
  }
  repair.transits = b.transits();
  join(repair, surprise.cut, b.path());
  repair.ok = true;
  describeLeftOut(repair);
  return repair;
}

}  // namespace coverbench
