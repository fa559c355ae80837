// Chains of chords along F's round boundary written as the arcs they trace (boundary_arcs.hpp).
#include "coverbench/boundary_arcs.hpp"

#include <algorithm>
#include <cmath>

#include "coverbench/planner.hpp"
#include "coverbench/transit_router.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

/// The way a -> b -> c turns at b when it turns by a small step (more than 1e-12 rad, at most
/// kArcFitMaxTurn): +1 left, -1 right; 0 otherwise. (By the tangent of the turn: no atan2 per
/// waypoint of a path.)
double smallTurnAt(Point a, Point b, Point c) {
  static const double max_tan = std::tan(kArcFitMaxTurn);
  const Point u = b - a, v = c - b;
  const double cross = u.x * v.y - u.y * v.x, along = dot(u, v);
  if (!(along > 0.0)) return 0.0;
  const double t = std::fabs(cross) / along;
  if (t > max_tan || t < 1e-12) return 0.0;
  return cross > 0.0 ? 1.0 : -1.0;
}

/// The bulge of the arc from p[i] to p[j] through the chain's vertices, or 0 when the chain
/// p[i..j] does not lie on one arc within the fit's tolerances. `turn_sign` is the sign every
/// vertex turns by.
double chainBulge(const std::vector<Point>& p, std::size_t i, std::size_t j, double turn_sign) {
  // The circle through both ends and the middle vertex; the sweep from the ends' angles about it.
  const Point a = p[i], m = p[(i + j) / 2], b = p[j];
  const Point ab = b - a, am = m - a;
  const double cross = ab.x * am.y - ab.y * am.x;
  if (std::fabs(cross) <= 1e-15) return 0.0;
  const double ab2 = dot(ab, ab), am2 = dot(am, am);
  // Circumcentre relative to a.
  const Point c{(am.y * ab2 - ab.y * am2) / (2.0 * cross), (ab.x * am2 - am.x * ab2) / (2.0 * cross)};
  const Point centre = a + c;
  const double t0 = std::atan2(a.y - centre.y, a.x - centre.x), t1 = std::atan2(b.y - centre.y, b.x - centre.x);
  double sweep = wrapAngle(t1 - t0);
  // The way the chain turns decides the way round (a chain of over a half circle is not fitted).
  if (sweep * turn_sign <= 0.0) return 0.0;
  if (std::fabs(sweep) > M_PI * (1.0 - 1e-9)) return 0.0;
  const double bulge = effectiveBulge(a, b, std::tan(sweep / 4.0));
  if (bulge == 0.0) return 0.0;
  // The arc as the path will hold it: every vertex on it, every chord close to it.
  // (Squared: no square root per vertex.) A chord of length L has sagitta R - sqrt(R^2 - L^2 / 4)
  // <= s exactly when L^2 / 4 <= R^2 - (R - s)^2.
  const ArcGeometry g = arcGeometry(a, b, bulge);
  const double lo = std::fmax(0.0, g.radius - kArcFitTolerance), hi = g.radius + kArcFitTolerance;
  const double lo2 = lo * lo, hi2 = hi * hi;
  const double inner = std::fmax(0.0, g.radius - kArcFitSagitta);
  const double chord2 = 4.0 * (g.radius * g.radius - inner * inner);
  for (std::size_t k = i; k < j; ++k) {
    if (k > i) {
      const Point v = p[k] - g.centre;
      const double d2 = dot(v, v);
      if (d2 < lo2 || d2 > hi2) return 0.0;
    }
    const Point chord = p[k + 1] - p[k];
    if (dot(chord, chord) > chord2) return 0.0;
  }
  return bulge;
}

/// Appends the straight chain p (p[0] is the path's current end), its segments of tool state
/// `tool`, as arcs where it fits them and they are free.
void appendChain(const std::vector<Point>& p, bool tool, const Workspace& ws, Path& out, ArcFit& fit) {
  const std::size_t n = p.size();
  std::size_t i = 0;
  // The run p[..run_last] turning one way (run_sign) by small steps, found once for every start
  // within it (so a chain no arc fits costs n log n, not n^2).
  std::size_t run_last = 0;
  double run_sign = 0.0;
  while (i + 1 < n) {
    // The run p[i..last]; then the longest p[i..j] within it that fits an arc: all of it (the
    // common case: one round join of F), else by bisection.
    if (i + 2 > run_last) {
      run_last = i + 1;
      run_sign = 0.0;
      for (std::size_t j = i + 2; j < n; ++j) {
        const double turn = smallTurnAt(p[j - 2], p[j - 1], p[j]);
        if (turn == 0.0 || (run_sign != 0.0 && turn != run_sign)) break;
        run_sign = turn;
        run_last = j;
      }
    }
    const std::size_t last = run_last;
    const double sign = run_sign;
    std::size_t best = 0;
    double best_bulge = 0.0;
    if (last - i >= kArcFitMinChords) {
      best_bulge = chainBulge(p, i, last, sign);
      if (best_bulge != 0.0) {
        best = last;
      } else {
        std::size_t fits = i + kArcFitMinChords - 1, fails = last;  // fits: a known fit, or below the minimum
        while (fails - fits > 1) {
          const std::size_t mid = fits + (fails - fits) / 2;
          const double b = chainBulge(p, i, mid, sign);
          if (b != 0.0) {
            fits = mid;
            best = mid;
            best_bulge = b;
          } else {
            fails = mid;
          }
        }
      }
    }
    if (best != 0) {
      if (arcFree(ws, p[i], p[best], best_bulge)) {
        out.arcTo(p[best], best_bulge, tool);
        ++fit.arcs;
        fit.chords += best - i;
        i = best;
        continue;
      }
      ++fit.refused;
      for (std::size_t k = i + 1; k <= best; ++k) out.moveTo(p[k], tool);
      i = best;
      continue;
    }
    out.moveTo(p[i + 1], tool);
    ++i;
  }
}

}  // namespace

bool arcFree(const Workspace& ws, Point a, Point b, double bulge) {
  const ToolParams& tool = ws.tool();
  return ws.field().arcFree(a, b, bulge, tool.radius(), tool.clearance, kPlanningMargin);
}

bool pathFree(const Workspace& ws, const Path& path) {
  for (std::size_t i = 0; i < path.segments(); ++i)
    if (!arcFree(ws, path.waypoints[i], path.waypoints[i + 1], path.bulgeOf(i))) return false;
  return true;
}

Path withBoundaryArcs(const Path& path, const Workspace& ws, ArcFit& fit) {
  const std::size_t n = path.waypoints.size();
  if (n < kArcFitMinChords + 1) return path;
  Path out;
  out.moveTo(path.waypoints[0], false);
  const bool lifts = ws.vehicle().liftsTool();
  // Chains of straight segments of one tool state (a lifted move is a chain of its own: it may
  // leave F, and is never fitted).
  std::vector<Point> chain{path.waypoints[0]};
  bool chain_tool = false, chain_fits = false;
  auto flush = [&] {
    if (chain.size() > 1) {
      if (chain_fits)
        appendChain(chain, chain_tool, ws, out, fit);
      else
        for (std::size_t k = 1; k < chain.size(); ++k) out.moveTo(chain[k], chain_tool);
    }
    chain.assign(1, out.waypoints.back());
  };
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double bulge = path.bulgeOf(i);
    const bool tool = path.tool_on[i];
    const bool fits = bulge == 0.0 && !(lifts && !tool);
    if (chain.size() > 1 && (tool != chain_tool || fits != chain_fits || bulge != 0.0)) flush();
    if (bulge != 0.0) {
      out.arcTo(path.waypoints[i + 1], bulge, tool);
      chain.assign(1, out.waypoints.back());
      continue;
    }
    chain_tool = tool;
    chain_fits = fits;
    chain.push_back(path.waypoints[i + 1]);
  }
  flush();
  return out;
}

void fitBoundaryArcs(PlanResult& result, const Workspace& ws, const Problem& problem) {
  if (problem.straight_segments_only || !result.hasPath()) return;
  ArcFit fit;
  result.path = withBoundaryArcs(result.path, ws, fit);
  result.stats["boundary_arcs"] = static_cast<double>(fit.arcs);
  result.stats["boundary_arc_chords"] = static_cast<double>(fit.chords);
}

}  // namespace coverbench
