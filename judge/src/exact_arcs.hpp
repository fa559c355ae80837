#pragma once
// Arcs for the judge's two CGAL units: an arc segment (a car's path) as chords whose ends lie
// exactly on the exact circle, with a certified bound on how far the arc strays from them.
#include <algorithm>
#include <cmath>
#include <vector>

#include "exact_kernel.hpp"

namespace coverbench::judge {

struct ExactArc {
  P2 centre;    ///< exact: the chord's midpoint moved (1 - b^2) / (4 b) chord lengths to its left
  FT radius2;   ///< exact: |a - centre|^2 = |b - centre|^2
  int turn = 1; ///< +1 counter-clockwise (b > 0), -1 clockwise
  /// a, then points exactly on the circle in the arc's order, then b.
  std::vector<P2> points;
  /// A rational upper bound of the distance from any point of the arc to its chords.
  FT stray;
  /// The points follow the arc's turn, each chord spanning less than a half circle: the bound
  /// holds. Always true for arcs of at most a half circle; false means: refuse the segment.
  bool ordered = true;
};

/// The arc from a to b with bulge `bulge` (nonzero, |bulge| <= 1), cut where chords of about
/// `sagitta` stray: a rotation by angle t of (a - centre) with the rational cosine
/// (1 - s^2) / (1 + s^2) and sine 2 s / (1 + s^2), s = tan(t / 2) rounded to a double, is a
/// rational point exactly on the circle, whatever the rounding.
inline ExactArc exactArc(Point a, Point b, double bulge, double sagitta) {
  ExactArc e;
  const P2 A = exactPoint(a), B = exactPoint(b);
  const FT bb(bulge);
  const FT k = (FT(1) - bb * bb) / (FT(4) * bb);
  const V2 d = B - A;
  e.centre = P2((A.x() + B.x()) / 2 - k * d.y(), (A.y() + B.y()) / 2 + k * d.x());
  const V2 u = A - e.centre;
  e.radius2 = u.squared_length();
  e.turn = bulge > 0 ? 1 : -1;
  const double radius = std::sqrt(CGAL::to_double(e.radius2));
  const double sweep = 4.0 * std::atan(bulge);
  const double step = 2.0 * std::acos(std::fmax(-1.0, 1.0 - sagitta / radius));
  const int pieces = static_cast<int>(std::ceil(std::fabs(sweep) / std::fmax(step, 1e-12)));
  e.points.push_back(A);
  for (int j = 1; j < pieces; ++j) {
    const FT s(std::tan(0.5 * sweep * static_cast<double>(j) / static_cast<double>(pieces)));
    const FT den = FT(1) + s * s;
    const FT c = (FT(1) - s * s) / den, sn = FT(2) * s / den;
    e.points.push_back(e.centre + V2(u.x() * c - u.y() * sn, u.x() * sn + u.y() * c));
  }
  e.points.push_back(B);
  // A radius from below: the double square root shrunk until its square is at most radius2.
  double lo = radius * (1.0 - 1e-12);
  while (lo > 0.0 && FT(lo) * FT(lo) > e.radius2) lo *= 1.0 - 1e-12;
  // A chord of length L on a circle of radius R strays by R - sqrt(R^2 - L^2 / 4) <= L^2 / (4 R).
  FT worst = 0;
  const CGAL::Orientation way = e.turn > 0 ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN;
  for (std::size_t j = 0; j + 1 < e.points.size(); ++j) {
    worst = std::max(worst, CGAL::squared_distance(e.points[j], e.points[j + 1]));
    // Each chord turns the arc's way about the centre, and spans less than a half circle (its
    // midpoint's side of the centre: the arc's points before and after it face the same way).
    if (CGAL::orientation(e.centre, e.points[j], e.points[j + 1]) != way) e.ordered = false;
  }
  e.stray = lo > 0.0 ? worst / (FT(4) * FT(lo)) : FT(1e9);
  if (lo <= 0.0) e.ordered = false;
  return e;
}

}  // namespace coverbench::judge
