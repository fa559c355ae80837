// The car's headland rings (coverbench/car_sweep.hpp, docs/vehicles.md): thinned, joined and
// driven as the car can, started elsewhere where they start in a pocket, or taken as passes; and
// the passes along what their smoothing left undriven.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include <boost/geometry/algorithms/convex_hull.hpp>
#include <boost/geometry/geometries/multi_point.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/ring.hpp>
#include <boost/geometry/strategies/strategies.hpp>

#include "car_sweep_parts.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::vehicle_detail {
namespace {

/// A run of short undriven ring pieces (a stair's treads, risers and nosings) becomes one pass
/// when its pieces lie within this many spacings across the run's direction...
constexpr double kRunBandSpacings = 3.0;
/// ...and none turns more than this from it (radians: 75 degrees; a stair of 0.15 m rise and
/// 0.30 m run has risers 63 degrees off its pitch).
constexpr double kRunMaxTurn = 5.0 * M_PI / 12.0;

/// The ring with the vertices of its rounded corners thinned: a vertex is dropped where the chord
/// that skips it stays within `deviation` of it and is free (the workspace's exact segment check).
/// A car's smoothing turns at every vertex, and a corner offset at 1 mm chords gives it a turn
/// every 2 cm, each a curve (three-point turns for a car that reverses) over the last.
Ring thinned(Workspace& ws, const Ring& ring, double deviation) {
  if (ring.size() < 4) return ring;
  Ring out{ring.front()};
  for (std::size_t i = 1; i < ring.size(); ++i) {
    const Point next = ring[(i + 1) % ring.size()];
    const Point a = out.back(), v = ring[i];
    const double len = distance(a, next);
    const double off = len > 0.0 ? std::fabs(cross(next - a, v - a)) / len : distance(a, v);
    if (off <= deviation && ws.router().isFree(a, next)) continue;
    out.push_back(v);
  }
  return out.size() >= 3 ? out : ring;
}

/// A straight stretch of ring the sweep drives as a pass (ringStretches).
struct RingStretch {
  Point a, b;
  bool run;  ///< made of a run of shorter pieces
};

/// The straight stretches the sweep drives of what the rings' smoothing left undriven (`pieces`,
/// in order). A piece `min_length` or longer is one as it is. Consecutive shorter pieces that join
/// (a stair's treads, risers and nosings; a ring's bend) make runs: the most of them whose points
/// lie within `band` across the straight line from the run's first point to its last, no piece
/// turning more than kRunMaxTurn from that line. A run becomes one straight line along it: along
/// the longest edge of its points' convex hull (a stair's pitch, through its nosings), touching
/// them from one side, the side where it is free (the nosings' side, not the corners'); where
/// neither side is free, or the run is one piece, nothing (as a short piece).
std::vector<RingStretch> ringStretches(Workspace& ws, const std::vector<std::pair<Point, Point>>& pieces, double min_length,
                                       double band) {
  namespace bg = boost::geometry;
  using BgPoint = bg::model::d2::point_xy<double>;
  std::vector<RingStretch> out;
  std::vector<Point> run;
  std::size_t k = 0;
  while (k < pieces.size()) {
    if (distance(pieces[k].first, pieces[k].second) >= min_length) {
      out.push_back({pieces[k].first, pieces[k].second, false});
      ++k;
      continue;
    }
    // The run's points: the first piece's ends, then each next piece's end while the pieces join
    // (within a tenth of the band: the smoothing drives a few millimetres of a bend), are short
    // and lie within the band; it ends at the last of them within the turn too (a partial tread
    // and a riser turn more from their chord than the whole flight's pieces do from theirs).
    run.assign({pieces[k].first, pieces[k].second});
    std::size_t fits_to = k + 1;  // the pieces [k, fits_to) make the run
    for (std::size_t end = k + 1; end < pieces.size(); ++end) {
      const auto& [pa, pb] = pieces[end];
      if (distance(pa, pb) >= min_length || distance(run.back(), pa) > 0.1 * band) break;
      run.push_back(pb);
      const Point chord = pb - run.front();
      const double length = std::hypot(chord.x, chord.y);
      if (length <= 0.0) continue;
      const Point u = chord * (1.0 / length);
      double lo = 0.0, hi = 0.0;
      bool turns = false;
      for (std::size_t i = 1; i < run.size(); ++i) {
        const double across = cross(u, run[i] - run.front());
        lo = std::min(lo, across), hi = std::max(hi, across);
        const Point d = run[i] - run[i - 1];
        turns = turns || dot(d, u) < std::hypot(d.x, d.y) * std::cos(kRunMaxTurn);
      }
      if (hi - lo > band) break;
      if (!turns) fits_to = end + 1;
    }
    run.resize(fits_to - k + 1);
    k = fits_to;
    if (run.size() < 3) continue;
    bg::model::multi_point<BgPoint> points;
    for (const Point& p : run) points.emplace_back(p.x, p.y);
    bg::model::ring<BgPoint> hull;
    bg::convex_hull(points, hull);
    Point u{0.0, 0.0};
    double longest = 0.0;
    for (std::size_t i = 0; i + 1 < hull.size(); ++i) {
      const Point d{hull[i + 1].x() - hull[i].x(), hull[i + 1].y() - hull[i].y()};
      if (const double length = std::hypot(d.x, d.y); length > longest) longest = length, u = d * (1.0 / length);
    }
    if (longest <= 0.0) continue;
    const Point nrm{-u.y, u.x};
    double lo = 0.0, hi = 0.0, t0 = 0.0, t1 = 0.0;
    for (const Point& p : run) {
      const double across = cross(u, p - run.front()), at = dot(u, p - run.front());
      lo = std::min(lo, across), hi = std::max(hi, across);
      t0 = std::min(t0, at), t1 = std::max(t1, at);
    }
    for (const double off : {hi, lo}) {
      const Point a = run.front() + u * t0 + nrm * off, b = run.front() + u * t1 + nrm * off;
      if (ws.router().isFree(a, b)) {
        out.push_back({a, b, true});
        break;
      }
    }
  }
  return out;
}

/// The start of the k-th longest edge (0: the longest; the first of equal ones) of the ring of
/// `thin` that holds `vertex`, if it has one.
std::optional<Point> ringEdgeStart(const std::vector<Ring>& thin, Point vertex, std::size_t k) {
  const auto ring = std::find_if(thin.begin(), thin.end(), [&](const Ring& r) { return std::find(r.begin(), r.end(), vertex) != r.end(); });
  if (ring == thin.end() || k >= ring->size()) return std::nullopt;
  std::vector<std::size_t> edges(ring->size());
  std::iota(edges.begin(), edges.end(), std::size_t{0});
  auto length = [&](std::size_t i) { return distance((*ring)[i], (*ring)[(i + 1) % ring->size()]); };
  std::stable_sort(edges.begin(), edges.end(), [&](std::size_t i, std::size_t j) { return length(i) > length(j); });
  return (*ring)[edges[k]];
}

/// Where the car stops on the rings before it drove half their length (they start in a pocket it
/// cannot turn out of), they start again at the start of that ring's longest edge, kept when the
/// car paints more of them so. With ring_start, they start at that ring's ring_start-th longest
/// edge instead, kept as the car drives them (carSweep: where the car starts in a pocket).
void restartRings(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& thin, double spacing, std::size_t ring_start,
                  CarSweep& out) {
  const auto at = ringEdgeStart(thin, rings.path().waypoints.front(), ring_start);
  if (!at && ring_start != 0) return;
  PathBuilder other(ws);
  if (at) other.moveTo(*at, false);
  const std::size_t unreached = coverRings(other, thin, 1.5 * spacing);
  CarSmoothing driven = smoothForCar(ws, other.path());
  if (ring_start > 0 || pathLength(driven.path, true) > pathLength(out.headland.path, true)) {
    rings = other;
    out.unreached_rings = unreached;
    out.headland = std::move(driven);
    out.ring_start = ring_start;
  }
}

/// The rings taken as passes (rings_as_passes 1 or 2): the car starts along the rings' longest
/// segment (where they start may be a pocket too), driven as the rings drive it (1) or the other
/// way (2), and every other painted segment of them is a pass ordered with the rows (sweepOnce):
/// where the rings lead it into a pocket no row is reached from, the rows come first.
void ringsAsPasses(const Path& planned, int rings_as_passes, CarSweep& out) {
  std::size_t longest = 0;
  for (std::size_t k = 1; k < planned.segments(); ++k)
    if (planned.tool_on[k] && segmentLength(planned, k) > segmentLength(planned, longest)) longest = k;
  CarSmoothing start;
  const bool backwards = rings_as_passes == 2;
  start.path.moveTo(planned.waypoints[backwards ? longest + 1 : longest], false);
  start.path.moveTo(planned.waypoints[backwards ? longest : longest + 1], true);
  for (std::size_t k = 0; k < planned.segments(); ++k)
    if (planned.tool_on[k] && k != longest) start.undriven.emplace_back(planned.waypoints[k], planned.waypoints[k + 1]);
  out.headland = std::move(start);
  out.rings_as_passes = rings_as_passes;
}

}  // namespace

void driveRings(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, double spacing, int rings_as_passes,
                std::size_t ring_start, CarSweep& out) {
  // The rings first, from the outermost, as the car can drive them (smoothForCar).
  std::vector<Ring> thin;
  for (const Ring& ring : loops) thin.push_back(thinned(ws, ring, 0.03 * spacing));
  out.unreached_rings = coverRings(rings, thin, 1.5 * spacing);
  if (rings.path().segments() > 0 && !rings_as_passes) out.headland = smoothForCar(ws, rings.path());
  // The rings start at their lowest vertex (coverRings); elsewhere where the car stops on them
  // before it drove half their length, or with ring_start (restartRings).
  const bool again = ring_start > 0 || (out.headland.stopped && pathLength(out.headland.path, true) < 0.5 * pathLength(rings.path(), true));
  if (again && rings.path().segments() > 0) restartRings(ws, rings, thin, spacing, ring_start, out);
  if (rings_as_passes && rings.path().segments() > 0) ringsAsPasses(rings.path(), rings_as_passes, out);
}

std::size_t addRingPasses(Workspace& ws, const std::vector<std::pair<Point, Point>>& undriven, double spacing,
                          std::vector<CarRow>& rows, std::vector<char>& run_pass) {
  // What the rings' smoothing skipped (a ring bent round a socket tighter than the car turns, a
  // stair's steps) is not lost: each straight stretch of it two spacings or longer (for a
  // forward-only car, also a turn radius or longer: each costs it two loop checks), and each run
  // of shorter pieces along a line (ringStretches), becomes a pass the sweep orders with the
  // rows. A forward-only car's pass ends short of F's edge ahead, by up to a turn radius, so that
  // it can turn out of it.
  const VehicleModel& car = ws.vehicle();
  const double rho = car.turn_radius * (1.0 + kCarRadiusSlack);
  const double min_pass = car.reverse ? 2.0 * spacing : std::max(2.0 * spacing, rho);
  std::size_t added = 0;
  for (const RingStretch& stretch : ringStretches(ws, undriven, min_pass, kRunBandSpacings * spacing)) {
    Point a = stretch.a, b = stretch.b;
    const double length = distance(a, b);
    if (length < min_pass) continue;
    if (!car.reverse && !leaveRoomToTurn(ws, a, b, rho, rho, rho, 2.0 * spacing)) continue;
    rows.push_back({a, b, 0, false});
    run_pass.push_back(stretch.run);
    ++added;
  }
  return added;
}

}  // namespace coverbench::vehicle_detail
