// Exact areas of the pass-count level sets {q : passes(q) >= k}, by Green's theorem on the
// boundary of the arrangement of the tool-on capsules (+1) and the continuation disks (-1).
//
// A continuation disk lies in both capsules it joins, so the count is also the number of shapes
// containing q, a shape being a tool-on capsule minus the continuation disk at its start (if any):
// one shape per segment, half as many as capsules and disks. Every boundary of the arrangement
// lies on a capsule's straight side or on a circle: of radius r around a waypoint, or, for a
// segment that is an arc (Path::bulge) of radius R around c, of radius R + r or R - r around c
// (arcs are shapes of their own, not chords). Each side and
// each circle is cut where the other shapes' boundaries cross it; on each piece, the pass count
// just left and just right of it is constant, so the piece bounds the level sets whose level
// lies between the two counts, and adds its line integral
// 1/2 (x dy - y dx) to their areas (a straight piece exactly, an arc in closed form). No chords,
// no scanlines: the error is floating-point rounding, plus the three rules below (each moves a
// boundary by at most about kSnap; tests/metrics/pass_areas_test.cpp finds reversed and translated random
// paths within 1e-12 m^2 of each other).
//
// - Waypoints closer than kSnap are one point (otherwise two almost equal circles would cross at
//   points rounding cannot place); so are arcs' centres (and a centre and a waypoint), and circles
//   around one point whose radii differ by at most kSnap are one circle (concentric passes one
//   tool width apart: one's outer circle is the next one's inner circle, walked once with both as
//   its owners, which gives arcs along arcs the rule of sides along sides below). An arc whose
//   radius is under 10 kSnap, or whose sagitta is at most kSnap, is taken as its chord.
// - A line or circle within kSnap of touching a circle touches it at one point (lineCircle).
// - A side running along another capsule's side (closer than kSnap, parallel) is decided by a
//   rule, not by rounding: along sides facing the same way, the lower-numbered capsule counts as
//   containing the piece of the higher-numbered one (so the two together bound two levels, once
//   each); along sides facing each other, neither contains the other's piece (their integrals
//   cancel: no boundary between two shapes that touch).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

// Boost 1.74's R-tree includes a header Boost itself has deprecated (a #pragma message per build).
#define BOOST_ALLOW_DEPRECATED_HEADERS
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/iterator/function_output_iterator.hpp>

#include "coverbench/metrics.hpp"

namespace coverbench {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;

constexpr double kSnap = 1e-9;  ///< m
constexpr double kTwoPi = 2.0 * M_PI;

/// a into [0, 2 pi): the angles here lie within a few turns of it.
double wrapAngle(double a) {
  if (!(std::fabs(a) < 8.0 * kTwoPi)) return std::fmod(std::fmod(a, kTwoPi) + kTwoPi, kTwoPi);
  while (a < 0.0) a += kTwoPi;
  while (a >= kTwoPi) a -= kTwoPi;
  return a;
}

/// A radius and the band around it within which a line or circle touches the circle (kSnap).
struct Round {
  double rho = 0.0, rho2 = 0.0, in2 = 0.0, out2 = 0.0;
};
Round roundOf(double rho) { return {rho, rho * rho, (rho - kSnap) * (rho - kSnap), (rho + kSnap) * (rho + kSnap)}; }

/// A shape of the arrangement: the capsule of radius r around [a, b], minus the disk of radius r
/// around a if `bite` (the segment continues a tool-on segment). A capsule with a == b is a disk.
/// For an arc segment (`arc`), the capsule is the set within r of the arc of radius R around c:
/// the ring sector between the circles R - r and R + r over the arc's angles (the whole sector of
/// radius R + r when R <= r), and the disks around a and b.
struct Shape {
  Point a, b;
  bool bite = false;
  bool arc = false;
  Point d{0.0, 0.0};    ///< b - a
  double inv_dd = 0.0;  ///< 1 / |d|^2 (0 for a disk)
  Point n{0.0, 0.0};    ///< the left normal, of length r
  // An arc: its centre, radius, the unit vectors from c at the two ends of its angles taken
  // counter-clockwise (lo to hi, at most a half turn), and its outer and inner circles (as walked:
  // radii within kSnap of another circle's around the same centre are that circle's).
  Point c{0.0, 0.0};
  double radius = 0.0;
  Point lo{1.0, 0.0}, hi{1.0, 0.0};
  Round outer, inner;  ///< radii R + r and |R - r|
  bool has_inner = false;  ///< |R - r| > kSnap
  bool twice = false;      ///< the region a tight arc passes twice (LevelAreas::addArc), not the arc
  static Shape of(Point a, Point b, bool bite) {
    Shape s;
    s.a = a, s.b = b, s.bite = bite;
    return s;
  }
  bool isDisk() const { return !arc && a == b; }
  bool isSegment() const { return !arc && !(a == b); }
  /// Whether x (relative to c) lies in the arc's angles.
  bool inSpan(Point x) const { return cross(lo, x) >= 0.0 && cross(x, hi) >= 0.0; }
};

/// Part of a circle that lies on a shape's boundary: angles [start, start + span) around the
/// centre (span 2 pi for a whole disk, pi for a capsule's cap or bite), with the shape inside the
/// circle there (`inside`, a cap or a disk) or outside it (a bite).
struct Owner {
  std::size_t shape;
  double start, span;
  bool inside;
  Point from{1.0, 0.0};  ///< the unit vector at angle `start`
  Point to{-1.0, 0.0};   ///< the unit vector at angle `start + span`
  bool covers(double angle) const { return span >= kTwoPi || wrapAngle(angle - start) < span; }
};

struct Circle {
  Point centre;
  Round round;
  std::vector<Owner> owners;
};

/// For each point, the earliest point that was kept and lies within kSnap of it in x and in y
/// (itself if there is none: then it is kept). Found among the points sorted by x, those within kSnap in x.
std::vector<std::uint32_t> snapToEarlier(const std::vector<Point>& points) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> by_x(n);
  for (std::uint32_t k = 0; k < n; ++k) by_x[k] = k;
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t u, std::uint32_t v) {
    return points[u].x < points[v].x || (points[u].x == points[v].x && u < v);
  });
  std::vector<std::uint32_t> rank(n), kept(n);  // rank in by_x; the point each one became
  for (std::uint32_t k = 0; k < n; ++k) rank[by_x[k]] = k;
  for (std::uint32_t k = 0; k < n; ++k) {
    const Point p = points[k];
    kept[k] = k;
    auto consider = [&](std::uint32_t m) {
      if (m < k && kept[m] == m && m < kept[k] && std::fabs(points[m].y - p.y) <= kSnap) kept[k] = m;
    };
    for (std::uint32_t r = rank[k]; r-- > 0 && p.x - points[by_x[r]].x <= kSnap;) consider(by_x[r]);
    for (std::uint32_t r = rank[k] + 1; r < n && points[by_x[r]].x - p.x <= kSnap; ++r) consider(by_x[r]);
  }
  return kept;
}

class LevelAreas {
 public:
  LevelAreas(const Path& path, double radius, std::size_t levels) : r_(radius), areas_(levels, 0.0) {
    build(path);
  }

  std::vector<double> compute() {
    if (shapes_.empty() || r_ <= 0.0) return areas_;
    std::vector<std::pair<BBox, std::uint32_t>> boxes;
    boxes.reserve(shapes_.size());
    boxes_.reserve(shapes_.size());
    for (std::uint32_t k = 0; k < shapes_.size(); ++k) {
      const Shape& s = shapes_[k];
      Box axis;  // the box of the segment or arc
      axis.add(s.a), axis.add(s.b);
      if (s.arc)
        for (const Point e : {Point{1.0, 0.0}, Point{0.0, 1.0}, Point{-1.0, 0.0}, Point{0.0, -1.0}})
          if (s.inSpan(e)) axis.add(s.c + e * s.radius);
      boxes_.push_back({axis.min_x - r_, axis.min_y - r_, axis.max_x + r_, axis.max_y + r_});
      boxes.push_back({BBox(BPoint(boxes_[k].min_x, boxes_[k].min_y), BPoint(boxes_[k].max_x, boxes_[k].max_y)), k});
    }
    index_ = Index(boxes.begin(), boxes.end());
    for (Shape& s : shapes_)
      if (s.isSegment()) {
        s.d = s.b - s.a;
        s.inv_dd = 1.0 / dot(s.d, s.d);
        const double len = std::sqrt(dot(s.d, s.d));
        s.n = {-s.d.y / len * r_, s.d.x / len * r_};
      }
    // One query per group of consecutive shapes: a shape's box holds both its sides and the whole
    // circles around its ends, so the shapes near any of them are among those found around the
    // group's box; each element keeps those near its own box. A group is shapes whose boxes
    // together are at most r wider and taller than the first's (the millimetre steps of a rounded
    // turn: one query instead of dozens). A circle is walked with the first shape it bounds (circles_
    // is in that order); a part of it outside the group's box (an arc's circle that a later arc
    // shares) finds its shapes with a query of its own.
    constexpr std::size_t kMaxGroup = 32;
    std::size_t next_circle = 0, group_end = 0;
    for (std::size_t k = 0; k < shapes_.size(); ++k) {
      if (k == group_end) {
        Box group = boxes_[k];
        const double max_w = group.width() + r_, max_h = group.height() + r_;
        for (group_end = k + 1; group_end < shapes_.size() && group_end - k < kMaxGroup; ++group_end) {
          Box grown = group;
          grown.add({boxes_[group_end].min_x, boxes_[group_end].min_y});
          grown.add({boxes_[group_end].max_x, boxes_[group_end].max_y});
          if (grown.width() > max_w || grown.height() > max_h) break;
          group = grown;
        }
        group_ = group;
        around_.clear();
        index_.query(bgi::intersects(BBox(BPoint(group.min_x, group.min_y), BPoint(group.max_x, group.max_y))),
                     boost::make_function_output_iterator([&](const auto& found) { around_.push_back(found.second); }));
        around_boxes_.clear();
        for (const std::uint32_t j : around_) around_boxes_.push_back(boxes_[j]);  // nearBox scans these per element
      }
      if (shapes_[k].isSegment()) {
        const Point n = shapes_[k].n;
        // Oriented with the capsule on the left: back along the left side, forward along the right.
        side(k, shapes_[k].b + n, shapes_[k].a + n);
        side(k, shapes_[k].a - n, shapes_[k].b - n);
      }
      for (; next_circle < circles_.size() && circles_[next_circle].owners.front().shape == k; ++next_circle)
        circle(circles_[next_circle]);
    }
    return areas_;
  }

 private:
  using Index = bgi::rtree<std::pair<BBox, std::uint32_t>, bgi::quadratic<16>>;

  void build(const Path& path) {
    // Tool-on waypoints, snapped: a point within kSnap (in x and in y) of an earlier one that was
    // kept becomes the earliest such.
    const std::size_t n = path.waypoints.size();
    auto used = [&](std::size_t k) { return (k < path.tool_on.size() && path.tool_on[k]) || (k > 0 && path.tool_on[k - 1]); };
    std::vector<Point> points;
    std::vector<std::uint32_t> id(n, UINT32_MAX);  // a used waypoint's index in `points`
    for (std::size_t k = 0; k < n; ++k)
      if (used(k)) id[k] = static_cast<std::uint32_t>(points.size()), points.push_back(path.waypoints[k]);
    if (points.empty()) return;
    std::vector<std::uint32_t> kept = snapToEarlier(points);
    Box extent;
    for (const std::uint32_t k : kept) extent.add(points[k]);
    // Integrals about the path's centre keep the terms (and their rounding) small.
    origin_ = {(extent.min_x + extent.max_x) / 2, (extent.min_y + extent.max_y) / 2};
    auto at = [&](std::size_t waypoint) { return points[kept[id[waypoint]]] - origin_; };
    // The arcs' centres, from their snapped ends, snapped in turn to the waypoints and each other
    // (their ids follow the waypoints': the waypoints' snapping is the same again).
    std::vector<std::uint32_t> centre_id(path.tool_on.size(), UINT32_MAX);
    std::vector<Point> centres;
    for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
      const double bulge = path.bulgeOf(i);
      if (!path.tool_on[i] || bulge == 0.0 || at(i) == at(i + 1)) continue;
      const ArcGeometry g = arcGeometry(at(i), at(i + 1), bulge);
      if (g.radius < 10.0 * kSnap || g.radius * (1.0 - std::cos(g.sweep / 2)) <= kSnap) continue;  // its chord
      centre_id[i] = static_cast<std::uint32_t>(points.size() + centres.size());
      centres.push_back(g.centre + origin_);
    }
    if (!centres.empty()) {
      points.insert(points.end(), centres.begin(), centres.end());
      kept = snapToEarlier(points);
    }
    circles_at_.assign(points.size(), {});
    shapes_.reserve(path.tool_on.size() + centres.size());
    circles_.reserve(points.size() + 2 * centres.size());
    // The circle of radius rho around point `p` (an id), made on first use; `o` bounds part of it.
    auto addOwner = [&](std::uint32_t p, double rho, Owner o) {
      const std::uint32_t centre = kept[p];
      for (const std::uint32_t c : circles_at_[centre])
        if (std::fabs(circles_[c].round.rho - rho) <= kSnap) return circles_[c].owners.push_back(o), c;
      const auto c = static_cast<std::uint32_t>(circles_.size());
      circles_.push_back({points[centre] - origin_, roundOf(rho), {o}});
      circles_at_[centre].push_back(c);
      return c;
    };
    for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
      if (!path.tool_on[i]) continue;
      const Point a = at(i), b = at(i + 1);
      const bool bite = i > 0 && path.tool_on[i - 1];
      const std::size_t k = shapes_.size();
      const std::uint32_t ia = kept[id[i]], ib = kept[id[i + 1]];
      if (centre_id[i] != UINT32_MAX) {
        const std::uint32_t c = kept[centre_id[i]];
        addArc(k, a, b, bite, path.bulgeOf(i) > 0.0, c, points[c] - origin_, ia, ib, addOwner);
        continue;
      }
      if (a == b) {
        if (bite) continue;  // a disk minus the same disk: nothing
        shapes_.push_back(Shape::of(a, b, false));
        addOwner(ia, r_, {k, 0.0, kTwoPi, true});
        continue;
      }
      shapes_.push_back(Shape::of(a, b, bite));
      const double heading = std::atan2(b.y - a.y, b.x - a.x);
      const Point right = Point{b.y - a.y, a.x - b.x} * (1.0 / std::sqrt(dot(b - a, b - a)));  // heading - pi / 2
      addOwner(ib, r_, {k, wrapAngle(heading - M_PI / 2), M_PI, true, right, right * -1.0});  // the end cap faces forward
      if (bite)  // the bite's forward half is inside the capsule
        addOwner(ia, r_, {k, wrapAngle(heading - M_PI / 2), M_PI, false, right, right * -1.0});
      else  // the start cap faces back
        addOwner(ia, r_, {k, wrapAngle(heading + M_PI / 2), M_PI, true, right * -1.0, right});
    }
  }

  /// Shape k, the arc from a to b (counter-clockwise if `ccw`) around point `centre` (an id, at c;
  /// a and b are points ia and ib), and the parts of circles its boundary runs along: the circle of
  /// radius R + r over the arc's angles (the shape inside it), and where R > r, as for a segment,
  /// the circle of radius R - r over them (the shape outside it) and the half circles around its
  /// ends facing away from the arc (the start's facing forward, the shape outside it, for a bite).
  /// Where R <= r the disks around the ends meet at a point x beyond c, and each of those half
  /// circles ends there. And where R < r the tool passes some points twice in the one arc: those
  /// within r of both ends but beyond r of the arc's middle (the arc point opposite them), between
  /// the circle of radius r - R over the opposite angles (outside it) and the circles around the
  /// ends from where they touch it to x (inside them): shape k + 1, `twice`.
  template <class AddOwner>
  void addArc(std::size_t k, Point a, Point b, bool bite, bool ccw, std::uint32_t centre, Point c, std::uint32_t ia,
              std::uint32_t ib, AddOwner& addOwner) {
    Shape s = Shape::of(a, b, bite);
    s.arc = true;
    s.c = c;
    const double da = norm(a - s.c), db = norm(b - s.c);
    s.radius = (da + db) / 2;
    const Point ua = (a - s.c) * (1.0 / da), ub = (b - s.c) * (1.0 / db);
    s.lo = ccw ? ua : ub;
    s.hi = ccw ? ub : ua;
    const double t_lo = std::atan2(s.lo.y, s.lo.x);
    const double span = wrapAngle(std::atan2(s.hi.y, s.hi.x) - t_lo);
    s.outer = circles_[addOwner(centre, s.radius + r_, Owner{k, wrapAngle(t_lo), span, true, s.lo, s.hi})].round;
    s.has_inner = s.radius - r_ > kSnap;
    if (s.has_inner)
      s.inner = circles_[addOwner(centre, s.radius - r_, Owner{k, wrapAngle(t_lo), span, false, s.lo, s.hi})].round;
    // x = c - m t, m the arc's middle direction, |x - a| = |x - b| = r; x = c where R is within
    // kSnap of r (t grows as sqrt(r (r - R)): rounding must not move the caps' ends).
    const bool twice = r_ - s.radius > kSnap;
    const double half = span / 2;
    const Point m{std::cos(t_lo + half), std::sin(t_lo + half)};
    const double sin_half = std::sin(half);
    const double t = !twice ? 0.0
                            : std::fmax(0.0, std::sqrt(std::fmax(0.0, r2_ - s.radius * s.radius * sin_half * sin_half)) -
                                                 s.radius * std::cos(half));
    const Point x = s.c - m * t;
    // The half circles around the ends facing away from the arc, counter-clockwise from `from`
    // (+-u, u the unit vector from c to the end p) to -from; where R <= r, split at x's direction
    // into the part at the outer end (+u: the shape's) and the part at the inner end (`twice`'s).
    struct Half {
      Point from, to;
    };
    auto split = [&](Point p, Point u, Point from) -> std::pair<Half, Half> {
      const Point to = from * -1.0;
      if (s.has_inner) return {{from, to}, {to, to}};
      const Point v = (x - p) * (1.0 / norm(x - p));
      if (dot(from, u) < 0.0) return {{v, to}, {from, v}};
      return {{from, v}, {v, to}};
    };
    auto own = [&](std::uint32_t at, std::size_t shape, Half h, bool inside, bool half_circle) {
      const double start = std::atan2(h.from.y, h.from.x);
      addOwner(at, r_, Owner{shape, wrapAngle(start), half_circle ? M_PI : wrapAngle(std::atan2(h.to.y, h.to.x) - start),
                             inside, h.from, h.to});
    };
    const Point start_from = ccw ? ua * -1.0 : ua;  // on a left turn, the start cap runs from the inner side
    const auto [a_outer, a_inner] = split(a, ua, start_from);
    const auto [b_outer, b_inner] = split(b, ub, ccw ? ub : ub * -1.0);
    own(ib, k, b_outer, true, s.has_inner);
    if (twice) own(ib, k + 1, b_inner, true, false);
    if (!bite) {
      own(ia, k, a_outer, true, s.has_inner);
      if (twice) own(ia, k + 1, a_inner, true, false);
    } else {
      // The forward half, and where R <= r on to x's direction (where `twice` lies inside the
      // circle and this shape outside it, they cancel: neither is walked).
      own(ia, k, {start_from * -1.0, start_from}, false, true);
      if (!s.has_inner && !twice) own(ia, k, a_inner, false, false);
    }
    shapes_.push_back(s);
    if (!twice) return;
    Shape e = s;
    e.bite = false;
    e.twice = true;
    e.has_inner = true;
    const Point from = s.lo * -1.0, to = s.hi * -1.0;
    e.inner = circles_[addOwner(centre, r_ - s.radius, Owner{k + 1, wrapAngle(t_lo + M_PI), span, false, from, to})].round;
    shapes_.push_back(e);
  }

  /// The shapes found around the current shape whose boxes meet [lo, hi] (into near_). Without
  /// branches: which boxes meet is hard to predict, a mispredicted branch costs more than the test.
  void nearBox(double lo_x, double lo_y, double hi_x, double hi_y) {
    if (lo_x < group_.min_x - kSnap || lo_y < group_.min_y - kSnap || hi_x > group_.max_x + kSnap ||
        hi_y > group_.max_y + kSnap) {
      near_.clear();
      index_.query(bgi::intersects(BBox(BPoint(lo_x, lo_y), BPoint(hi_x, hi_y))),
                   boost::make_function_output_iterator([&](const auto& found) { near_.push_back(found.second); }));
      return;
    }
    near_.resize(around_.size());
    std::size_t m = 0;
    for (std::size_t j = 0; j < around_.size(); ++j) {
      const Box& b = around_boxes_[j];
      near_[m] = around_[j];
      m += static_cast<std::size_t>((b.max_x >= lo_x) & (b.min_x <= hi_x) & (b.max_y >= lo_y) & (b.min_y <= hi_y));
    }
    near_.resize(m);
  }

  /// Adds `integral` to the areas of the levels between the counts on the piece's two sides.
  void add(int left, int right, double integral) {
    const int lo = std::min(left, right), hi = std::max(left, right);
    const double signed_integral = left > right ? integral : -integral;
    for (int level = std::max(lo + 1, 1); level <= hi && level <= static_cast<int>(areas_.size()); ++level)
      areas_[static_cast<std::size_t>(level - 1)] += signed_integral;
  }

  /// Parameters t where the line p + t v meets the circle (c, rho). A line within kSnap of touching
  /// the circle touches it, at one point: a side along another within kSnap is decided by the rule
  /// up to the point where it touches that side's end circle, which must therefore be a cut; and
  /// rounding alone, at a line that touches, would open a chord of 1e-8 r with a sliver no test can
  /// place. (A real chord that short, 2 sqrt(2 r kSnap), bounds a sliver of 1e-14 m^2 at most.)
  /// `inv_vv` is 1 / |v|^2.
  static void lineCircle(Point p, Point v, double inv_vv, Point c, const Round& rho, std::vector<double>& out) {
    const double t0 = dot(c - p, v) * inv_vv;  // foot of the perpendicular from c
    const Point off = p + v * t0 - c;
    const double h2 = dot(off, off);
    if (h2 > rho.out2) return;
    const double half = h2 >= rho.in2 ? 0.0 : std::sqrt((rho.rho2 - h2) * inv_vv);
    out.push_back(t0 - half);
    out.push_back(t0 + half);
  }

  /// Points (relative to o) where the circle (o, ro) meets the circle (c, rc): none for the same
  /// centre, one where they come within kSnap of touching (outside or inside each other).
  static void circleCircle(Point o, const Round& ro, Point c, const Round& rc, std::vector<Point>& out) {
    const Point d = c - o;
    const double dd = dot(d, d);
    if (dd == 0.0) return;
    if (ro.rho == rc.rho) {
      if (dd > 4.0 * ro.out2) return;
      const double h = dd >= 4.0 * ro.in2 ? 0.0 : std::sqrt((ro.rho2 - dd / 4.0) / dd);  // half chord / |d|
      const Point m = d * 0.5, perp{-d.y * h, d.x * h};
      out.push_back(m - perp);
      out.push_back(m + perp);
      return;
    }
    const double dist = std::sqrt(dd), sum = ro.rho + rc.rho, diff = std::fabs(ro.rho - rc.rho);
    if (dist > sum + 2.0 * kSnap || dist < diff - 2.0 * kSnap) return;
    const Point u = d * (1.0 / dist);
    if (dist >= sum - 2.0 * kSnap || dist <= diff + 2.0 * kSnap) {  // touching: on the line of the centres
      const Point x = u * (dist <= diff + 2.0 * kSnap && ro.rho < rc.rho ? -ro.rho : ro.rho);
      out.push_back(x);
      out.push_back(x);
      return;
    }
    const double along = (dd + ro.rho2 - rc.rho2) / (2.0 * dist);
    const double h = std::sqrt(std::fmax(0.0, ro.rho2 - along * along));
    const Point m = u * along, perp{-u.y * h, u.x * h};
    out.push_back(m - perp);
    out.push_back(m + perp);
  }

  /// Squared distance from q to shape k's axis (its segment, centre or arc).
  double axisDistance2(std::size_t k, Point q) const {
    const Shape& s = shapes_[k];
    if (s.arc) {
      const Point x = q - s.c;
      if (s.inSpan(x)) {
        const double e = std::sqrt(dot(x, x)) - s.radius;
        return e * e;
      }
      return std::fmin(dot(q - s.a, q - s.a), dot(q - s.b, q - s.b));
    }
    const double u = std::clamp(dot(q - s.a, s.d) * s.inv_dd, 0.0, 1.0);
    const Point off = q - (s.a + s.d * u);
    return dot(off, off);
  }

  /// Whether the segment [p, q] comes within `reach` of shape k's axis (an arc: always, its box
  /// having met the segment's).
  bool axisWithin(std::size_t k, Point p, Point q, double reach) const {
    const Shape& s = shapes_[k];
    if (s.arc) return true;
    const double reach2 = reach * reach;
    auto pointSegment2 = [](Point x, Point a, Point d, double inv_dd) {
      const double u = std::clamp(dot(x - a, d) * inv_dd, 0.0, 1.0);
      const Point off = x - (a + d * u);
      return dot(off, off);
    };
    const Point v = q - p;
    const double inv_vv = 1.0 / dot(v, v);
    if (pointSegment2(p, s.a, s.d, s.inv_dd) <= reach2 || pointSegment2(q, s.a, s.d, s.inv_dd) <= reach2 ||
        pointSegment2(s.a, p, v, inv_vv) <= reach2 || pointSegment2(s.b, p, v, inv_vv) <= reach2)
      return true;
    // Farther than reach at all four ends: within it only if the segments cross.
    const double c1 = cross(v, s.a - p), c2 = cross(v, s.b - p), c3 = cross(s.d, p - s.a), c4 = cross(s.d, q - s.a);
    return ((c1 > 0) != (c2 > 0)) && ((c3 > 0) != (c4 > 0));
  }

  /// Whether shape k contains q (not on its boundary). On a side of capsule `self` running along
  /// `dir` (zero on circles), a side of k it runs along decides by the rule for sides along sides.
  bool contains(std::size_t k, Point q, std::size_t self, Point dir) const {
    const Shape& s = shapes_[k];
    if (s.arc) {
      const Point x = q - s.c;
      const double rho2 = dot(x, x);
      const bool near_a = dot(q - s.a, q - s.a) < r2_, near_b = dot(q - s.b, q - s.b) < r2_;
      // Passed twice: within r of both ends, and beyond r of the arc point opposite q (q's
      // direction reversed lies in the arc's angles, and q is farther than r - R from c).
      if (s.twice) return near_a && near_b && s.inSpan(x * -1.0) && rho2 > s.inner.rho2;
      const bool ring = s.inSpan(x) && rho2 < s.outer.rho2 && (!s.has_inner || rho2 > s.inner.rho2);
      return (ring || near_a || near_b) && !(s.bite && near_a);
    }
    const Point d = s.d;
    const double u = std::clamp(dot(q - s.a, d) * s.inv_dd, 0.0, 1.0);
    const Point off = q - (s.a + d * u);
    const double dist2 = dot(off, off);
    if ((dir.x != 0.0 || dir.y != 0.0) && u > 0.0 && u < 1.0 && std::fabs(dist2 - r2_) < 2.0 * r_ * kSnap &&
        std::fabs(cross(dir, d)) < 1e-6 * std::sqrt(dot(d, d) * dot(dir, dir))) {
      const bool right = cross(d, q - s.a) < 0.0;  // q on k's right side, which runs along d
      const bool same = (dot(dir, d) > 0.0) == right;
      return same && k < self;
    }
    return dist2 < r2_ && !(s.bite && dot(q - s.a, q - s.a) < r2_);
  }

  /// A point of an element: its parameter t (along a side, or the angle around a circle) and the
  /// point (on a side) or its offset from the centre (on a circle).
  struct Cut {
    double t;
    Point p;
    bool operator<(const Cut& o) const { return t < o.t; }
  };

  /// Cuts the element from `start` to `end` where the nearby shapes' boundaries cross it, counts
  /// the shapes containing each piece (not `self` nor those in `owners`, the shapes the element
  /// bounds: of those, `on_left` lie on its left and `on_right` on its right), and adds each piece's
  /// integral to the levels between the counts on its two sides. A shape no boundary of which
  /// crosses the element contains all of it or none: it is tested once.
  /// Every point of the element lies within `reach` of `mid`, and the distance to a shape's axis
  /// changes no faster than the point: a shape whose axis is farther than r + reach from `mid`, or
  /// nearer than r - reach, is crossed by none of the element.
  template <class Crossings, class Middle, class Integral>
  void pieces(Cut start, Cut end, Point mid, double reach, int on_left, int on_right, std::size_t self, Point dir,
              const std::vector<std::size_t>& owners, Crossings crossings, Middle middle, Integral integral) {
    cuts_.clear();
    cuts_.push_back(start);
    cuts_.push_back(end);
    events_.clear();
    int base = 0;
    const double far = r_ + reach + kSnap, near = r_ - reach - kSnap;
    for (const std::uint32_t k : near_) {
      if (k == self || std::find(owners.begin(), owners.end(), k) != owners.end()) continue;
      const Shape& s = shapes_[k];
      const double d2 = axisDistance2(k, mid);
      // An arc's circles may lie up to kSnap farther from its axis than r (snapped to another's);
      // what a tight arc passes twice lies within r of it, but not all that does.
      const double far_k = s.arc ? far + 2.0 * kSnap : far, near_k = s.arc ? near - 2.0 * kSnap : near;
      if (d2 > far_k * far_k) continue;
      const double a2 = s.bite ? dot(mid - s.a, mid - s.a) : INFINITY;
      if (near > 0.0 && a2 < near * near) continue;  // deep in the bite
      if (near_k > 0.0 && d2 < near_k * near_k && a2 > far * far && !s.twice) {
        ++base;
        continue;
      }
      // Where k's boundary crosses the element, and whether k contains each stretch between.
      own_.clear();
      own_.push_back(start);
      crossings(k, own_);
      if (own_.size() == 1) {
        base += contains(k, mid, self, dir);
        continue;
      }
      std::sort(own_.begin() + 1, own_.end());
      own_.push_back(end);
      bool was = false;
      for (std::size_t j = 0; j + 1 < own_.size(); ++j) {
        if (!(own_[j + 1].t > own_[j].t)) continue;
        const bool in = contains(k, middle(own_[j], own_[j + 1]), self, dir);
        if (j == 0) {
          base += in;
        } else {
          if (in != was) events_.push_back({own_[j].t, in ? 1 : -1});
          cuts_.push_back(own_[j]);
        }
        was = in;
      }
    }
    std::sort(cuts_.begin(), cuts_.end());
    std::sort(events_.begin(), events_.end());
    int count = base;
    std::size_t next = 0;
    for (std::size_t c = 0; c + 1 < cuts_.size(); ++c) {
      const Cut& a = cuts_[c];
      const Cut& b = cuts_[c + 1];
      while (next < events_.size() && events_[next].first <= a.t) count += events_[next++].second;
      if (b.t > a.t) add(count + on_left, count + on_right, integral(a, b));
    }
  }

  /// One straight side of capsule `self`, from p to q with the capsule on its left.
  void side(std::size_t self, Point p, Point q) {
    const Point v = q - p;
    const double inv_vv = 1.0 / dot(v, v);
    nearBox(std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y));
    // Long sides pass many shapes: keep those whose axis comes within r of the side.
    if (dot(v, v) > r2_)
      near_.erase(std::remove_if(near_.begin(), near_.end(),
                                 [&](std::uint32_t k) { return k != self && !axisWithin(k, p, q, r_ + kSnap); }),
                  near_.end());
    // The side touches the circles around its own capsule's ends, at its ends, and crosses
    // nothing of them. Crossings strictly inside the side are kept.
    const Point own_a = shapes_[self].a, own_b = shapes_[self].b;
    auto keep = [&](double t, std::vector<Cut>& out) {
      if (t > 0.0 && t < 1.0) out.push_back({t, p + v * t});
    };
    auto crossings = [&](std::size_t k, std::vector<Cut>& out) {
      const Shape& s = shapes_[k];
      line_.clear();
      if (!(s.a == own_a) && !(s.a == own_b)) lineCircle(p, v, inv_vv, s.a, tool_, line_);
      if (!s.isDisk() && !(s.b == own_a) && !(s.b == own_b)) lineCircle(p, v, inv_vv, s.b, tool_, line_);
      if (s.arc) {
        lineCircle(p, v, inv_vv, s.c, s.outer, line_);
        if (s.has_inner) lineCircle(p, v, inv_vv, s.c, s.inner, line_);
      } else if (!s.isDisk()) {
        const Point n = s.n, w = s.d;
        for (const Point& a : {s.a + n, s.a - n}) {
          const double denom = cross(v, w);
          if (std::fabs(denom) <= 1e-12 * std::sqrt(dot(v, v) * dot(w, w))) continue;  // parallel
          const double u = cross(a - p, v) / denom;
          if (u >= 0.0 && u <= 1.0) line_.push_back(cross(a - p, w) / denom);
        }
      }
      for (double t : line_) keep(t, out);
    };
    owners_.clear();
    pieces({0.0, p}, {1.0, q}, (p + q) * 0.5, std::sqrt(dot(v, v)) / 2, 1, 0, self, v, owners_, crossings,
           [](const Cut& a, const Cut& b) { return (a.p + b.p) * 0.5; },
           [](const Cut& a, const Cut& b) { return 0.5 * cross(a.p, b.p); });
  }

  /// The offset from the centre of the middle of the arc from a to b (counter-clockwise) on a
  /// circle of radius rho.
  static Point arcMiddle(const Cut& a, const Cut& b, double rho) {
    if (b.t - a.t < 3.0) {  // well under a half circle: along the bisector of the two ends
      const Point u = a.p + b.p;
      return u * (rho / std::sqrt(dot(u, u)));
    }
    const double t = (a.t + b.t) / 2;
    return Point{std::cos(t), std::sin(t)} * rho;
  }

  /// One circle (of radius r around a waypoint, or an arc's outer or inner circle),
  /// counter-clockwise (its disk on the left), in the arcs where the shapes it bounds do not cancel.
  void circle(const Circle& c) {
    const Point o = c.centre;
    const Round& ro = c.round;
    const double rho = ro.rho;
    std::vector<Cut>& ends = ends_;  // angles where an owner's arc begins or ends, unit vectors
    ends.clear();
    for (const Owner& w : c.owners)
      if (w.span < kTwoPi) ends.push_back({w.start, w.from}), ends.push_back({wrapAngle(w.start + w.span), w.to});
    std::sort(ends.begin(), ends.end());
    if (ends.empty()) ends.push_back({0.0, {1.0, 0.0}});
    ends.push_back({ends.front().t + kTwoPi, ends.front().p});
    std::vector<std::size_t>& owners = owners_;
    for (std::size_t e = 0; e + 1 < ends.size(); ++e) {
      const double t0 = ends[e].t, t1 = ends[e + 1].t;
      if (!(t1 > t0)) continue;
      int on_left = 0, on_right = 0;
      owners.clear();
      for (const Owner& w : c.owners)
        if (w.covers((t0 + t1) / 2)) ++(w.inside ? on_left : on_right), owners.push_back(w.shape);
      if (on_left == on_right) continue;  // the shapes on the two sides cancel: no level changes here
      const Cut start{t0, ends[e].p * rho}, end{t1, ends[e + 1].p * rho};
      // The arc's box: its ends and the extreme points of the circle it passes.
      const Point p0 = o + start.p, p1 = o + end.p;
      double lo_x = std::min(p0.x, p1.x), hi_x = std::max(p0.x, p1.x);
      double lo_y = std::min(p0.y, p1.y), hi_y = std::max(p0.y, p1.y);
      for (int quarter = 0; quarter < 8; ++quarter) {
        if (quarter * M_PI / 2 > t0 && quarter * M_PI / 2 < t1) {
          static constexpr double kCos[4] = {1.0, 0.0, -1.0, 0.0}, kSin[4] = {0.0, 1.0, 0.0, -1.0};
          const Point x = o + Point{kCos[quarter % 4], kSin[quarter % 4]} * rho;
          lo_x = std::min(lo_x, x.x), hi_x = std::max(hi_x, x.x), lo_y = std::min(lo_y, x.y), hi_y = std::max(hi_y, x.y);
        }
      }
      nearBox(lo_x, lo_y, hi_x, hi_y);
      // A point x (relative to o) on the circle is on the arc unless it is on the rest of the circle.
      const Point u0 = start.p, u1 = end.p;
      const bool whole = t1 - t0 >= kTwoPi;
      auto onArc = [&](Point x) {
        if (whole) return true;
        if (t1 - t0 <= M_PI) return cross(u0, x) > 0.0 && cross(x, u1) > 0.0;
        return !(cross(u1, x) > 0.0 && cross(x, u0) > 0.0);
      };
      const double span = t1 - t0;
      const double reach = rho * std::fmin(span / 2, 2.0);  // at least the chord from the middle to an end
      const Point mid = o + arcMiddle(start, end, rho);
      auto crossings = [&](std::size_t k, std::vector<Cut>& out) {
        const Shape& s = shapes_[k];
        points_.clear();
        circleCircle(o, ro, s.a, tool_, points_);
        if (!s.isDisk()) circleCircle(o, ro, s.b, tool_, points_);
        if (s.arc) {
          circleCircle(o, ro, s.c, s.outer, points_);
          if (s.has_inner) circleCircle(o, ro, s.c, s.inner, points_);
        }
        // A shape with an end at o has sides touching the circle of radius r there where its cap
        // or bite ends (already a cut), and crossing it nowhere else.
        if (s.isSegment() && !(rho == r_ && (s.a == o || s.b == o))) {
          for (const Point& a : {s.a + s.n, s.a - s.n}) {
            line_.clear();
            lineCircle(a, s.d, s.inv_dd, o, ro, line_);
            for (double t : line_)
              if (t >= 0.0 && t <= 1.0) points_.push_back(a + s.d * t - o);
          }
        }
        for (const Point& x : points_) {
          if (!onArc(x)) continue;
          double t = std::atan2(x.y, x.x);  // into [t0, t0 + 2 pi)
          while (t < t0) t += kTwoPi;
          while (t >= t0 + kTwoPi) t -= kTwoPi;
          if (t > t0 && t < t1) out.push_back({t, x});
        }
      };
      pieces(start, end, mid, reach, on_left, on_right, shapes_.size(), {0.0, 0.0}, owners,
             crossings, [&](const Cut& a, const Cut& b) { return o + arcMiddle(a, b, rho); },
             [&](const Cut& a, const Cut& b) {
               return 0.5 * (o.x * (b.p.y - a.p.y) - o.y * (b.p.x - a.p.x) + ro.rho2 * (b.t - a.t));
             });
    }
  }

  double r_, r2_ = r_ * r_;
  Round tool_ = roundOf(r_);  ///< the circles of radius r around waypoints
  std::vector<double> areas_;
  Point origin_{0.0, 0.0};
  std::vector<Shape> shapes_;
  std::vector<Circle> circles_;
  std::vector<Box> boxes_;  ///< each shape's box (its axis' box grown by r)
  Index index_;
  Box group_;  ///< the box the shapes in around_ were queried for
  std::vector<std::vector<std::uint32_t>> circles_at_;  ///< the circles around each snapped point
  std::vector<std::uint32_t> around_, near_;
  std::vector<Box> around_boxes_;  ///< the boxes of around_, in its order
  std::vector<Cut> cuts_, own_, ends_;
  std::vector<double> line_;
  std::vector<std::size_t> owners_;
  std::vector<Point> points_;
  std::vector<std::pair<double, int>> events_;  ///< (where, change of the count)
};

}  // namespace

std::vector<double> passLevelAreas(const Path& path, double radius, std::size_t levels) {
  std::vector<double> areas = LevelAreas(path, radius, levels).compute();
  // An empty level sums its pieces to a rounding residue of either sign (about 1e-16 m^2), and
  // two equal levels may come out in either order: the sets are nested, so their areas are not.
  for (std::size_t k = 0; k < areas.size(); ++k)
    areas[k] = std::fmax(0.0, k > 0 ? std::fmin(areas[k], areas[k - 1]) : areas[k]);
  return areas;
}

}  // namespace coverbench
