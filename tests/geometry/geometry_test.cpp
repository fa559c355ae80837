// Geometry predicates against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "coverbench/flux_profile.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/region_ops.hpp"

namespace coverbench {
namespace {

// wrapAngle is std::remainder(a, 2 pi) bit for bit (its fast paths are one comparison and one
// exact subtraction): at the edges of each path (+-pi, +-2 pi, +-3 pi, the doubles beside them,
// +-0) and over a million angles spread over ten turns.
TEST(Geometry, WrapAngleIsRemainderBitForBit) {
  auto same = [](double a) {
    const double want = std::remainder(a, 2.0 * M_PI), got = wrapAngle(a);
    return std::signbit(want) == std::signbit(got) && (want == got || (std::isnan(want) && std::isnan(got)));
  };
  std::vector<double> edges{0.0, -0.0, M_PI, -M_PI, 2.0 * M_PI, -2.0 * M_PI, 3.0 * M_PI, -3.0 * M_PI, 1e-300, INFINITY, NAN};
  for (const double e : std::vector<double>(edges))
    for (const double towards : {INFINITY, -INFINITY}) edges.push_back(std::nextafter(e, towards));
  for (const double e : edges) EXPECT_TRUE(same(e)) << e;
  std::uint64_t x = 88172645463325252ull;  // xorshift: the same angles every run
  for (int i = 0; i < 1000000; ++i) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    const double a = (static_cast<double>(x >> 11) / 9007199254740992.0 - 0.5) * 20.0 * M_PI;
    ASSERT_TRUE(same(a)) << a;
  }
}

// A bulge on a chord under kMinArcChord is a straight segment, whichever way the chord lies; on
// a chord of kMinArcChord or more along either axis, it stays.
TEST(Geometry, EffectiveBulgeDropsOnlyChordsTooShortForAnArc) {
  EXPECT_EQ(effectiveBulge({0, 0}, {1e-9, 0}, 0.5), 0.5);
  EXPECT_EQ(effectiveBulge({0, 0}, {0, -1e-9}, 0.5), 0.5);
  EXPECT_EQ(effectiveBulge({0, 0}, {0.9e-9, 0}, 0.5), 0.0);
  EXPECT_EQ(effectiveBulge({0, 0}, {0.8e-9, 0.8e-9}, 0.5), 0.5);  // 1.13e-9 long
  EXPECT_EQ(effectiveBulge({0, 0}, {0.7e-9, 0.7e-9}, 0.5), 0.0);  // 0.99e-9 long
  EXPECT_EQ(effectiveBulge({0, 0}, {1, 1}, 0.5e-12), 0.0);
}

TEST(Geometry, SignedAreaFollowsOrientation) {
  const Ring ccw{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  EXPECT_DOUBLE_EQ(signedArea(ccw), 2.0);
  const Ring cw(ccw.rbegin(), ccw.rend());
  EXPECT_DOUBLE_EQ(signedArea(cw), -2.0);
}

TEST(Geometry, PointSegmentDistance) {
  EXPECT_DOUBLE_EQ(distancePointSegment({1, 1}, {0, 0}, {2, 0}), 1.0);   // above the middle
  EXPECT_DOUBLE_EQ(distancePointSegment({3, 4}, {0, 0}, {0, 0}), 5.0);   // degenerate segment
  EXPECT_DOUBLE_EQ(distancePointSegment({5, 4}, {0, 0}, {2, 0}), 5.0);   // beyond the end: 3-4-5
}

TEST(Geometry, SegmentSegmentDistance) {
  EXPECT_DOUBLE_EQ(distanceSegmentSegment({0, 0}, {2, 2}, {0, 2}, {2, 0}), 0.0);  // crossing
  EXPECT_DOUBLE_EQ(distanceSegmentSegment({0, 0}, {1, 0}, {0, 0.5}, {1, 0.5}), 0.5);  // parallel
  EXPECT_DOUBLE_EQ(distanceSegmentSegment({0, 0}, {1, 0}, {1, 0}, {2, 1}), 0.0);  // touching at an end
  EXPECT_DOUBLE_EQ(distanceSegmentSegment({0, 0}, {1, 0}, {2, 0}, {3, 0}), 1.0);  // collinear, apart
}

TEST(Geometry, SegmentThroughFilledPolygonHasZeroDistance) {
  const Ring square{{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  // Both ends outside, clipping the corner near (2, 2) over 2.8 cm only.
  EXPECT_DOUBLE_EQ(distanceSegmentFilledRing({0, 3.98}, {3.98, 0}, square), 0.0);
  // Passing the corner (1, 2) at distance 0.5 / sqrt(2).
  EXPECT_NEAR(distanceSegmentFilledRing({0, 1.5}, {1.5, 3.0}, square), 0.5 / std::sqrt(2.0), 1e-15);
  // A segment entirely inside.
  EXPECT_DOUBLE_EQ(distanceSegmentFilledRing({1.2, 1.5}, {1.8, 1.5}, square), 0.0);
}

TEST(Geometry, RingSimplicity) {
  EXPECT_TRUE(ringIsSimple({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_FALSE(ringIsSimple({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));  // bow tie
  EXPECT_FALSE(ringIsSimple({{0, 0}, {2, 0}, {1, 0}}));         // folds back, zero area
  EXPECT_FALSE(ringIsSimple({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}));  // vertex on an edge
  EXPECT_FALSE(ringIsSimple({{0, 0}, {2, 0}, {2, 2}, {1, 0}, {1, 2}, {0, 2}}));  // vertex on an edge, not a neighbour's
  EXPECT_FALSE(ringIsSimple({{0, 0}, {2, 0}, {2, 2}, {2, 2}, {0, 2}}));  // a zero-length edge
  EXPECT_FALSE(ringIsSimple({{0, 0}, {1, 1}, {2, 0}, {2, 2}, {1, 1}, {0, 2}}));  // a vertex used twice (figure eight)
  EXPECT_TRUE(ringIsSimple({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}}));  // collinear neighbours going on
  EXPECT_FALSE(ringIsSimple({{0, 0}, {3, 0}, {1, 0}, {1, 2}, {0, 2}}));  // folding back along the last edge
}

/// The definition of a simple ring, edge against edge (what ringIsSimple answered before its sweep):
/// no zero-length edge, non-adjacent edges never meet, adjacent edges do not fold back, an area.
bool simpleByEveryPair(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Point a = ring[i], b = ring[(i + 1) % n];
    if (a == b) return false;
    for (std::size_t j = i + 1; j < n; ++j) {
      const Point c = ring[j], d = ring[(j + 1) % n];
      if (j != i + 1 && !(i == 0 && j == n - 1)) {
        if (segmentsIntersect(a, b, c, d)) return false;
        continue;
      }
      const Point shared = (j == i + 1) ? b : a, p = (j == i + 1) ? a : b, q = (j == i + 1) ? d : c;
      if (cross(shared - p, q - p) == 0.0 && dot(p - shared, q - shared) > 0.0) return false;
    }
  }
  return std::fabs(signedArea(ring)) > 0.0;
}

// Property: the sweep answers as the definition does on 200,000 random rings of 3 to 9 vertices on
// a 4 x 4 grid of integers (touching, collinear and repeated vertices are common there) and on
// 20,000 of 3 to 40 vertices at random doubles, with both answers common.
TEST(Geometry, RingSimplicityBySweepIsTheDefinition) {
  std::uint64_t state = 12345;
  auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 33;
  };
  std::size_t simple = 0, not_simple = 0;
  for (int k = 0; k < 220000; ++k) {
    const bool grid = k < 200000;
    const std::size_t n = grid ? 3 + next() % 7 : 3 + next() % 38;
    Ring ring;
    for (std::size_t i = 0; i < n; ++i) {
      if (grid) {
        ring.push_back({static_cast<double>(next() % 4), static_cast<double>(next() % 4)});
      } else {
        // Around a circle, a little shuffled: simple often, not always.
        const double t = 2 * M_PI * (static_cast<double>(i) + 0.9 * (static_cast<double>(next() % 1000) / 1000.0)) / static_cast<double>(n);
        const double r = 1.0 + static_cast<double>(next() % 1000) / 1000.0;
        ring.push_back({r * std::cos(t), r * std::sin(t)});
      }
    }
    const bool want = simpleByEveryPair(ring);
    ASSERT_EQ(ringIsSimple(ring), want) << "ring " << k;
    (want ? simple : not_simple) += 1;
  }
  EXPECT_GT(simple, 20000u);
  EXPECT_GT(not_simple, 20000u);
}

TEST(RegionOps, OffsetOfSquareHasRoundCorners) {
  const Region square = regionFromRings({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}});
  const Region grown = offsetRegion(square, 0.1, 1e-6);
  // Area of a rounded square: 1 + 4 * 0.1 + pi * 0.01 (chords cut at most 1e-6 off).
  EXPECT_NEAR(area(grown), 1.4 + M_PI * 0.01, 1e-4);
  const Region shrunk = offsetRegion(square, -0.1, 1e-6);
  EXPECT_NEAR(area(shrunk), 0.64, 1e-9);
}

TEST(RegionOps, SubtractMakesHoles) {
  const Region outer = regionFromRings({{{0, 0}, {4, 0}, {4, 4}, {0, 4}}});
  const Region hole = regionFromRings({{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  const Region result = subtract(outer, hole);
  ASSERT_EQ(result.size(), 1u);
  EXPECT_EQ(result[0].holes.size(), 1u);
  EXPECT_NEAR(area(result), 15.0, 1e-9);
}

TEST(RegionOps, SimplifyingKeepsAnIslandInAHole) {
  // A frame 10 x 10 round a 6 x 6 hole, a 2 x 2 island in the hole (an uncovered patch inside a
  // covered band inside an uncovered rim): 100 - 36 + 4. The frame's hole must not take the island.
  const Region frame = subtract(regionFromRings({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}}),
                                regionFromRings({{{2, 2}, {8, 2}, {8, 8}, {2, 8}}}));
  const Region island = regionFromRings({{{4, 4}, {6, 4}, {6, 6}, {4, 6}}});
  const Region both = unite(frame, island);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_NEAR(area(simplifyRegion(both, 0.01)), 68.0, 1e-9);
}

TEST(RegionOps, CircumscribedCircleContainsCircleWithinTolerance) {
  const Ring ring = circumscribedCircle({0, 0}, 1.0, 1e-4);
  for (const Point& p : ring) {
    EXPECT_GE(norm(p), 1.0);
    EXPECT_LE(norm(p), 1.0 + 1e-4);
  }
  for (std::size_t i = 0; i < ring.size(); ++i)  // every edge stays outside the circle
    EXPECT_GE(distancePointSegment({0, 0}, ring[i], ring[(i + 1) % ring.size()]), 1.0 - 1e-12);
}

}  // namespace
}  // namespace coverbench

// Row spacing for an even coat (flux_profile.hpp), against hand-computed sums of profiles.
namespace coverbench {
namespace {

FluxProfile profileOf(FluxProfile::Kind kind, double beta = 0.0, double sigma = 0.0) {
  FluxProfile p;
  p.kind = kind;
  p.beta = beta;
  p.sigma = sigma;
  return p;
}

TEST(EvenSpacing, RippleOfHandSummedProfiles) {
  const FluxProfile uniform = profileOf(FluxProfile::Kind::Uniform);
  // Uniform passes s apart tile the wall: flat; s/2 apart every point has two: flat; 0.75 s apart
  // a point has one pass (0.75 of the mean) or two (1.5): ripple 0.5.
  EXPECT_NEAR(passRipple(uniform, 0.2, 0.2), 0.0, 1e-12);
  EXPECT_NEAR(passRipple(uniform, 0.2, 0.1), 0.0, 1e-12);
  EXPECT_NEAR(passRipple(uniform, 0.2, 0.15), 0.5, 1e-12);
  // beta = 2: f(x) = 3 (1 - x^2 / r^2) / (4 r). Passes r apart: g d = 3/4 (2 - (x^2 + (x - r)^2) / r^2),
  // 0.75 at a pass's centre (ripple 0.25), 1.125 half-way.
  const FluxProfile parabola = profileOf(FluxProfile::Kind::Beta, 2.0);
  EXPECT_NEAR(passRipple(parabola, 0.2, 0.1), 0.25, 2e-3);  // sampled at 512 points, the first 0.1/1024 from the centre
  EXPECT_GT(passRipple(parabola, 0.2, 0.1), 0.24);
  EXPECT_TRUE(std::isnan(passRipple(FluxProfile{}, 0.2, 0.1)));  // no profile: no coat
}

TEST(EvenSpacing, TheWidestSpacingWithinTheRippleIsChosen) {
  // Uniform: no overlap, s itself.
  double ripple = -1.0;
  EXPECT_EQ(evenSpacing(profileOf(FluxProfile::Kind::Uniform), 0.3, 0.05, &ripple), 0.3);
  EXPECT_EQ(ripple, 0.0);
  for (const FluxProfile& p : {profileOf(FluxProfile::Kind::Beta, 2.5), profileOf(FluxProfile::Kind::Beta, 1.5),
                               profileOf(FluxProfile::Kind::Gaussian, 0.0, 0.05)}) {
    for (double tolerance : {0.02, 0.05, 0.1}) {
      const double s = 0.3, d = evenSpacing(p, s, tolerance, &ripple);
      ASSERT_GT(d, s / 10) << toString(p.kind) << " " << tolerance;
      EXPECT_LT(d, s);  // a fan that thins at its edges must overlap
      EXPECT_LE(passRipple(p, s, d), tolerance);
      EXPECT_EQ(ripple, passRipple(p, s, d));
      // Every wider spacing on the scan's grid is not that even.
      for (double wider = s; wider > d + s / 1000; wider -= s / 1000) EXPECT_GT(passRipple(p, s, wider), tolerance) << wider;
    }
  }
  // A ripple no spacing down to s/10 reaches: none.
  EXPECT_EQ(evenSpacing(profileOf(FluxProfile::Kind::Gaussian, 0.0, 0.006), 0.3, 1e-9), 0.0);
  EXPECT_EQ(evenSpacing(FluxProfile{}, 0.3, 0.05), 0.0);
}

}  // namespace
}  // namespace coverbench
