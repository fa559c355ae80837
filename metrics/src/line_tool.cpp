// The line and rectangle tools in the fast engine (line_tool.hpp). A swept shape is checked
// through its boundary curves, each measured in closed form by the ClearanceField (segments and arcs), with the shape
// shrunk by kShrink so that touching the wall's edge or an obstacle (allowed) is told apart from
// crossing it: a shape whose shrunk boundary meets an edge goes past it by more than kShrink.
#include "line_tool.hpp"

#include <algorithm>

namespace coverbench::line_tool {
namespace {

/// How far the checked shapes are shrunk (m): twice the validity tolerance, so that a crossing
/// reads below -kValidityTolerance and a touch does not.
constexpr double kShrink = 2.0 * kValidityTolerance;

Point leftNormal(Point d) {
  const double len = norm(d);
  return {-d.y / len, d.x / len};
}

/// Folds the gaps of one boundary curve (a segment or an arc) into `g`.
void fold(const SegmentClearance& c, Gaps& g) {
  if (!c.inside) g.outside = true;
  else g.boundary = std::fmin(g.boundary, c.boundary_distance - kShrink);
  if (c.obstacle_distance <= 0.0) g.overlaps = true;
  else if (c.obstacle_distance - kShrink < g.obstacle) g.obstacle = c.obstacle_distance - kShrink;
  if (c.nearest_obstacle >= 0 && (g.nearest < 0 || c.obstacle_distance - kShrink <= g.obstacle)) g.nearest = c.nearest_obstacle;
}

/// Obstacles lying wholly inside a shape touch none of its boundary curves: one point of each
/// obstacle near `box` is tested with `inside`.
template <class Inside>
void obstaclesWithin(const ClearanceField& field, const Box& box, Inside inside, Gaps& g) {
  const std::vector<Obstacle>& obstacles = field.wall().obstacles;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    const Point probe = o.type == ObstacleType::Circle || o.polygon.empty() ? o.center : o.polygon[0];
    if (probe.x < box.min_x || probe.x > box.max_x || probe.y < box.min_y || probe.y > box.max_y) continue;
    if (!inside(probe)) continue;
    g.overlaps = true;
    g.nearest = static_cast<long>(k);
  }
}

void settle(Gaps& g) {
  if (g.outside) g.boundary = 0.0;
  if (g.overlaps) g.obstacle = 0.0;
  g.boundary = std::fmax(g.boundary, 0.0);
  g.obstacle = std::fmax(g.obstacle, 0.0);
}

/// a + b = s + e exactly (Knuth's two-sum).
void twoSum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

/// The sign of the exact sum of `terms`: Shewchuk's expansion growth, exact for doubles whose
/// products neither overflow nor underflow (coordinates of at most 1e6 m and 1e-9 m apart).
int signOfSum(const std::vector<double>& terms) {
  std::vector<double> expansion;  // non-overlapping, in increasing magnitude
  for (double q : terms) {
    std::vector<double> grown;
    for (double component : expansion) {
      double sum = 0.0, error = 0.0;
      twoSum(q, component, sum, error);
      if (error != 0.0) grown.push_back(error);
      q = sum;
    }
    if (q != 0.0) grown.push_back(q);
    expansion = std::move(grown);
  }
  return expansion.empty() ? 0 : (expansion.back() > 0.0 ? 1 : -1);
}

/// The exact sign of d1 . d2 (`cross` false) or d1 x d2 (true), d1 = m1.b - m1.a and d2 =
/// m2.b - m2.a taken exactly (each difference a two-sum, each product split by an fma).
int exactSign(const Segment& m1, const Segment& m2, bool cross) {
  double d[2][2][2];  // [move][x or y][value, error]
  const Segment* moves[2] = {&m1, &m2};
  for (int k = 0; k < 2; ++k) {
    twoSum(moves[k]->b.x, -moves[k]->a.x, d[k][0][0], d[k][0][1]);
    twoSum(moves[k]->b.y, -moves[k]->a.y, d[k][1][0], d[k][1][1]);
  }
  std::vector<double> terms;
  auto product = [&](int i, int j, double sign) {  // sign * d1[i] * d2[j], all four parts
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double p = d[0][i][a] * d[1][j][b];
        terms.push_back(sign * p);
        terms.push_back(sign * std::fma(d[0][i][a], d[1][j][b], -p));
      }
  };
  if (cross) {
    product(0, 1, 1.0);
    product(1, 0, -1.0);
  } else {
    product(0, 0, 1.0);
    product(1, 1, 1.0);
  }
  return signOfSum(terms);
}

}  // namespace

Turn turnBetween(Segment m1, Segment m2) {
  Turn t;
  const Point d1 = m1.b - m1.a, d2 = m2.b - m2.a;
  t.u1 = leftNormal(d1);
  t.u2 = leftNormal(d2);
  // Which way and whether it turns at all are decided exactly from the waypoints, as the exact
  // judge decides them: a right angle in doubles may be a hair over one (the other way round).
  const int along = exactSign(m1, m2, false), turn = exactSign(m1, m2, true);
  if (along < 0) t.u2 = t.u2 * -1.0;  // more than a right angle: the line's shorter way round
  if (turn == 0) return t;            // straight on, or straight back: no turn
  const double sweep = std::atan2(cross(t.u1, t.u2), dot(t.u1, t.u2));
  // The sign the exact cross gives (a turn too small for doubles: the least one, that way).
  t.sweep = std::copysign(std::fmax(std::fabs(sweep), 1e-300), static_cast<double>(turn * (along < 0 ? -1 : 1)));
  return t;
}

Gaps segmentGaps(const ClearanceField& field, Point a, Point b, double h, double e, double cutoff) {
  Gaps g;
  const Point t = (b - a) * (1.0 / distance(a, b)), u = leftNormal(b - a);
  const Point a1 = a - t * e, b1 = b + t * e;  // the rectangle's ends
  const double len = distance(a1, b1);
  const double shrink = std::fmin(kShrink, len / 4.0), hh = std::fmax(h - kShrink, 0.0);
  const Point a2 = a1 + t * shrink, b2 = b1 - t * shrink;
  const Point corner[4] = {a2 - u * hh, b2 - u * hh, b2 + u * hh, a2 + u * hh};
  for (int k = 0; k < 4; ++k) fold(field.measure(corner[k], corner[(k + 1) % 4], cutoff), g);
  Box box{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (const Point& p : corner)
    box = {std::fmin(box.min_x, p.x), std::fmin(box.min_y, p.y), std::fmax(box.max_x, p.x), std::fmax(box.max_y, p.y)};
  const double len2 = distance(a2, b2);
  obstaclesWithin(field, box, [&](Point q) {
    const Point v = q - a2;
    const double along = dot(v, t), across = cross(t, v);
    return along >= 0.0 && along <= len2 && std::fabs(across) <= hh;
  }, g);
  settle(g);
  return g;
}

std::vector<std::pair<Point, Point>> turnCorners(const Turn& turn, double h, double e) {
  if (e == 0.0) return {{turn.u1, turn.u2}};
  // The heading is u turned back by a right angle (u is its left normal), before and after.
  const Point t1{turn.u1.y, -turn.u1.x}, t2{turn.u2.y, -turn.u2.x};
  const double k = 1.0 / std::hypot(h, e);
  return {{(turn.u1 * h + t1 * e) * k, (turn.u2 * h + t2 * e) * k}, {(turn.u1 * h - t1 * e) * k, (turn.u2 * h - t2 * e) * k}};
}

Gaps turnGaps(const ClearanceField& field, Point p, const Turn& turn, double h, double e, double cutoff) {
  Gaps g;
  const double rr = std::fmax(std::hypot(h, e) - kShrink, 0.0);
  const double bulge = std::tan(turn.sweep / 4.0);
  const double sign = turn.sweep > 0.0 ? 1.0 : -1.0;
  for (const auto& [c1, c2] : turnCorners(turn, h, e)) {
    const Point k1 = c1 * rr, k2 = c2 * rr;
    fold(field.measure(p - k1, p + k1, cutoff), g);
    fold(field.measure(p - k2, p + k2, cutoff), g);
    for (double side : {1.0, -1.0}) fold(field.measureArc(p + k1 * side, p + k2 * side, bulge, cutoff), g);
    obstaclesWithin(field, Box{p.x - rr, p.y - rr, p.x + rr, p.y + rr}, [&](Point q) {
      // The wedge from k1 to k2 (at most a right angle), or the opposite one.
      auto inWedge = [&](Point v) { return sign * cross(k1, v) >= 0.0 && sign * cross(v, k2) >= 0.0; };
      const Point v = q - p;
      return norm(v) <= rr && (inWedge(v) || inWedge(v * -1.0));
    }, g);
  }
  settle(g);
  return g;
}

std::vector<Ring> sweptRings(const Path& path, double h, double e) {
  std::vector<Ring> rings;
  bool have = false;      // a tool-on move came before, with only zero-length moves since
  Segment last{};         // that move
  const double reach = std::hypot(h, e);
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    if (!path.tool_on[i]) {
      have = false;
      continue;
    }
    if (a == b) continue;
    const Point d = b - a, u = leftNormal(d), t = d * (1.0 / norm(d));
    if (have) {
      const Turn turn = turnBetween(last, Segment{a, b});
      if (turn.sweep != 0.0) {
        const double sagitta = std::fmin(kSectorSagitta * reach, 5e-5);
        const auto chords = static_cast<int>(std::ceil(std::fabs(turn.sweep) / (2.0 * std::acos(1.0 - sagitta / reach))));
        for (const auto& corners : turnCorners(turn, h, e)) {
          const double start = std::atan2(corners.first.y, corners.first.x);
          for (double side : {1.0, -1.0}) {
            Ring sector{a};
            for (int k = 0; k <= chords; ++k) {
              const double angle = start + turn.sweep * k / chords;
              sector.push_back(a + Point{std::cos(angle), std::sin(angle)} * (side * reach));
            }
            rings.push_back(std::move(sector));
          }
        }
      }
    }
    const Point a1 = a - t * e, b1 = b + t * e;
    rings.push_back({a1 - u * h, b1 - u * h, b1 + u * h, a1 + u * h});
    have = true;
    last = Segment{a, b};
  }
  return rings;
}

}  // namespace coverbench::line_tool
