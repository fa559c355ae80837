#pragma once
// The line and rectangle tools (path.hpp: ToolShape) for the judge's two CGAL units: how the tool
// turns at a waypoint, decided exactly, and rational polygons that contain (outer) or lie inside
// (inner) the rectangles and the sectors it sweeps. A rectangle of half-width h and half-depth e
// is a line of half-width h grown by e along the heading; a line is e = 0. The rectangle's corners and the sectors' arcs are
// irrational in general; like an arc of a car's path, a shape is judged through a certified
// container: a valid verdict holds for the shape itself, and a shape within about 1e-16 of its
// limit (1e-7 m for a turn's arcs) may be refused.
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "coverbench/path.hpp"
#include "exact_kernel.hpp"

namespace coverbench::judge {

inline V2 leftNormal(const V2& d) { return V2(-d.y(), d.x()); }
inline FT crossOf(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// A rational k near rho / |m| with k^2 |m|^2 >= rho2 (outer) or <= rho2 (inner), checked exactly;
/// rho / |m| itself along an axis.
inline FT scaleFor(const V2& m, double rho, const FT& rho2, bool outer) {
  // Along an axis |m| is rational: k = rho / |m| exactly (so a rectangle that touches an edge at
  // exactly its half-width or reach is judged touching).
  if ((m.x() == 0) != (m.y() == 0) && FT(rho) * FT(rho) == rho2) return FT(rho) / CGAL::abs(m.x() == 0 ? m.y() : m.x());
  const FT len2 = m.squared_length();
  double k = rho / std::sqrt(CGAL::to_double(len2));
  for (int i = 0; i < 64; ++i) {
    const FT kk(k);
    const FT lhs = kk * kk * len2;
    if (outer ? lhs >= rho2 : lhs <= rho2) return kk;
    k = outer ? k * (1.0 + 1e-15) : k * (1.0 - 1e-15);
  }
  throw std::logic_error("judge: no rational scale of a line tool's half-width passed its exact check");
}

/// A tool's half-width h and half-depth e (e = 0: a line), and their squares exactly.
struct ExactShape {
  double h = 0.0, e = 0.0;
  FT h2, e2;
  explicit ExactShape(const ToolParams& tool)
      : h(tool.radius()), e(tool.halfDepth()), h2((FT(tool.tool_width) / 2) * (FT(tool.tool_width) / 2)),
        e2((FT(tool.depth) / 2) * (FT(tool.depth) / 2)) {
    if (!tool.isRectangle()) e2 = 0;
  }
  /// The corners' distance from the centre: sqrt(h^2 + e^2), and its square exactly.
  double reach() const { return std::hypot(h, e); }
  FT reach2() const { return h2 + e2; }
  /// A rational radius at least reach() (checked exactly): the disk that holds the tool in every
  /// heading; a line's is h itself.
  FT reachAtLeast() const {
    if (e == 0.0) return h2 == FT(h) * FT(h) ? FT(h) : throw std::logic_error("judge: a line's half-width is not exact");
    double r = reach();
    while (FT(r) * FT(r) < reach2()) r = std::nextafter(r, INFINITY);
    return FT(r);
  }
};

/// The rectangle the tool sweeps from a to b (a != b): a rational rectangle square to b - a whose
/// half-width is at least h and which reaches at least e behind a and past b (outer), or at most
/// (inner). Counter-clockwise.
inline std::vector<P2> lineRectangle(const P2& a, const P2& b, const ExactShape& s, bool outer) {
  const V2 d = b - a, m = leftNormal(d);
  const V2 km = m * scaleFor(m, s.h, s.h2, outer);
  if (s.e == 0.0) return {a - km, b - km, b + km, a + km};
  const V2 kd = d * scaleFor(d, s.e, s.e2, outer);
  return {a - kd - km, b + kd - km, b + kd + km, a - kd + km};
}

/// How the line turns between a move along d1 and one along d2: from the ray of m1 (d1's left
/// normal) to the ray of m2 (d2's, turned over when d1 and d2 make more than a right angle) the
/// way `way` says, by at most a right angle; at a right angle the way the heading turns. No turn
/// (`turns` false) when d1 and d2 are parallel.
struct ExactTurn {
  bool turns = false;
  V2 m1, m2;
  CGAL::Orientation way = CGAL::COLLINEAR;
  double sweep = 0.0;  ///< the signed angle, in doubles: only to space the fans' vertices
};
inline ExactTurn exactTurn(const V2& d1, const V2& d2) {
  ExactTurn t;
  if (crossOf(d1, d2) == 0) return t;
  t.turns = true;
  t.m1 = leftNormal(d1);
  t.m2 = leftNormal(d2);
  if (d1 * d2 < 0) t.m2 = -t.m2;
  const FT c = crossOf(t.m1, t.m2);
  t.way = c > 0 ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN;
  const double x1 = CGAL::to_double(t.m1.x()), y1 = CGAL::to_double(t.m1.y());
  const double x2 = CGAL::to_double(t.m2.x()), y2 = CGAL::to_double(t.m2.y());
  double sweep = std::remainder(std::atan2(y2, x2) - std::atan2(y1, x1), 2.0 * M_PI);
  if ((sweep > 0) != (c > 0)) sweep = -sweep;  // a right angle's sign, as the exact cross says
  t.sweep = sweep;
  return t;
}

using Triangle = std::array<P2, 3>;

/// The turn of each corner of a tool: `t` with m1 and m2 replaced by the directions from the
/// centre to one corner before and after the turn, one corner of each opposite pair (the others
/// are their reflections through the centre: a fan's side -1). A line's are t itself (its ends);
/// a rectangle's two are h m + e d and h m - e d, d the heading that has m as its left normal:
/// rational, so each ray is exact.
inline std::vector<ExactTurn> cornerTurns(const ExactTurn& t, const ExactShape& s) {
  if (s.e == 0.0) return {t};
  auto heading = [](const V2& m) { return V2(m.y(), -m.x()); };
  std::vector<ExactTurn> out;
  for (int sign : {1, -1}) {
    ExactTurn c = t;
    c.m1 = t.m1 * FT(s.h) + heading(t.m1) * FT(sign * s.e);
    c.m2 = t.m2 * FT(s.h) + heading(t.m2) * FT(sign * s.e);
    out.push_back(c);
  }
  return out;
}

/// A rational lambda >= 1 / cos(theta / 2), theta the angle between va and vb (at most a right
/// angle), checked exactly: lambda^2 (va.vb) >= (2 - lambda^2) |va| |vb|, squared where both sides
/// are positive. 0 when none is found.
inline FT stretchFor(const V2& va, const V2& vb) {
  const FT dot = va * vb, p = va.squared_length() * vb.squared_length();
  if (dot < 0) return FT(0);
  const double theta = std::acos(std::fmin(1.0, CGAL::to_double(dot) / std::sqrt(CGAL::to_double(p))));
  double lambda = (1.0 / std::cos(theta / 2.0)) * (1.0 + 1e-9);
  for (int i = 0; i < 64; ++i, lambda *= 1.0 + 1e-6) {
    const FT l2 = FT(lambda) * FT(lambda);
    if (l2 >= FT(2)) return FT(lambda);
    const FT lhs = l2 * dot, rhs = FT(2) - l2;
    if (lhs * lhs >= rhs * rhs * p) return FT(lambda);
  }
  return FT(0);
}

/// One sector of radius h (h2 = h^2 exactly) of a turn about p (side +1; -1: the opposite
/// sector, its reflection through p) as a fan of triangles (p, A_j, A_j+1), A_0 on m1's ray and
/// the last on m2's, every pair turning the turn's way. Outer: each triangle's far edge lies at
/// least h from p (checked exactly), so the fan contains the sector; empty when a check fails
/// (retry with a smaller sagitta). Inner: every A_j lies within h of p, so the fan lies in the
/// sector. Each triangle is listed
/// counter-clockwise. The A_j between the ends are A_0 turned by rational rotations (cosine
/// (1 - s^2) / (1 + s^2), sine 2 s / (1 + s^2)): exactly as far from p as A_0.
inline std::vector<Triangle> sectorFan(const P2& p, const ExactTurn& t, double h, const FT& h2, double sagitta,
                                       bool outer, int side) {
  const double step = 2.0 * std::acos(std::fmax(-1.0, 1.0 - sagitta / h));
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::fabs(t.sweep) / std::fmax(step, 1e-12))));
  const double rho = outer ? h / std::cos(std::fabs(t.sweep) / (2.0 * pieces)) * (1.0 + 1e-12) : h * (1.0 - 1e-12);
  const FT rho2 = FT(rho) * FT(rho);
  const V2 first = t.m1 * scaleFor(t.m1, rho, outer ? rho2 : h2, outer);
  const V2 last = t.m2 * scaleFor(t.m2, rho, outer ? rho2 : h2, outer);
  std::vector<V2> arm{first};
  for (int j = 1; j < pieces; ++j) {
    const FT s(std::tan(0.5 * t.sweep * static_cast<double>(j) / static_cast<double>(pieces)));
    const FT den = FT(1) + s * s;
    const FT c = (FT(1) - s * s) / den, sn = FT(2) * s / den;
    arm.emplace_back(first.x() * c - first.y() * sn, first.x() * sn + first.y() * c);
  }
  arm.push_back(last);
  std::vector<Triangle> fan;
  const FT sign(side);
  for (std::size_t j = 0; j + 1 < arm.size(); ++j) {
    P2 a = p + arm[j] * sign, b = p + arm[j + 1] * sign;
    if (CGAL::orientation(p, a, b) != t.way) return {};
    if (outer && CGAL::squared_distance(p, K::Line_2(a, b)) < h2) {
      // Arms of unequal length (a turn too small to space them): the triangle with both arms
      // stretched by lambda >= 1 / cos(theta / 2) holds the sector, as both are at least h long.
      const FT lambda = stretchFor(arm[j], arm[j + 1]);
      if (lambda == 0) return {};
      a = p + arm[j] * (sign * lambda), b = p + arm[j + 1] * (sign * lambda);
    }
    fan.push_back(t.way == CGAL::LEFT_TURN ? Triangle{p, a, b} : Triangle{p, b, a});
  }
  return fan;
}

}  // namespace coverbench::judge
