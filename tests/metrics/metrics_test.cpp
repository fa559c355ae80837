// The metrics engine against hand-computed values, and its invariances over generated walls.
#include <gtest/gtest.h>

#include <cmath>

#include "coverbench/metrics.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::rect;
using test::rectWall;

struct Move {
  Point to;
  bool on;
};
Path makePath(Point start, std::vector<Move> moves) {
  Path p;
  p.moveTo(start, false);
  for (const Move& m : moves) {
    p.waypoints.push_back(m.to);  // keeps zero-length and repeated moves as given
    p.tool_on.push_back(m.on);
  }
  return p;
}

double overlapArea(const PathMetrics& m) { return m.passes.overlap * m.passes.swept_area; }

bool contains(const Region& region, Point p) {
  for (const PolygonWithHoles& poly : region)
    if (pointInPolygon(poly, p)) return true;
  return false;
}

const double kR = 0.1;
const ToolParams kTool{2 * kR, 0.0};
const double kCapsule3 = 2 * kR * 3.0 + M_PI * kR * kR;  // one 3 m pass

TEST(Metrics, OneStraightPassOnAnEmptyWall) {
  const Wall w = rectWall(4, 2);
  const PathMetrics m = computeMetrics(w, kTool, makePath({0.5, 1}, {{{3.5, 1}, true}}));
  const double reachable = 4 * 2 - (4 - M_PI) * kR * kR;  // the wall with its corners rounded by r
  EXPECT_NEAR(m.coverage.swept_area, kCapsule3, 1e-12);  // exact: a valid path's |S| is the pass areas' level 1
  EXPECT_NEAR(m.coverage.reachable_area, reachable, 1e-12);  // closed form (regionAreas)
  EXPECT_NEAR(m.coverage.paintable_area, 8.0, 1e-12);
  EXPECT_NEAR(m.coverage.coverage_reachable, kCapsule3 / reachable, 1e-12);
  EXPECT_NEAR(m.coverage.coverage_wall, kCapsule3 / 8.0, 1e-12);
  EXPECT_NEAR(m.passes.overlap, 0.0, 1e-12);
  EXPECT_NEAR(m.passes.histogram[0], 1.0, 1e-12);
  EXPECT_NEAR(m.passes.swept_area, kCapsule3, 1e-12);
  EXPECT_DOUBLE_EQ(m.lengths.total, 3.0);
  EXPECT_EQ(m.motion.turns, 0u);
  EXPECT_DOUBLE_EQ(m.motion.turning_angle, 0.0);
  EXPECT_NEAR(m.motion.duration_s, 3.0 / 0.3 + 0.3 / 0.5, 1e-12);  // cruise plus ramps
  EXPECT_NEAR(m.length_ratio, 3.0 / (reachable / (2 * kR)), 1e-6);
  EXPECT_EQ(m.waypoints, 2u);
}

TEST(Metrics, TwoParallelPassesCloserThanTheToolWidth) {
  // Rows 0.1 apart with a 0.2 tool, joined by a transit: two passes over a band 0.1 wide, plus
  // the lens where the end disks overlap.
  const Wall w = rectWall(4, 2);
  const Path p = makePath({0.5, 1.0}, {{{3.5, 1.0}, true}, {{0.5, 1.1}, false}, {{3.5, 1.1}, true}});
  const PathMetrics m = computeMetrics(w, kTool, p);
  const double d = 0.1;
  const double lens = 2 * kR * kR * std::acos(d / (2 * kR)) - d / 2 * std::sqrt(4 * kR * kR - d * d);
  const double both = (2 * kR - d) * 3.0 + lens;
  const double swept = 2 * kCapsule3 - both;
  EXPECT_NEAR(m.coverage.swept_area, swept, 1e-12);
  EXPECT_NEAR(overlapArea(m), both, 1e-12);  // exact
  EXPECT_NEAR(m.passes.histogram[1], both / swept, 0.005);
  EXPECT_EQ(passCount(p, kR, {2.0, 1.05}), 2);
  EXPECT_EQ(passCount(p, kR, {2.0, 0.95}), 1);
}

TEST(Metrics, LTurnHasACornerCoveredTwice) {
  // Inside the corner, points within r of both legs but farther than r from the corner
  // waypoint are passed twice: a square r x r minus a quarter disk.
  const Wall w = rectWall(4, 4);
  const Path p = makePath({1, 1}, {{{3, 1}, true}, {{3, 3}, true}});
  const PathMetrics m = computeMetrics(w, kTool, p);
  const double twice = kR * kR * (1 - M_PI / 4);
  const double swept = 0.8 + M_PI * kR * kR - kR * kR + M_PI * kR * kR / 4;
  EXPECT_NEAR(m.coverage.swept_area, swept, 1e-12);
  EXPECT_NEAR(overlapArea(m), twice, 1e-12);
  EXPECT_EQ(passCount(p, kR, {2.95, 1.05}), 1);  // near the corner: one continuous pass
  EXPECT_EQ(passCount(p, kR, {2.92, 1.08}), 2);  // in the inner corner, beyond r of the waypoint
  EXPECT_EQ(passCount(p, kR, {3.05, 0.95}), 1);  // outer corner
  EXPECT_EQ(m.motion.turns, 1u);
  EXPECT_EQ(m.motion.turns_30, 1u);
  EXPECT_NEAR(m.motion.turning_angle, M_PI / 2, 1e-12);
  EXPECT_NEAR(m.motion.duration_s, 2 * (2.0 / 0.3 + 0.3 / 0.5), 1e-12);  // stops at the corner
}

TEST(Metrics, UTurnPassCounts) {
  const Path p = makePath({1, 1}, {{{3, 1}, true}, {{3, 1.1}, true}, {{1, 1.1}, true}});
  EXPECT_EQ(passCount(p, kR, {2.0, 1.05}), 2);  // between the rows: both rows, no continuation
  EXPECT_EQ(passCount(p, kR, {3.0, 1.05}), 1);  // on the turn: one continuous pass
  EXPECT_EQ(passCount(p, kR, {2.0, 0.95}), 1);
  EXPECT_EQ(passCount(p, kR, {2.0, 1.25}), 0);
  const Motion mo = motion(p);
  EXPECT_EQ(mo.turns_30, 2u);
  EXPECT_NEAR(mo.turning_angle, M_PI, 1e-12);
  // Runs of 2, 0.1 and 2 m: the short one never reaches v (triangular profile).
  EXPECT_NEAR(mo.duration_s, 2 * (2 / 0.3 + 0.3 / 0.5) + 2 * std::sqrt(0.1 / 0.5), 1e-12);
}

TEST(Metrics, TransitOverPaintedAreaPaintsNothing) {
  const Wall w = rectWall(4, 2);
  const Path p = makePath({0.5, 1}, {{{3.5, 1}, true}, {{0.5, 1}, false}, {{0.5, 1.5}, true}});
  const PathMetrics m = computeMetrics(w, kTool, p);
  EXPECT_EQ(passCount(p, kR, {2.0, 1.0}), 1);  // the transit back over the row is not a pass
  EXPECT_DOUBLE_EQ(m.lengths.transit, 3.0);
  EXPECT_DOUBLE_EQ(m.lengths.cover, 3.5);
  // Only around the shared start point is anything passed twice: a square r x r and three
  // quarter disks.
  const double twice = kR * kR + 3 * M_PI * kR * kR / 4;
  EXPECT_NEAR(overlapArea(m), twice, 1e-12);
  const double swept = kCapsule3 + (2 * kR * 0.5 + M_PI * kR * kR) - twice;
  EXPECT_NEAR(m.coverage.swept_area, swept, 1e-12);
}

TEST(Metrics, PathThroughAnObstacleIsInvalidButStillScored) {
  const Wall w = rectWall(4, 2, {rect(1.5, 0.5, 1, 1)});
  const PathMetrics m = computeMetrics(w, {0.2, 0.05}, makePath({0.5, 1}, {{{3.5, 1}, true}}));
  EXPECT_FALSE(m.validity.valid);
  EXPECT_EQ(m.validity.violations, 1u);
  EXPECT_NEAR(m.validity.min_clearance, -0.1, 1e-12);
  // The swept capsule minus the window is what the path painted of the wall.
  EXPECT_NEAR(m.coverage.coverage_wall, (kCapsule3 - 0.2 * 1.0) / (8.0 - 1.0), 1e-4);
}

TEST(Metrics, SlitNarrowerThanToolPlusClearanceIsNotReachable) {
  // A 0.12 m slit between two windows: less than s + 2c = 0.14, so no valid path reaches into it.
  const Wall w = rectWall(3, 2, {rect(1.0, 0, 0.5, 1.5), rect(1.62, 0, 0.5, 1.5)});
  const ToolParams tool{0.1, 0.02};
  const CoverageRegions regions = coverageRegions(w, tool, Path{});
  EXPECT_TRUE(contains(regions.paintable, {1.56, 0.75}));
  EXPECT_FALSE(contains(regions.reachable, {1.56, 0.75}));
  EXPECT_TRUE(contains(regions.reachable, {0.5, 0.75}));
  // A planner covering everything reachable leaves the slit: coverage of the wall stays lower.
  Problem problem;
  problem.wall = &w;
  problem.tool = tool;
  const PlannerInfo& z = findPlanner("zigzag");
  problem.params = resolveParams(z, {});
  const PlanResult r = runPlanner(z, problem, Budget());
  ASSERT_EQ(r.status, PlanStatus::Ok);
  const Coverage c = coverage(w, tool, r.path);
  EXPECT_GE(c.coverage_reachable, 0.995);
  EXPECT_LT(c.coverage_wall, c.coverage_reachable);
}

double outlineLength(const Region& region) {
  double total = 0.0;
  for (const Ring& ring : allRings(region))
    for (std::size_t k = 0; k < ring.size(); ++k) total += distance(ring[k], ring[(k + 1) % ring.size()]);
  return total;
}

TEST(Metrics, RegionAreasInClosedFormForObstaclesApart) {
  // A 2 m x 1 m wall, r = 0.1, c = 0.02; a 0.4 m x 0.3 m window and a round socket of radius 0.05,
  // each more than 2 r + c inside the wall and more than 2 (r + c) from the other.
  const double r = 0.1, c = 0.02;
  const ToolParams tool{2 * r, c};
  const Wall w = rectWall(2, 1, {rect(0.8, 0.35, 0.4, 0.3), test::circle(0.4, 0.5, 0.05)});
  const RegionAreas a = regionAreas(w, tool);
  EXPECT_EQ(a.obstacles_in_closed_form, 2u);
  EXPECT_TRUE(a.wall_in_closed_form);
  const double opened = 2.0 - (4.0 - M_PI) * r * r;  // the wall with its corners rounded by r
  const double window = 0.4 * 0.3 + c * 1.4 + M_PI * c * c;  // the window dilated by c
  const double socket = M_PI * (0.05 + c) * (0.05 + c);
  EXPECT_NEAR(a.reachable, opened - window - socket, 1e-12);
  EXPECT_NEAR(a.paintable, 2.0 - 0.4 * 0.3 - M_PI * 0.05 * 0.05, 1e-12);
  // The polygons (chords within 50 um) agree to within their chords.
  const CoverageRegions g = coverageRegions(w, tool, Path{});
  EXPECT_NEAR(area(g.reachable), a.reachable, kMetricArcTolerance * outlineLength(g.reachable));
  EXPECT_NEAR(area(g.paintable), a.paintable, kMetricArcTolerance * outlineLength(g.paintable));
  // A gable (a convex pentagon) opens in closed form too: each corner of angle t loses
  // r^2 (cot(t / 2) - (pi - t) / 2).
  Wall gable;
  gable.boundary = {{0, 0}, {4, 0}, {4, 2}, {2, 3}, {0, 2}};
  double lost = 0.0;
  for (const double t : {M_PI / 2, M_PI / 2, M_PI / 2 + std::atan(0.5), 2 * std::atan(2.0), M_PI / 2 + std::atan(0.5)})
    lost += r * r * (1.0 / std::tan(t / 2) - (M_PI - t) / 2);
  const RegionAreas ga = regionAreas(gable, tool);
  EXPECT_TRUE(ga.wall_in_closed_form);
  EXPECT_NEAR(ga.reachable, 10.0 - lost, 1e-12);
  EXPECT_NEAR(ga.paintable, 10.0, 1e-12);
}

TEST(Metrics, RegionAreasTakeThePolygonsForObstaclesNearTheEdgeOrEachOther) {
  // r = 0.1, c = 0.02: a door on the bottom edge, two windows 0.2 m apart (under 2 (r + c)), an
  // L-shaped obstacle (not convex), a window 0.219 m inside the top edge (under 2 r + c), and one
  // window apart from everything: only the last is taken away in closed form.
  const ToolParams tool{0.2, 0.02};
  Obstacle ell;
  ell.type = ObstacleType::Polygon;
  ell.polygon = {{5.0, 0.5}, {5.6, 0.5}, {5.6, 0.7}, {5.2, 0.7}, {5.2, 1.2}, {5.0, 1.2}};
  const Obstacle apart = rect(3.0, 0.6, 0.5, 0.5);
  const Wall w = rectWall(7, 2.5, {rect(0.3, 0.0, 0.8, 2.0), rect(1.6, 0.5, 0.4, 0.6), rect(2.2, 0.5, 0.4, 0.6), ell,
                                   rect(4.0, 1.6, 0.5, 2.5 - 1.6 - 0.219), apart});
  const RegionAreas a = regionAreas(w, tool);
  EXPECT_EQ(a.obstacles_in_closed_form, 1u);
  EXPECT_FALSE(a.wall_in_closed_form);
  // The rest as polygons, minus the window apart in closed form.
  Wall rest = w;
  rest.obstacles.pop_back();
  const CoverageRegions g = coverageRegions(rest, tool, Path{});
  EXPECT_NEAR(a.reachable, area(g.reachable) - (0.25 + 0.02 * 2.0 + M_PI * 0.02 * 0.02), 1e-9 * a.reachable);
  EXPECT_NEAR(a.paintable, area(g.paintable) - 0.25, 1e-9 * a.paintable);
  // Moved 2 mm deeper (0.221 m inside), the window near the top edge is apart too.
  Wall deeper = w;
  deeper.obstacles[4] = rect(4.0, 1.6 - 0.002, 0.5, 2.5 - 1.6 - 0.219);
  EXPECT_EQ(regionAreas(deeper, tool).obstacles_in_closed_form, 2u);
}

TEST(Metrics, ZeroLengthToolOnSegmentSweepsADisk) {
  const Wall w = rectWall(2, 2);
  const Path p = makePath({1, 1}, {{{1, 1}, true}});
  EXPECT_NEAR(coverage(w, kTool, p).swept_area, M_PI * kR * kR, 1e-5);
  EXPECT_EQ(motion(p).turns, 0u);
}

// ---- properties over generated walls ------------------------------------------------------

Path planFor(const Wall& wall, const ToolParams& tool, const std::string& planner) {
  const PlannerInfo& info = findPlanner(planner);
  Problem problem;
  problem.wall = &wall;
  problem.tool = tool;
  problem.params = resolveParams(info, {});
  PlanResult r = runPlanner(info, problem, Budget());
  return r.path;
}

/// Calls `check(wall, planner, path)` for zigzag and spiral paths on random walls 1..seeds.
template <class Check>
void forEachPlannedPath(const ToolParams& tool, unsigned seeds, Check check) {
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const Wall wall = test::randomWall(seed);
    for (const std::string planner : {"zigzag", "spiral"}) {
      const Path path = planFor(wall, tool, planner);
      if (!path.waypoints.empty()) check(wall, planner + ", seed " + std::to_string(seed), path);
    }
  }
}

/// Distance from q to segment k of the path, straight or an arc (q's angle about the centre within
/// the arc's sweep: |q - centre| - radius; else the nearer end).
double distanceToSegment(const Path& path, std::size_t k, Point q) {
  const Point a = path.waypoints[k], b = path.waypoints[k + 1];
  if (path.bulgeOf(k) == 0.0) return distancePointSegment(q, a, b);
  const ArcGeometry g = arcGeometry(a, b, path.bulgeOf(k));
  const double t0 = std::atan2(a.y - g.centre.y, a.x - g.centre.x), t = std::atan2(q.y - g.centre.y, q.x - g.centre.x);
  const double along = std::remainder(t - t0, 2.0 * M_PI) * (g.sweep < 0.0 ? -1.0 : 1.0);
  const double into = along < 0.0 ? along + 2.0 * M_PI : along;
  if (into <= std::fabs(g.sweep)) return std::fabs(distance(q, g.centre) - g.radius);
  return std::fmin(distance(q, a), distance(q, b));
}

/// Share of the wall's paintable area swept, estimated on a grid of points with brute force.
double rasterCoverageWall(const Wall& wall, const ToolParams& tool, const Path& path, int n) {
  const Box box = boundingBox(wall.boundary);
  long inside = 0, swept = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Point q{box.min_x + (i + 0.5) * box.width() / n, box.min_y + (j + 0.5) * box.height() / n};
      if (!pointInRing(q, wall.boundary)) continue;
      bool blocked = false;
      for (const Obstacle& o : wall.obstacles)
        blocked = blocked || (o.type == ObstacleType::Circle ? distance(q, o.center) < o.radius
                                                               : pointInRing(q, o.polygon));
      if (blocked) continue;
      ++inside;
      for (std::size_t k = 0; k < path.tool_on.size(); ++k)
        if (path.tool_on[k] && distanceToSegment(path, k, q) <= tool.radius()) {
          ++swept;
          break;
        }
    }
  return inside ? static_cast<double>(swept) / static_cast<double>(inside) : 0.0;
}

TEST(MetricsProperties, ExactCoverageAgreesWithAFineRaster) {
  const ToolParams tool{0.2, 0.02};
  forEachPlannedPath(tool, 8, [&](const Wall& wall, const std::string& what, const Path& path) {
    const double exact = coverage(wall, tool, path).coverage_wall;
    EXPECT_NEAR(exact, rasterCoverageWall(wall, tool, path, 160), 0.01) << what;
  });
}

TEST(MetricsProperties, ScanlinesOfThePicturesWithinHalfAPercentOfTheExactPassCounts) {
  // The overlap pictures' scanlines (r / 10 apart) against the exact pass counts on real paths:
  // every histogram bin within 0.5 % of |S|; and the exact |S| against the polygon union, whose
  // 50 um chords lie inside the arcs (so it is smaller, by at most chord depth times perimeter).
  // A path's own arcs are chords there too: the disk swept along them reaches less far on an
  // arc's outer side and farther on its inner side, so there the union may come out larger by
  // as much.
  const ToolParams tool{0.1, 0.02};
  forEachPlannedPath(tool, 6, [&](const Wall& wall, const std::string& what, const Path& path) {
    const Passes exact = passes(path, tool.radius());
    const Passes scan = passesOnScanlines(path, tool.radius(), tool.radius() / 10.0);
    for (std::size_t k = 0; k < exact.histogram.size(); ++k)
      EXPECT_NEAR(scan.histogram[k], exact.histogram[k], 0.005) << "bin " << k << ", " << what;
    EXPECT_NEAR(scan.swept_area, exact.swept_area, 0.005 * exact.swept_area) << what;
    const CoverageRegions regions = coverageRegions(wall, tool, path);
    const double polygons = area(regions.swept);
    double perimeter = 0.0;
    for (const Ring& ring : allRings(regions.swept))
      for (std::size_t k = 0; k < ring.size(); ++k) perimeter += distance(ring[k], ring[(k + 1) % ring.size()]);
    EXPECT_LE(polygons, exact.swept_area + (path.hasArcs() ? kMetricArcTolerance * perimeter : 1e-9)) << what;
    // |R| from the closed forms and the rest's polygons, against the region itself: within R's chords.
    EXPECT_NEAR(coverage(wall, tool, path).reachable_area, area(regions.reachable),
                kMetricArcTolerance * outlineLength(regions.reachable)) << what;
    EXPECT_GE(polygons, exact.swept_area - kMetricArcTolerance * perimeter) << what;
  });
}

TEST(MetricsProperties, OverlapPictureHasTheOverlapArea) {
  // The overlap layer of the pictures: disjoint staircase polygons whose area is the overlap
  // area measured on the same scanlines.
  const ToolParams tool{0.1, 0.02};
  forEachPlannedPath(tool, 6, [&](const Wall&, const std::string& what, const Path& path) {
    const double h = tool.radius() / 4.0;
    const Passes p = passesOnScanlines(path, tool.radius(), h);
    const Region picture = overlapRegion(path, tool.radius(), h);
    double sum = 0.0, perimeter = 0.0;
    for (const PolygonWithHoles& poly : picture) {
      for (std::size_t k = 0; k < poly.outer.size(); ++k)
        perimeter += distance(poly.outer[k], poly.outer[(k + 1) % poly.outer.size()]);
      EXPECT_TRUE(ringIsSimple(poly.outer)) << what;
      sum += std::fabs(signedArea(poly.outer));
    }
    const double expected = p.overlap * p.swept_area;
    EXPECT_NEAR(sum, expected, 1e-9 + 1e-9 * expected) << what;
    // Overlapping polygons would make the union smaller than the sum; the union goes through
    // a 1 micrometre grid, which moves each edge by at most half of it.
    EXPECT_NEAR(area(regionFromRings(allRings(picture))), sum, 1e-6 * perimeter) << "polygons overlap, " << what;
  });
}

TEST(MetricsProperties, InvariantUnderTranslation) {
  const ToolParams tool{0.1, 0.02};
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Wall wall = test::randomWall(seed);
    const Path path = planFor(wall, tool, "zigzag");
    const Point shift{123.456, -78.9};
    Wall moved = wall;
    for (Point& p : moved.boundary) p = p + shift;
    for (Obstacle& o : moved.obstacles) {
      for (Point& p : o.polygon) p = p + shift;
      o.center = o.center + shift;
    }
    Path moved_path = path;
    for (Point& p : moved_path.waypoints) p = p + shift;
    const std::vector<NamedMetric> a = flatten(computeMetrics(wall, tool, path));
    const std::vector<NamedMetric> b = flatten(computeMetrics(moved, tool, moved_path));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].name == "min_clearance" && std::isinf(a[i].value)) continue;
      // Areas go through a 1 micrometre grid; everything else is the same up to rounding.
      EXPECT_NEAR(a[i].value, b[i].value, 1e-5 * std::fmax(1.0, std::fabs(a[i].value)))
          << a[i].name << ", seed " << seed;
    }
  }
}

TEST(MetricsProperties, ReversingAPathChangesNoMetric) {
  const ToolParams tool{0.1, 0.02};
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Wall wall = test::randomWall(seed);
    for (const char* planner : {"zigzag", "spiral"}) {
      const Path path = planFor(wall, tool, planner);
      Path reversed;
      reversed.waypoints.assign(path.waypoints.rbegin(), path.waypoints.rend());
      reversed.tool_on.assign(path.tool_on.rbegin(), path.tool_on.rend());
      for (auto b = path.bulge.rbegin(); b != path.bulge.rend(); ++b) reversed.bulge.push_back(-*b);  // arcs turn the other way
      const std::vector<NamedMetric> a = flatten(computeMetrics(wall, tool, path));
      const std::vector<NamedMetric> b = flatten(computeMetrics(wall, tool, reversed));
      for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].name == "min_clearance" && std::isinf(a[i].value)) continue;
        EXPECT_NEAR(a[i].value, b[i].value, 1e-9 * std::fmax(1.0, std::fabs(a[i].value)))
            << a[i].name << ", " << planner << ", seed " << seed;
      }
    }
  }
}

}  // namespace
}  // namespace coverbench

namespace coverbench {
namespace {

// The published clock of the 100 m polygon benchmarks: v = 3 m/s, a = 1 m/s^2, a stop at every
// waypoint. A segment of d metres takes 2 sqrt(d / a) when d < v^2 / a = 9 m, else d / v + v / a.
// Three collinear segments of 4, 9 and 16 m: 2 sqrt(4) = 4 s, 9 / 3 + 3 = 6 s, 16 / 3 + 3 s.
TEST(TimeModels, TheVelocityRampByHandOnThreeSegments) {
  const Path p = makePath({0, 0}, {{{4, 0}, true}, {{13, 0}, true}, {{29, 0}, true}});
  MotionLimits eth;
  eth.speed = 3.0;
  eth.acceleration = 1.0;
  eth.stops = MotionLimits::Stops::Waypoints;
  EXPECT_NEAR(motion(p, eth).duration_s, 4.0 + 6.0 + (16.0 / 3.0 + 3.0), 1e-12);
  // Stopping only at turns, the three are one straight run of 29 m.
  eth.stops = MotionLimits::Stops::Turns;
  EXPECT_NEAR(motion(p, eth).duration_s, 29.0 / 3.0 + 3.0, 1e-12);
  EXPECT_FALSE(motion(p, eth).turn_cost_s.has_value());  // no cost per turn set: no such metric
}

// The clock that turns (Bormann et al., ICRA 2018: v 0.3 m/s, omega 0.52 rad/s, no ramp): length / v
// plus every heading change / omega, by hand on three paths.
TEST(TimeModels, TheRotationClockByHandOnThreePaths) {
  MotionLimits ipa;
  ipa.speed = 0.3;
  ipa.acceleration = HUGE_VAL;
  ipa.rotation_speed = 0.52;
  EXPECT_EQ(ipa.describe(), "v 0.3 m/s, no ramp, stops at turns over 30 degrees, rotates in place at 0.52 rad/s");
  // 1. Three sides of a 2 x 1 m rectangle: 5 m and two quarter turns.
  const Path box = makePath({0, 0}, {{{2, 0}, true}, {{2, 1}, true}, {{0, 1}, true}});
  EXPECT_NEAR(motion(box, ipa).duration_s, 5.0 / 0.3 + M_PI / 0.52, 1e-12);
  const Timeline t = timeline(box, ipa);  // the rotations are waits, standing
  EXPECT_NEAR(t.wait_s[1], (M_PI / 2.0) / 0.52, 1e-12);
  EXPECT_NEAR(t.arrive_s[2], 2.0 / 0.3 + (M_PI / 2.0) / 0.52 + 1.0 / 0.3, 1e-12);
  EXPECT_NEAR(t.end_s, motion(box, ipa).duration_s, 1e-12);
  // 2. Turns of 135 and 45 degrees (whatever the stop angle): 3 + sqrt 2 m and half a turn.
  const Path zig = makePath({0, 0}, {{{1, 0}, true}, {{0, 1}, false}, {{0, 3}, true}});
  EXPECT_NEAR(motion(zig, ipa).duration_s, (3.0 + std::sqrt(2.0)) / 0.3 + M_PI / 0.52, 1e-12);
  // 3. With a ramp (v 1 m/s, a 1 m/s2, omega 0.5 rad/s): a heading change of atan(0.01), far under
  // the stop angle, is still a stop and a rotation; the straight-through waypoint after it is not.
  MotionLimits ramp;
  ramp.speed = 1.0;
  ramp.acceleration = 1.0;
  ramp.rotation_speed = 0.5;
  const Path kink = makePath({0, 0}, {{{4, 0}, true}, {{8, 0.04}, true}, {{12, 0.08}, true}});
  const double leg = std::sqrt(16.0 + 0.0016);  // each of the last two segments
  // Runs of 4 m and 2 * leg m, each d / v + v / a (longer than v^2 / a = 1 m), and the rotation.
  EXPECT_NEAR(motion(kink, ramp).duration_s, (4.0 + 1.0) + (2.0 * leg + 1.0) + std::atan(0.01) / 0.5, 1e-9);
  // Without the rotation the kink is driven through: one run.
  ramp.rotation_speed = 0.0;
  EXPECT_NEAR(motion(kink, ramp).duration_s, (4.0 + 2.0 * leg) + 1.0, 1e-9);
}

// The same three segments, scheduled: when the tool reaches each waypoint.
TEST(TimeModels, TheTimelineByHandOnThreeSegments) {
  const Path p = makePath({0, 0}, {{{4, 0}, true}, {{13, 0}, true}, {{29, 0}, true}});
  MotionLimits eth;
  eth.speed = 3.0;
  eth.acceleration = 1.0;
  eth.stops = MotionLimits::Stops::Waypoints;
  Timeline t = timeline(p, eth);
  ASSERT_EQ(t.arrive_s.size(), 4u);
  EXPECT_NEAR(t.arrive_s[1], 4.0, 1e-12);
  EXPECT_NEAR(t.arrive_s[2], 4.0 + 6.0, 1e-12);
  EXPECT_NEAR(t.arrive_s[3], 10.0 + 16.0 / 3.0 + 3.0, 1e-12);
  EXPECT_EQ(t.end_s, t.arrive_s[3]);
  EXPECT_EQ(t.wait_s, (std::vector<double>{0, 0, 0}));
  // One run of 29 m: 4 m accelerating from rest (sqrt(2 * 4 / a) = 2 sqrt 2 s, reaching 2 sqrt 2
  // m/s); on to v = 3 m/s in 3 - 2 sqrt 2 s over 0.5 m and 8.5 m at v; 11.5 m at v and 3 s braking.
  eth.stops = MotionLimits::Stops::Turns;
  t = timeline(p, eth);
  EXPECT_NEAR(t.arrive_s[1], 2.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(t.arrive_s[2], 3.0 + 8.5 / 3.0, 1e-12);
  EXPECT_NEAR(t.arrive_s[3], 3.0 + 8.5 / 3.0 + 11.5 / 3.0 + 3.0, 1e-12);
  EXPECT_NEAR(t.end_s, motion(p, eth).duration_s, 1e-12);
}

TEST(TimeModels, StopAngleAndTurnCost) {
  // Heading changes of 20 and 90 degrees: at a stop angle of 30 only the second stops; at 10 both.
  const Point bend{4 + 5 * std::cos(20 * M_PI / 180), 5 * std::sin(20 * M_PI / 180)};
  const Point end{bend.x - 3 * std::sin(20 * M_PI / 180), bend.y + 3 * std::cos(20 * M_PI / 180)};
  const Path p = makePath({0, 0}, {{{4, 0}, true}, {bend, true}, {end, true}});
  MotionLimits m;
  m.speed = 1.0;
  m.acceleration = 1.0;  // v^2 / a = 1 m: every run reaches v; a run of d takes d + 1 s
  EXPECT_NEAR(motion(p, m).duration_s, (9.0 + 1.0) + (3.0 + 1.0), 1e-9);
  m.stop_angle_deg = 10.0;
  EXPECT_NEAR(motion(p, m).duration_s, (4.0 + 1.0) + (5.0 + 1.0) + (3.0 + 1.0), 1e-9);
  m.turn_cost_s = 5.0;
  const Motion mo = motion(p, m);
  ASSERT_TRUE(mo.turn_cost_s.has_value());
  EXPECT_EQ(mo.turns, 2u);
  EXPECT_DOUBLE_EQ(*mo.turn_cost_s, 10.0);
  EXPECT_NEAR(mo.duration_s, 15.0, 1e-9);  // the cost per turn is its own metric, not in duration_s
  bool listed = false;
  for (const NamedMetric& metric : flatten(computeMetrics(rectWall(30, 10), kTool, p, {}, m)))
    listed = listed || (metric.name == "turn_cost_s" && metric.value == 10.0);
  EXPECT_TRUE(listed);
  EXPECT_EQ(m.describe(), "v 1 m/s, a 1 m/s2, stops at turns over 10 degrees, 5 s per turn (turn_cost_s)");
  EXPECT_EQ(MotionLimits{}.describe(), "v 0.3 m/s, a 0.5 m/s2, stops at turns over 30 degrees");
}

}  // namespace
}  // namespace coverbench
