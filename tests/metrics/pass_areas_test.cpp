// The exact pass-count areas (passLevelAreas) against closed forms, adversarial paths (sides along
// sides, paths doubling back, waypoints 1e-12 m apart, tangent circles), and, on many random and
// planned paths, against scanlines a thousand times finer than the tool and the definition
// (passCount) point by point.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

const double kR = 0.1;

void add(Path& p, Point to, bool on);
Path randomPath(std::mt19937& rng);
/// A path through the points with the tool on (repeated points kept, unlike Path::moveTo).
Path onPath(std::vector<Point> points) {
  Path p;
  p.waypoints.push_back(points.front());
  for (std::size_t i = 1; i < points.size(); ++i) add(p, points[i], true);
  return p;
}
void add(Path& p, Point to, bool on) {
  p.waypoints.push_back(to);
  p.tool_on.push_back(on);
  if (!p.bulge.empty()) p.bulge.push_back(0.0);
}
/// Appends the arc around c from the path's last point, turning by phi (radians; positive:
/// counter-clockwise, at most a half turn).
void arc(Path& p, Point c, double phi, bool on) {
  p.bulge.resize(p.tool_on.size(), 0.0);
  p.waypoints.push_back(c + rotate(p.waypoints.back() - c, phi));
  p.tool_on.push_back(on);
  p.bulge.push_back(std::tan(phi / 4));
}
/// The same path walked backwards (arcs turning the other way).
Path reversedPath(const Path& p) {
  Path r;
  r.waypoints.assign(p.waypoints.rbegin(), p.waypoints.rend());
  r.tool_on.assign(p.tool_on.rbegin(), p.tool_on.rend());
  for (auto b = p.bulge.rbegin(); b != p.bulge.rend(); ++b) r.bulge.push_back(-*b);
  return r;
}

double capsule(double length) { return 2 * kR * length + M_PI * kR * kR; }
double lens(double d) { return 2 * kR * kR * std::acos(d / (2 * kR)) - d / 2 * std::sqrt(4 * kR * kR - d * d); }

// Rounding only: terms of about 1 m^2 summed a few hundred times.
constexpr double kExact = 1e-12;

TEST(PassAreas, OneCapsule) {
  const std::vector<double> a = passLevelAreas(onPath({{0.5, 1.0}, {3.5, 1.0}}), kR, 4);
  EXPECT_NEAR(a[0], capsule(3.0), kExact);
  EXPECT_NEAR(a[1], 0.0, kExact);
}

TEST(PassAreas, SlantedCapsuleAndDisk) {
  EXPECT_NEAR(passLevelAreas(onPath({{0.1, 0.2}, {1.3, 2.9}}), kR, 2)[0], capsule(std::hypot(1.2, 2.7)), kExact);
  EXPECT_NEAR(passLevelAreas(onPath({{0.1, 0.2}, {0.1, 0.2}}), kR, 2)[0], M_PI * kR * kR, kExact);
}

TEST(PassAreas, TwoParallelPassesCloserThanTheToolWidth) {
  Path p = onPath({{0.5, 1.0}, {3.5, 1.0}});
  add(p, {0.5, 1.1}, false);
  add(p, {3.5, 1.1}, true);
  const double both = (2 * kR - 0.1) * 3.0 + lens(0.1);
  const std::vector<double> a = passLevelAreas(p, kR, 3);
  EXPECT_NEAR(a[0], 2 * capsule(3.0) - both, kExact);
  EXPECT_NEAR(a[1], both, kExact);
  EXPECT_NEAR(a[2], 0.0, kExact);
}

TEST(PassAreas, PassesExactlyOneToolWidthApartTouchWithoutOverlap) {
  // Sides along sides facing each other: no overlap and no gap, in either order, at every height.
  for (double y : {0.0, 1.0, 0.3, 12345.678}) {
    Path p = onPath({{0.5, y}, {3.5, y}});
    add(p, {3.5, y + 2 * kR}, false);
    add(p, {0.5, y + 2 * kR}, true);
    const std::vector<double> a = passLevelAreas(p, kR, 2);
    EXPECT_NEAR(a[0], 2 * capsule(3.0) - lens(2 * kR), 1e-9) << y;  // the end disks touch: lens 0
    EXPECT_NEAR(a[1], 0.0, 1e-9) << y;
  }
}

TEST(PassAreas, ThreeTimesAlongOneSegment) {
  // A -> B -> A -> B: three capsules minus continuation disks at B and at A.
  const std::vector<double> a = passLevelAreas(onPath({{1, 1}, {2, 1}, {1, 1}, {2, 1}}), kR, 4);
  EXPECT_NEAR(a[0], capsule(1.0), kExact);
  EXPECT_NEAR(a[1], capsule(1.0), kExact);  // every point at least twice
  EXPECT_NEAR(a[2], capsule(1.0) - 2 * M_PI * kR * kR, kExact);  // three times outside the two disks
  EXPECT_NEAR(a[3], 0.0, kExact);
}

TEST(PassAreas, ThePassCountPicturesHoldEachLevel) {
  // The pictures' layers of A -> B -> A -> B: at least 2 passes everywhere in the capsule, at
  // least 3 outside the two continuation disks, never 4; each within the scanlines' error (h per
  // metre of horizontal boundary: the capsule's two sides, the disks' outlines).
  const Path p = onPath({{1, 1}, {2, 1}, {1, 1}, {2, 1}});
  const double h = kR / 200;
  auto areaOf = [&](int k) {
    double sum = 0.0;
    for (const PolygonWithHoles& poly : passRegion(p, kR, h, k)) sum += std::fabs(signedArea(poly.outer));
    return sum;
  };
  const double error = h * (2.0 + 2 * 2 * M_PI * kR);
  EXPECT_NEAR(areaOf(2), capsule(1.0), error);
  EXPECT_NEAR(areaOf(3), capsule(1.0) - 2 * M_PI * kR * kR, error);
  EXPECT_EQ(areaOf(4), 0.0);
  EXPECT_EQ(areaOf(2), [&] {
    double sum = 0.0;
    for (const PolygonWithHoles& poly : overlapRegion(p, kR, h)) sum += std::fabs(signedArea(poly.outer));
    return sum;
  }());
}

TEST(PassAreasProperties, ThePassCountPicturesHaveTheScanlinesLevels) {
  // On random paths, each level's picture has the area the same scanlines measure for it.
  std::mt19937 rng(20261127);
  for (int trial = 0; trial < 200; ++trial) {
    const Path p = randomPath(rng);
    const double h = kR / 8;
    const Passes s = passesOnScanlines(p, kR, h, 4);
    for (int k = 2; k <= 4; ++k) {
      double share = 0.0, sum = 0.0;
      for (int j = k - 1; j < 4; ++j) share += s.histogram[static_cast<std::size_t>(j)];
      for (const PolygonWithHoles& poly : passRegion(p, kR, h, k)) sum += std::fabs(signedArea(poly.outer));
      EXPECT_NEAR(sum, share * s.swept_area, 1e-9) << "trial " << trial << ", at least " << k << " passes";
    }
  }
}

TEST(PassAreas, SameSegmentInTwoRunsCountsTwice) {
  Path p = onPath({{1, 1}, {2, 1}});
  add(p, {1, 1}, false);
  add(p, {2, 1}, true);
  const std::vector<double> a = passLevelAreas(p, kR, 3);
  EXPECT_NEAR(a[0], capsule(1.0), kExact);
  EXPECT_NEAR(a[1], capsule(1.0), kExact);
  EXPECT_NEAR(a[2], 0.0, kExact);
}

TEST(PassAreas, LTurnCornerTwice) {
  // Inside the corner, within r of both legs but beyond r of the corner: a square r x r minus a
  // quarter disk (the same figure as Metrics.LTurnHasACornerCoveredTwice, now exactly).
  const std::vector<double> a = passLevelAreas(onPath({{1, 1}, {3, 1}, {3, 3}}), kR, 3);
  EXPECT_NEAR(a[1], kR * kR * (1 - M_PI / 4), kExact);
  EXPECT_NEAR(a[0], 0.8 + M_PI * kR * kR - kR * kR + M_PI * kR * kR / 4, kExact);
  EXPECT_NEAR(a[2], 0.0, kExact);
}

TEST(PassAreas, WaypointsCloserThanANanometreAreOne) {
  // Two runs ending 1e-12 m apart: their end circles are one circle (no crossings rounding cannot
  // place), and the areas are those of the exact coincidence to far better than 1e-9 m^2.
  Path p = onPath({{1, 1}, {2, 1}});
  add(p, {2 + 1e-12, 1 - 1e-12}, false);
  add(p, {2 + 1e-12, 2}, true);
  Path q = onPath({{1, 1}, {2, 1}});
  add(q, {2, 1}, false);
  add(q, {2, 2}, true);
  const std::vector<double> a = passLevelAreas(p, kR, 3), b = passLevelAreas(q, kR, 3);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-10) << k;
  // The two capsules share the end disk, three quarters of it beyond the inner corner's square.
  EXPECT_NEAR(b[1], kR * kR + 3 * M_PI * kR * kR / 4, kExact);
}

TEST(PassAreas, TangentDisksAndInvariance) {
  // Disks touching at one point, translated far and rotated: the same areas.
  const double d = 2 * kR;
  for (const Point shift : {Point{0, 0}, Point{1000.25, -3000.5}}) {
    Path p = onPath({shift + Point{0, 0}, shift + Point{1, 0}});
    add(p, shift + Point{1 + d, 0}, false);
    add(p, shift + Point{1 + d, 0}, true);
    const std::vector<double> a = passLevelAreas(p, kR, 2);
    EXPECT_NEAR(a[0], capsule(1.0) + M_PI * kR * kR, 1e-9);
    EXPECT_NEAR(a[1], 0.0, 1e-9);
  }
}

// Arcs (Path::bulge) are shapes of their own: the set within r of an arc of radius R >= r turning
// by phi is a ring sector of area 2 |phi| R r plus two half disks.
double arcCapsule(double radius, double phi) { return 2 * std::fabs(phi) * radius * kR + M_PI * kR * kR; }

TEST(PassAreas, OneArcPass) {
  for (const double phi : {M_PI / 2, -M_PI / 2, M_PI, -M_PI, 0.2, 2.5})
    for (const double radius : {0.3, kR, 2.0}) {
      Path p = onPath({{1 + radius, 1}});
      arc(p, {1, 1}, phi, true);
      const std::vector<double> a = passLevelAreas(p, kR, 2);
      EXPECT_NEAR(a[0], arcCapsule(radius, phi), kExact) << "phi " << phi << ", R " << radius;
      EXPECT_NEAR(a[1], 0.0, kExact) << "phi " << phi << ", R " << radius;
    }
}

TEST(PassAreas, ArcTighterThanTheTool) {
  // R < r: the sector of radius R + r over the arc's angles and the disks around its ends, which
  // overlap beyond the centre. A half turn: half a disk of radius R + r, and the other halves of
  // the two end disks, less half their lens. Twice: the tool leaves the half of the lens beyond
  // the centre and comes back to it, but for the points within r - R of the centre, which it never leaves.
  for (const double radius : {0.05, 0.01, 0.099}) {
    for (const double phi : {M_PI, -M_PI}) {
      Path p = onPath({{1 + radius, 1}});
      arc(p, {1, 1}, phi, true);
      const std::vector<double> a = passLevelAreas(p, kR, 3);
      const double expected = M_PI * (radius + kR) * (radius + kR) / 2 + M_PI * kR * kR - lens(2 * radius) / 2;
      EXPECT_NEAR(a[0], expected, kExact) << "R " << radius;
      EXPECT_NEAR(a[1], lens(2 * radius) / 2 - M_PI * (kR - radius) * (kR - radius) / 2, kExact) << "R " << radius;
      EXPECT_NEAR(a[2], 0.0, kExact) << "R " << radius;
    }
  }
}

TEST(PassAreas, ArcThenItsTangentThenBackAlongTheArc) {
  // A quarter turn of radius 0.3 continued by its tangent: one pass, no overlap at the joint.
  Path p = onPath({{1.3, 1}});
  arc(p, {1, 1}, M_PI / 2, true);
  add(p, {0, 1.3}, true);
  std::vector<double> a = passLevelAreas(p, kR, 3);
  EXPECT_NEAR(a[0], arcCapsule(0.3, M_PI / 2) + 2 * kR * 1.0, kExact);
  EXPECT_NEAR(a[1], 0.0, kExact);
  // Back along the line and the arc: everything twice but the disk where the path turns back.
  add(p, {1, 1.3}, true);
  arc(p, {1, 1}, -M_PI / 2, true);
  a = passLevelAreas(p, kR, 3);
  EXPECT_NEAR(a[0], arcCapsule(0.3, M_PI / 2) + 2 * kR * 1.0, kExact);
  EXPECT_NEAR(a[1], arcCapsule(0.3, M_PI / 2) + 2 * kR * 1.0 - M_PI * kR * kR, kExact);
  EXPECT_NEAR(a[2], 0.0, kExact);
}

TEST(PassAreas, ConcentricArcsOneToolWidthApartTouchWithoutOverlap) {
  // Rings of radius 0.3 and 0.5: the first's outer circle is the second's inner one.
  Path p = onPath({{1.3, 1}});
  arc(p, {1, 1}, M_PI / 2, true);
  add(p, {1, 1.5}, false);
  arc(p, {1, 1}, -M_PI / 2, true);
  std::vector<double> a = passLevelAreas(p, kR, 2);
  EXPECT_NEAR(a[0], arcCapsule(0.3, M_PI / 2) + arcCapsule(0.5, M_PI / 2), kExact);
  EXPECT_NEAR(a[1], 0.0, kExact);
  // The same arc again in another run: everything twice.
  add(p, {1.3, 1}, false);
  arc(p, {1, 1}, M_PI / 2, true);
  a = passLevelAreas(p, kR, 3);
  EXPECT_NEAR(a[0], arcCapsule(0.3, M_PI / 2) + arcCapsule(0.5, M_PI / 2), kExact);
  EXPECT_NEAR(a[1], arcCapsule(0.3, M_PI / 2), kExact);
  EXPECT_NEAR(a[2], 0.0, kExact);
}

TEST(PassAreas, NoToolOnNothing) {
  Path p = onPath({{0, 0}, {1, 0}});
  p.tool_on[0] = false;
  EXPECT_EQ(passLevelAreas(p, kR, 2), std::vector<double>(2, 0.0));
}

/// Random paths of 2-14 segments in a 1 m square: slanted, axis-aligned, one and half a tool
/// width up, doubling back, 1 mm steps, repeated points, tool on and off.
Path randomPath(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Path p;
  p.waypoints.push_back({u(rng), u(rng)});
  const int n = 2 + static_cast<int>(rng() % 13);
  for (int i = 0; i < n; ++i) {
    const Point last = p.waypoints.back();
    Point next{u(rng), u(rng)};
    switch (rng() % 8) {
      case 0: next = last + Point{0.3, 0.0}; break;
      case 1: next = last + Point{0.0, 0.2}; break;  // a tool width: rows that touch
      case 2: if (p.waypoints.size() > 1) next = p.waypoints[p.waypoints.size() - 2]; break;
      case 3: next = last + Point{1e-3 * u(rng), 1e-3 * u(rng)}; break;
      case 4: next = last; break;
      case 5: next = last + Point{0.0, 0.1}; break;
      default: break;
    }
    p.waypoints.push_back(next);
    p.tool_on.push_back(rng() % 4 != 0);
  }
  return p;
}

TEST(PassAreasProperties, AgreeWithVeryFineScanlinesOnRandomPaths) {
  std::mt19937 rng(20261124);
  for (int trial = 0; trial < 400; ++trial) {
    const Path p = randomPath(rng);
    const std::vector<double> a = passLevelAreas(p, kR, 4);
    const double h = kR / 2000;
    const Passes s = passesOnScanlines(p, kR, h, 4);
    // The scanlines' own error: each line stands for a band h high, which a horizontal edge can
    // cut anywhere, so up to h per metre of horizontal boundary (the capsules' sides, at most twice
    // the tool-on length, and their ends and joints, at most 2r each).
    const double scan_error = h * (2 * pathLengths(p).cover + 2 * kR * static_cast<double>(p.tool_on.size()) + 2 * kR);
    // Levels from the scanline histogram: |{>= k}| = |S| * (h_k + ... + h_4).
    for (std::size_t k = 0; k < 4; ++k) {
      double share = 0.0;
      for (std::size_t j = k; j < 4; ++j) share += s.histogram[j];
      EXPECT_NEAR(a[k], share * s.swept_area, scan_error) << "trial " << trial << ", level " << k + 1;
    }
  }
}

/// Random paths with arcs: quarter and half turns and small ones, of radii above, at and below r
/// (down to a hundredth of it), tangents after them, concentric arcs one tool width apart, arcs
/// walked back, tool on and off.
Path randomArcPath(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Path p;
  p.waypoints.push_back({u(rng), u(rng)});
  const int n = 2 + static_cast<int>(rng() % 10);
  Point centre{u(rng), u(rng)};
  for (int i = 0; i < n; ++i) {
    const Point last = p.waypoints.back();
    const bool on = rng() % 4 != 0;
    const double phi = (rng() % 2 ? 1.0 : -1.0) * std::array<double, 4>{M_PI / 2, M_PI, 0.3, 2.0 * u(rng)}[rng() % 4];
    switch (rng() % 7) {
      case 0: {  // a new centre at a radius of 0.01 to 3 r, or exactly r
        static constexpr double kRadii[] = {0.01, 0.05, 0.1, 0.1, 0.15, 0.3};
        const double radius = kRadii[rng() % 6];
        const double angle = 2 * M_PI * u(rng);
        centre = last - Point{std::cos(angle), std::sin(angle)} * radius;
        arc(p, centre, phi, on);
        break;
      }
      case 1:  // around the last centre
        arc(p, centre, phi, on);
        break;
      case 2: {  // one tool width farther out, around the same centre
        const Point out = last - centre;
        add(p, centre + out * ((norm(out) + 2 * kR) / norm(out)), false);
        arc(p, centre, phi, on);
        break;
      }
      case 3: {  // the tangent at the end of the last arc
        const Point radial = last - centre;
        const double turn = !p.bulge.empty() && p.bulge.back() < 0 ? -1.0 : 1.0;
        add(p, last + Point{-radial.y, radial.x} * (turn * 0.3 / norm(radial)), on);
        break;
      }
      case 4:  // back along the last segment
        if (p.waypoints.size() > 1) {
          const double back = p.bulge.empty() ? 0.0 : -p.bulge.back();
          p.bulge.resize(p.tool_on.size(), 0.0);
          p.waypoints.push_back(p.waypoints[p.waypoints.size() - 2]);
          p.tool_on.push_back(on);
          p.bulge.push_back(back);
        }
        break;
      default:
        add(p, {u(rng), u(rng)}, on);
        break;
    }
  }
  return p;
}

/// How far a level's boundary reaches at most: the capsules' sides (twice the tool-on length, plus
/// r times the arcs' angles, at most pi r each) and their ends.
double boundaryBound(const Path& p) {
  return 2 * pathLengths(p).cover + 3 * M_PI * kR * static_cast<double>(p.segments() + 1);
}

TEST(PassAreasProperties, ArcsAgreeWithFineChords) {
  // The same paths with every arc cut into chords within 2e-6 m of it: each level's boundary moves
  // by at most that, so its area by at most 2e-6 m times the boundary's length (measured: under
  // a tenth of it). Chords much finer are no better reference: their nearly parallel sides cross
  // where rounding cannot place them.
  std::mt19937 rng(63);
  const double sagitta = 2e-6;
  for (int trial = 0; trial < 200; ++trial) {
    const Path p = randomArcPath(rng);
    const std::vector<double> a = passLevelAreas(p, kR, 4), b = passLevelAreas(chordalPath(p, sagitta), kR, 4);
    for (std::size_t k = 0; k < 4; ++k)
      EXPECT_NEAR(a[k], b[k], sagitta * boundaryBound(p)) << "trial " << trial << ", level " << k + 1;
  }
}

TEST(PassAreasProperties, PlannedRoundCornersAgreeWithFineChords) {
  // Every planner's path (round corners as arcs) on a wall with obstacles, at the tool's width.
  const Wall wall = loadWallFile(test::sourcePath("datasets/canonical/seed_5x5_3obs.json"));
  const ToolParams tool{2 * kR, 0.02};
  const double sagitta = 2e-6;
  int with_arcs = 0;
  for (const std::string& planner : test::plannerNames()) {
    const PlanResult r = test::planWith(planner, wall, tool);
    ASSERT_TRUE(r.hasPath()) << planner;
    with_arcs += r.path.hasArcs();
    const std::vector<double> a = passLevelAreas(r.path, kR, 4), b = passLevelAreas(chordalPath(r.path, sagitta), kR, 4);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(a[k], b[k], sagitta * boundaryBound(r.path)) << planner << ", level " << k + 1;
  }
  EXPECT_GE(with_arcs, 3);
}

TEST(PassAreasProperties, ArcsReversedAndMovedHaveTheSameAreas) {
  // An arc's centre comes from its ends and bulge, rounded anew when reversed or moved: the areas
  // agree within 1e-11 m^2 (measured: 1e-12 on 3000 paths).
  std::mt19937 rng(64);
  for (int trial = 0; trial < 1000; ++trial) {
    const Path p = randomArcPath(rng);
    Path moved = p;
    for (Point& w : moved.waypoints) w = w + Point{1000.5, -250.25};
    const std::vector<double> a = passLevelAreas(p, kR, 4), b = passLevelAreas(reversedPath(p), kR, 4),
                              c = passLevelAreas(moved, kR, 4);
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_NEAR(a[k], b[k], 1e-11) << "trial " << trial << ", level " << k + 1;
      EXPECT_NEAR(a[k], c[k], 1e-11) << "trial " << trial << ", level " << k + 1;
    }
  }
}

TEST(PassAreasProperties, ReversedAndMovedPathsHaveTheSameAreas) {
  // The same passes walked backwards, or 1 km away: the crossings are computed anew from other
  // roundings, the sides along sides and the touching circles meet in the other order.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    const Path p = randomPath(rng);
    Path reversed, moved = p;
    reversed.waypoints.assign(p.waypoints.rbegin(), p.waypoints.rend());
    reversed.tool_on.assign(p.tool_on.rbegin(), p.tool_on.rend());
    for (Point& w : moved.waypoints) w = w + Point{1000.5, -250.25};
    const std::vector<double> a = passLevelAreas(p, kR, 4), b = passLevelAreas(reversed, kR, 4),
                              c = passLevelAreas(moved, kR, 4);
    // Nested sets: no negative area, no level larger than the one below (no share of |S| below 0).
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_GE(a[k], 0.0) << "trial " << trial;
      if (k > 0) { EXPECT_LE(a[k], a[k - 1]) << "trial " << trial; }
    }
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_NEAR(a[k], b[k], 1e-12) << "trial " << trial << ", level " << k + 1;
      EXPECT_NEAR(a[k], c[k], 1e-12) << "trial " << trial << ", level " << k + 1;
    }
  }
}

TEST(PassAreasProperties, LevelsFollowTheDefinitionPointByPoint) {
  // On a grid of points, the share with passCount >= k, times the box, approaches |{>= k}|.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 30; ++trial) {
    const Path p = randomPath(rng);
    const std::vector<double> a = passLevelAreas(p, kR, 3);
    const Box box = boundingBox(p.waypoints);
    const int n = 300;
    const double cell_x = (box.width() + 2 * kR) / n, cell_y = (box.height() + 2 * kR) / n;
    std::vector<double> grid(3, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const Point q{box.min_x - kR + (i + 0.5) * cell_x, box.min_y - kR + (j + 0.5) * cell_y};
        const int c = passCount(p, kR, q);
        for (int k = 0; k < 3; ++k) grid[static_cast<std::size_t>(k)] += c > k ? cell_x * cell_y : 0.0;
      }
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(a[k], grid[k], 0.004 + 0.01 * a[k]) << "trial " << trial << ", level " << k + 1;
  }
}

}  // namespace
}  // namespace coverbench
