// Exact areas of the pass-count level sets {q : passes(q) >= k}, by Green's theorem on the
// boundary of the arrangement of the tool-on capsules (+1) and the continuation disks (-1).
//
// A continuation disk lies in both capsules it joins, so the count is also the number of shapes
// containing q, a shape being a tool-on capsule minus the continuation disk at its start (if any):
// one shape per segment, half as many as capsules and disks. Every boundary of the arrangement
// lies on a capsule's straight side or on a circle of radius r around a waypoint. Each side and
// each circle is cut where the other shapes' boundaries cross it; on each piece, the pass count
// just left and just right of it is constant, so the piece bounds the level sets whose level
// lies between the two counts, and adds its line integral
// 1/2 (x dy - y dx) to their areas (a straight piece exactly, an arc in closed form). No chords,
// no scanlines: the error is floating-point rounding, plus the three rules below (each moves a
// boundary by at most about kSnap; tests/pass_areas_test.cpp finds reversed and translated random
// paths within 1e-12 m^2 of each other).
//
// - Waypoints closer than kSnap are one point (otherwise two almost equal circles would cross at
//   points rounding cannot place).
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

/// A shape of the arrangement: the capsule of radius r around [a, b], minus the disk of radius r
/// around a if `bite` (the segment continues a tool-on segment). A capsule with a == b is a disk.
struct Shape {
  Point a, b;
  bool bite = false;
  Point d{0.0, 0.0};    ///< b - a
  double inv_dd = 0.0;  ///< 1 / |d|^2 (0 for a disk)
  Point n{0.0, 0.0};    ///< the left normal, of length r
  bool isDisk() const { return a == b; }
};

/// Part of a circle that lies on a shape's boundary: angles [start, start + span) around the
/// centre (span 2 pi for a whole disk, pi for a capsule's cap or bite), with the shape inside the
/// circle there (`inside`, a cap or a disk) or outside it (a bite).
struct Owner {
  std::size_t shape;
  double start, span;
  bool inside;
  Point from{1.0, 0.0};  ///< the unit vector at angle `start` (a half circle ends at -from)
  bool covers(double angle) const { return span >= kTwoPi || wrapAngle(angle - start) < span; }
};

struct Circle {
  Point centre;
  std::vector<Owner> owners;
};

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
      boxes_.push_back({std::fmin(s.a.x, s.b.x) - r_, std::fmin(s.a.y, s.b.y) - r_, std::fmax(s.a.x, s.b.x) + r_,
                        std::fmax(s.a.y, s.b.y) + r_});
      boxes.push_back({BBox(BPoint(boxes_[k].min_x, boxes_[k].min_y), BPoint(boxes_[k].max_x, boxes_[k].max_y)), k});
    }
    index_ = Index(boxes.begin(), boxes.end());
    for (Shape& s : shapes_)
      if (!s.isDisk()) {
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
    // is in that order).
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
        around_.clear();
        index_.query(bgi::intersects(BBox(BPoint(group.min_x, group.min_y), BPoint(group.max_x, group.max_y))),
                     boost::make_function_output_iterator([&](const auto& found) { around_.push_back(found.second); }));
        around_boxes_.clear();
        for (const std::uint32_t j : around_) around_boxes_.push_back(boxes_[j]);  // nearBox scans these per element
      }
      if (!shapes_[k].isDisk()) {
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
    // kept becomes the earliest such. Found among the points sorted by x, those within kSnap in x.
    const std::size_t n = path.waypoints.size();
    std::vector<std::uint32_t> by_x;
    for (std::size_t k = 0; k < n; ++k)
      if ((k < path.tool_on.size() && path.tool_on[k]) || (k > 0 && path.tool_on[k - 1])) by_x.push_back(static_cast<std::uint32_t>(k));
    if (by_x.empty()) return;
    std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t u, std::uint32_t v) {
      return path.waypoints[u].x < path.waypoints[v].x || (path.waypoints[u].x == path.waypoints[v].x && u < v);
    });
    std::vector<std::uint32_t> rank(n), kept(n);  // rank in by_x; the waypoint each one became
    for (std::uint32_t k = 0; k < by_x.size(); ++k) rank[by_x[k]] = k;
    Box extent;
    for (std::uint32_t k = 0; k < n; ++k) {
      if (!((k < path.tool_on.size() && path.tool_on[k]) || (k > 0 && path.tool_on[k - 1]))) continue;
      const Point p = path.waypoints[k];
      kept[k] = k;
      auto consider = [&](std::uint32_t m) {
        const Point q = path.waypoints[m];
        if (m < k && kept[m] == m && m < kept[k] && std::fabs(q.y - p.y) <= kSnap) kept[k] = m;
      };
      for (std::uint32_t r = rank[k]; r-- > 0 && p.x - path.waypoints[by_x[r]].x <= kSnap;) consider(by_x[r]);
      for (std::uint32_t r = rank[k] + 1; r < by_x.size() && path.waypoints[by_x[r]].x - p.x <= kSnap; ++r) consider(by_x[r]);
      extent.add(path.waypoints[kept[k]]);
    }
    std::vector<Point> snapped(n);
    for (std::uint32_t k : by_x) snapped[k] = path.waypoints[kept[k]];
    // Integrals about the path's centre keep the terms (and their rounding) small.
    origin_ = {(extent.min_x + extent.max_x) / 2, (extent.min_y + extent.max_y) / 2};
    // One circle per kept waypoint.
    std::vector<std::uint32_t> circle_of(n, UINT32_MAX);
    auto addOwner = [&](std::size_t waypoint, Owner o) {
      std::uint32_t& c = circle_of[kept[waypoint]];
      if (c != UINT32_MAX) return circles_[c].owners.push_back(o);
      c = static_cast<std::uint32_t>(circles_.size());
      circles_.push_back({snapped[waypoint] - origin_, {o}});
    };
    for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
      if (!path.tool_on[i]) continue;
      const Point a = snapped[i] - origin_, b = snapped[i + 1] - origin_;
      const bool bite = i > 0 && path.tool_on[i - 1];
      const std::size_t k = shapes_.size();
      if (a == b) {
        if (bite) continue;  // a disk minus the same disk: nothing
        shapes_.push_back({a, b, false});
        addOwner(i, {k, 0.0, kTwoPi, true});
        continue;
      }
      shapes_.push_back({a, b, bite});
      const double heading = std::atan2(b.y - a.y, b.x - a.x);
      const Point right = Point{b.y - a.y, a.x - b.x} * (1.0 / std::sqrt(dot(b - a, b - a)));  // heading - pi / 2
      addOwner(i + 1, {k, wrapAngle(heading - M_PI / 2), M_PI, true, right});  // the end cap faces forward
      if (bite)
        addOwner(i, {k, wrapAngle(heading - M_PI / 2), M_PI, false, right});  // the bite's forward half is inside the capsule
      else
        addOwner(i, {k, wrapAngle(heading + M_PI / 2), M_PI, true, right * -1.0});  // the start cap faces back
    }
  }

  /// The shapes found around the current shape whose boxes meet [lo, hi] (into near_). Without
  /// branches: which boxes meet is hard to predict, a mispredicted branch costs more than the test.
  void nearBox(double lo_x, double lo_y, double hi_x, double hi_y) {
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

  /// Parameters t where the line p + t v meets the circle (c, r). A line within kSnap of touching
  /// the circle touches it, at one point: a side along another within kSnap is decided by the rule
  /// up to the point where it touches that side's end circle, which must therefore be a cut; and
  /// rounding alone, at a line that touches, would open a chord of 1e-8 r with a sliver no test can
  /// place. (A real chord that short, 2 sqrt(2 r kSnap), bounds a sliver of 1e-14 m^2 at most.)
  /// `inv_vv` is 1 / |v|^2.
  void lineCircle(Point p, Point v, double inv_vv, Point c, std::vector<double>& out) const {
    const double t0 = dot(c - p, v) * inv_vv;  // foot of the perpendicular from c
    const Point off = p + v * t0 - c;
    const double h2 = dot(off, off);
    if (h2 > touch_out2_) return;
    const double half = h2 >= touch_in2_ ? 0.0 : std::sqrt((r2_ - h2) * inv_vv);
    out.push_back(t0 - half);
    out.push_back(t0 + half);
  }

  /// Points (relative to o) where the circle (o, r) meets the circle (c, r): none for the same
  /// centre, one where they come within kSnap of touching.
  void circleCircle(Point o, Point c, std::vector<Point>& out) const {
    const Point d = c - o;
    const double dd = dot(d, d);
    if (dd == 0.0 || dd > 4.0 * touch_out2_) return;
    const double h = dd >= 4.0 * touch_in2_ ? 0.0 : std::sqrt((r2_ - dd / 4.0) / dd);  // half chord / |d|
    const Point m = d * 0.5, perp{-d.y * h, d.x * h};
    out.push_back(m - perp);
    out.push_back(m + perp);
  }

  /// Squared distance from q to shape k's axis (its segment, or its centre).
  double axisDistance2(std::size_t k, Point q) const {
    const Shape& s = shapes_[k];
    const double u = std::clamp(dot(q - s.a, s.d) * s.inv_dd, 0.0, 1.0);
    const Point off = q - (s.a + s.d * u);
    return dot(off, off);
  }

  /// Whether the segment [p, q] comes within `reach` of shape k's axis.
  bool axisWithin(std::size_t k, Point p, Point q, double reach) const {
    const Shape& s = shapes_[k];
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
      if (d2 > far * far) continue;
      const double a2 = s.bite ? dot(mid - s.a, mid - s.a) : INFINITY;
      if (near > 0.0 && a2 < near * near) continue;  // deep in the bite
      if (near > 0.0 && d2 < near * near && a2 > far * far) {
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
      if (!(s.a == own_a) && !(s.a == own_b)) lineCircle(p, v, inv_vv, s.a, line_);
      if (!s.isDisk()) {
        if (!(s.b == own_a) && !(s.b == own_b)) lineCircle(p, v, inv_vv, s.b, line_);
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

  /// The offset from the centre of the middle of the arc from a to b (counter-clockwise).
  Point arcMiddle(const Cut& a, const Cut& b) const {
    if (b.t - a.t < 3.0) {  // well under a half circle: along the bisector of the two ends
      const Point u = a.p + b.p;
      return u * (r_ / std::sqrt(dot(u, u)));
    }
    const double t = (a.t + b.t) / 2;
    return Point{std::cos(t), std::sin(t)} * r_;
  }

  /// One circle of radius r around a waypoint, counter-clockwise (its disk on the left), in the
  /// arcs where the shapes it bounds do not cancel.
  void circle(const Circle& c) {
    const Point o = c.centre;
    std::vector<Cut>& ends = ends_;  // angles where an owner's arc begins or ends, unit vectors
    ends.clear();
    for (const Owner& w : c.owners)
      if (w.span < kTwoPi) ends.push_back({w.start, w.from}), ends.push_back({wrapAngle(w.start + w.span), w.from * -1.0});
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
      const Cut start{t0, ends[e].p * r_}, end{t1, ends[e + 1].p * r_};
      // The arc's box: its ends and the extreme points of the circle it passes.
      const Point p0 = o + start.p, p1 = o + end.p;
      double lo_x = std::min(p0.x, p1.x), hi_x = std::max(p0.x, p1.x);
      double lo_y = std::min(p0.y, p1.y), hi_y = std::max(p0.y, p1.y);
      for (int quarter = 0; quarter < 8; ++quarter) {
        if (quarter * M_PI / 2 > t0 && quarter * M_PI / 2 < t1) {
          static constexpr double kCos[4] = {1.0, 0.0, -1.0, 0.0}, kSin[4] = {0.0, 1.0, 0.0, -1.0};
          const Point x = o + Point{kCos[quarter % 4], kSin[quarter % 4]} * r_;
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
      const double reach = r_ * std::fmin(span / 2, 2.0);  // at least the chord from the middle to an end
      const Point mid = o + arcMiddle(start, end);
      auto crossings = [&](std::size_t k, std::vector<Cut>& out) {
        const Shape& s = shapes_[k];
        points_.clear();
        circleCircle(o, s.a, points_);
        if (!s.isDisk()) circleCircle(o, s.b, points_);
        // A shape with an end at o has sides touching this circle where its cap or bite ends
        // (already a cut), and crossing it nowhere else.
        if (!s.isDisk() && !(s.a == o) && !(s.b == o)) {
          for (const Point& a : {s.a + s.n, s.a - s.n}) {
            line_.clear();
            lineCircle(a, s.d, s.inv_dd, o, line_);
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
             crossings, [&](const Cut& a, const Cut& b) { return o + arcMiddle(a, b); },
             [&](const Cut& a, const Cut& b) {
               return 0.5 * (o.x * (b.p.y - a.p.y) - o.y * (b.p.x - a.p.x) + r2_ * (b.t - a.t));
             });
    }
  }

  double r_, r2_ = r_ * r_;
  double touch_in2_ = (r_ - kSnap) * (r_ - kSnap), touch_out2_ = (r_ + kSnap) * (r_ + kSnap);
  std::vector<double> areas_;
  Point origin_{0.0, 0.0};
  std::vector<Shape> shapes_;
  std::vector<Circle> circles_;
  std::vector<Box> boxes_;  ///< each shape's box (its axis' box grown by r)
  Index index_;
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
  Path chords;
  std::vector<double> areas = LevelAreas(measuredPath(path, chords), radius, levels).compute();
  // An empty level sums its pieces to a rounding residue of either sign (about 1e-16 m^2), and
  // two equal levels may come out in either order: the sets are nested, so their areas are not.
  for (std::size_t k = 0; k < areas.size(); ++k)
    areas[k] = std::fmax(0.0, k > 0 ? std::fmin(areas[k], areas[k - 1]) : areas[k]);
  return areas;
}

}  // namespace coverbench
