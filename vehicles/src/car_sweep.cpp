// Planning for a car from the start: headland rings, then rows in a turn-aware order
// (coverbench/car_sweep.hpp, docs/vehicles.md).
#include "coverbench/car_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <numeric>
#include <optional>
#include <queue>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <boost/geometry/algorithms/convex_hull.hpp>
#include <boost/geometry/geometries/multi_point.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/ring.hpp>
#include <boost/geometry/strategies/strategies.hpp>

#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

/// The fill rounds (carSweep): at most this many...
constexpr int kFillRounds = 8;
/// ...each giving a pass to every piece left unpainted of at least this many spacings²...
constexpr double kFillMinArea = 0.4;
/// ...where a stretch of at least this many spacings fits (first 5 walls of each family, seed 3,
/// forward-only car: these three chosen by the median coverage of residential and stairwell walls,
/// docs/vehicles.md).
constexpr double kFillMinPass = 1.3;
/// A fill round is kept when what it paints more is at least this share of a band one spacing
/// wide along the path it adds (rows paint about 0.8; fill passes, reached by long curves, 0.02-0.09:
/// below 0.03, as on obstacle-free walls where only the corners are left, the round is not kept).
constexpr double kFillMinYield = 0.03;
/// A fill round not worth it from where the sweep ended is tried with the whole sweep planned
/// again only when the sweep leaves at least this share of F's reach unpainted (on the canonical
/// facade, 0.7 %, it would double the planning time for nothing).
constexpr double kFillResweepLeft = 0.03;
/// The fill rounds' raster (PaintGrid) has at most about this many cells.
constexpr double kFillMaxCells = 4e6;
/// Curves checked for freedom per row before the routed links are tried.
constexpr std::size_t kMaxCurveChecks = 64;
/// Strokes after the fill rounds (forward-only): at most this many, searched for over at most
/// kStrokeBudget poses in all, kStrokeExpansions each...
constexpr std::size_t kStrokes = 400;
constexpr std::size_t kStrokeBudget = 1000000;
constexpr std::size_t kStrokeExpansions = 20000;
/// ...each a spacing long at least, where at least kStrokeOpen of its cells are unpainted (or
/// kStrokeOpenLast, where the search finds none), and going on by half spacings (up to
/// kStrokeSteps) while kStrokeOpenOn of each step's are. The route to a stroke paints where
/// kStrokeOpenOn of a segment's cells are unpainted.
constexpr double kStrokeOpen = 0.5;
constexpr double kStrokeOpenLast = 0.25;
constexpr double kStrokeOpenOn = 0.3;
constexpr int kStrokeSteps = 80;
/// Poses searched from a stroke's end for a way back to the path (else it counts as a dead end).
constexpr std::size_t kStrokeLoopExpansions = 3000;
/// A stroke the search at cells of R/2 does not find is searched for at cells of R/4, then R/8
/// (searchCarUntil's fineness), up to this fineness.
constexpr int kStrokeFinestSearch = 4;
/// Strokes are looked for only when the fill rounds leave at least this share of the reach
/// unpainted.
constexpr double kStrokeMinLeft = 0.01;
/// A forward-only car is in a pocket where a search of its motions finds fewer than kPocketPoses
/// poses; where it starts in one, the rings start at up to kRingStarts longest edges of their
/// first ring (carSweep).
constexpr std::size_t kPocketPoses = 5000;
constexpr std::size_t kRingStarts = 8;
/// Rows a stuck car goes back at most, from the furthest it got.
constexpr std::size_t kMaxBacktracks = 4;
/// Rows tried along a route round the obstacles when no curve was free.
constexpr std::size_t kMaxRoutedTries = 8;
/// Of those, the nearest this many are also searched for over the car's own motions
/// (searchCarRoute), each up to kSearchExpansions poses.
constexpr std::size_t kSearchTries = 2;
constexpr std::size_t kSearchExpansions = 800;
/// Poses searched over the whole sweep at most (searches that fail cost the most; this bounds
/// their time: about 2 us a pose).
constexpr std::size_t kSearchBudget = 6000;
/// Poses searched for a loop from a row's end (carCanLoop) before it counts as a dead end.
constexpr std::size_t kLoopExpansions = 300;
/// What entering a stack of rows anywhere but at its bottom or top row costs (in turn radii) when
/// choosing the next row: there its block order begins (carBlockOrder).
constexpr double kInsideStackPenalty = 4.0;
/// How much of the rings' end (in turn radii) a car stuck there gives up at most.
constexpr double kRingGiveUpRadii = 10.0;

/// A run of short undriven ring pieces (a stair's treads, risers and nosings) becomes one pass
/// when its pieces lie within this many spacings across the run's direction...
constexpr double kRunBandSpacings = 3.0;
/// ...and none turns more than this from it (radians: 75 degrees; a stair of 0.15 m rise and
/// 0.30 m run has risers 63 degrees off its pitch).
constexpr double kRunMaxTurn = 5.0 * M_PI / 12.0;

/// The path's first `waypoints` waypoints (and the segments between them).
Path upTo(const Path& path, std::size_t waypoints) {
  Path out = path;
  out.waypoints.resize(waypoints);
  out.tool_on.resize(waypoints - 1);
  if (!out.bulge.empty()) out.bulge.resize(waypoints - 1);
  return out;
}

/// Appends `piece` (which starts where `out` ends) to `out`.
void append(Path& out, const Path& piece) {
  for (std::size_t k = 0; k < piece.segments(); ++k) out.arcTo(piece.waypoints[k + 1], piece.bulgeOf(k), piece.tool_on[k]);
}

/// A forward-only car's pass from a to b, each end moved back (by up to `max_cut_a` at a, up to
/// `max_cut_b` at b, in steps of a quarter turn radius) until a turn radius straight ahead of it is
/// free: room to turn out of it, whichever way the pass is driven. Whether the pass still runs at
/// least `min_length` its way (else it is not worth a pass).
bool leaveRoomToTurn(Workspace& ws, Point& a, Point& b, double rho, double max_cut_a, double max_cut_b,
                     double min_length) {
  const Point u = (b - a) * (1.0 / distance(a, b));
  for (int end = 0; end < 2; ++end) {
    Point& tip = end == 0 ? b : a;
    const Point ahead = end == 0 ? u : u * -1.0;
    const double max_cut = end == 0 ? max_cut_b : max_cut_a;
    double cut = 0.0;
    while (cut < max_cut && !ws.router().isFree(tip, tip + ahead * rho)) {
      cut += 0.25 * rho;
      tip = tip - ahead * (0.25 * rho);
    }
  }
  return dot(b - a, u) >= min_length;
}

/// The piece starts where the car is, heading its way (or, for a car that reverses, backing up).
bool startsAlong(const Path& piece, Pose pose, bool reverse) {
  return piece.segments() > 0 && distance(piece.waypoints.front(), pose.at) <= 1e-12 &&
         headingsJoin(pose.heading, startHeading(piece), reverse);
}

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

/// The length of a path, or of its painted segments only.
double pathLength(const Path& path, bool painted_only = false) {
  double length = 0.0;
  for (std::size_t k = 0; k < path.segments(); ++k)
    if (path.tool_on[k] || !painted_only) length += segmentLength(path, k);
  return length;
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

/// A row's direction from a to b (a unit vector; exact for rows along an axis).
Point rowDirection(const CarRow& r) {
  const Point d = r.b - r.a;
  if (d.y == 0.0) return {d.x > 0.0 ? 1.0 : -1.0, 0.0};
  if (d.x == 0.0) return {0.0, d.y > 0.0 ? 1.0 : -1.0};
  return d * (1.0 / std::hypot(d.x, d.y));
}

/// A sweep step's candidate: a row entered from one end, with the straight distance to that end
/// (a curve is never shorter).
struct Candidate {
  double bound;
  std::size_t row;
  bool from_a;
};

/// The order candidates are taken in: nearest first, ties by row and then end.
bool farther(const Candidate& p, const Candidate& q) {
  return p.bound > q.bound || (p.bound == q.bound && (p.row > q.row || (p.row == q.row && p.from_a < q.from_a)));
}

/// The rows' ends in a uniform grid, so that a step of the sweep looks at the cells about the car
/// rather than at every row's ends. `NearestFirst` walks it.
class EntryGrid {
 public:
  EntryGrid(const std::vector<CarRow>& rows, double cell) : rows_(rows), cell_(cell) {
    if (rows.empty()) return;
    lo_ = hi_ = rows.front().a;
    for (const CarRow& r : rows)
      for (Point p : {r.a, r.b}) {
        lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
        hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y)};
      }
    nx_ = static_cast<long>((hi_.x - lo_.x) / cell_) + 1;
    ny_ = static_cast<long>((hi_.y - lo_.y) / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_ * ny_));
    row_ends_.assign(static_cast<std::size_t>(ny_), 0);
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (bool from_a : {true, false}) {
        const Point p = from_a ? rows[i].a : rows[i].b;
        cells_[static_cast<std::size_t>(cellY(p) * nx_ + cellX(p))].push_back(2 * i + (from_a ? 0 : 1));
        ++row_ends_[static_cast<std::size_t>(cellY(p))];
      }
    ends_ = 2 * rows.size();
  }
  /// A row painted is taken out of the grid (its ends are never candidates: `keep` admits no
  /// painted row), and put back when a backtrack unpaints it; the sweep then walks past fewer ends.
  void setPainted(std::size_t row, bool painted) {
    for (bool from_a : {true, false}) {
      const Point p = from_a ? rows_[row].a : rows_[row].b;
      std::vector<std::size_t>& ends = cells_[static_cast<std::size_t>(cellY(p) * nx_ + cellX(p))];
      const std::size_t id = 2 * row + (from_a ? 0 : 1);
      std::size_t& in_row = row_ends_[static_cast<std::size_t>(cellY(p))];
      if (!painted) {
        ends.push_back(id);
        ++in_row, ++ends_;
      } else if (const auto at = std::find(ends.begin(), ends.end(), id); at != ends.end()) {
        *at = ends.back();  // the order within a cell is immaterial: candidates come out in `farther`'s order
        ends.pop_back();
        --in_row, --ends_;
      }
    }
  }
  long cellX(Point p) const { return static_cast<long>(std::floor((p.x - lo_.x) / cell_)); }
  long cellY(Point p) const { return static_cast<long>(std::floor((p.y - lo_.y) / cell_)); }

  /// The candidates from `from`, nearest first in `farther`'s order, among the ends `keep(row,
  /// from_a)` admits. Cells are visited in square rings about `from`'s cell: once rings 0..k are
  /// seen, every end not yet seen is at least k cells away, so a seen one nearer than that is next.
  template <class Keep>
  class NearestFirst {
   public:
    NearestFirst(const EntryGrid& grid, Point from, Keep keep)
        : grid_(grid), from_(from), keep_(std::move(keep)), cx_(grid.cellX(from)), cy_(grid.cellY(from)) {
      last_ring_ = std::max({cx_, grid.nx_ - 1 - cx_, cy_, grid.ny_ - 1 - cy_, 0L});
    }
    /// The next candidate, or nothing when every admitted end was returned.
    std::optional<Candidate> next() {
      while (true) {
        const bool all_seen = ring_ > last_ring_ || visited_ == grid_.ends_;
        if (!seen_.empty() && (all_seen || seen_.front().bound < static_cast<double>(ring_ - 1) * grid_.cell_)) {
          std::pop_heap(seen_.begin(), seen_.end(), farther);
          const Candidate c = seen_.back();
          seen_.pop_back();
          return c;
        }
        if (all_seen) return std::nullopt;
        visitRing(ring_++);
      }
    }

   private:
    void visitCell(long x, long y) {
      const std::vector<std::size_t>& ends = grid_.cells_[static_cast<std::size_t>(y * grid_.nx_ + x)];
      visited_ += ends.size();
      for (std::size_t id : ends) {
        const std::size_t row = id / 2;
        const bool from_a = id % 2 == 0;
        if (!keep_(row, from_a)) continue;
        const Point d = (from_a ? grid_.rows_[row].a : grid_.rows_[row].b) - from_;
        seen_.push_back({std::sqrt(d.x * d.x + d.y * d.y), row, from_a});
        std::push_heap(seen_.begin(), seen_.end(), farther);
      }
    }
    /// The cells k cells from `from`'s (in the square metric) that lie in the grid, in grid rows
    /// holding ends.
    void visitRing(long k) {
      const long x0 = std::max(cx_ - k, 0L), x1 = std::min(cx_ + k, grid_.nx_ - 1);
      for (long y = std::max(cy_ - k, 0L), y1 = std::min(cy_ + k, grid_.ny_ - 1); y <= y1; ++y) {
        if (grid_.row_ends_[static_cast<std::size_t>(y)] == 0) continue;
        if (y == cy_ - k || y == cy_ + k) {
          for (long x = x0; x <= x1; ++x) visitCell(x, y);
        } else {
          if (cx_ - k >= 0 && cx_ - k < grid_.nx_) visitCell(cx_ - k, y);
          if (k > 0 && cx_ + k >= 0 && cx_ + k < grid_.nx_) visitCell(cx_ + k, y);
        }
      }
    }
    const EntryGrid& grid_;
    Point from_;
    Keep keep_;
    long cx_, cy_, last_ring_;
    long ring_ = 0;  // rings 0..ring_-1 are seen
    std::size_t visited_ = 0;  // ends in the cells visited, admitted or not
    std::vector<Candidate> seen_;  // a heap in `farther`'s order
  };

 private:
  const std::vector<CarRow>& rows_;
  double cell_;
  Point lo_{}, hi_{};
  long nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::size_t>> cells_;  // 2 * row + (0 for end a, 1 for end b)
  std::vector<std::size_t> row_ends_;  // ends in each row of cells
  std::size_t ends_ = 0;               // ends in the grid
};

}  // namespace

std::vector<std::size_t> carBlockOrder(std::size_t m, std::size_t k, std::size_t p, bool whole) {
  std::vector<std::size_t> order;
  const std::size_t least = 2 * k + 1;
  if (k == 0 || m < least || p >= k) return order;
  // Blocks of about equal size, all but the last odd; when m leaves 2k over, a last block of 2k.
  // Not whole: blocks of 2k + 1, the last of 2k + 2 when lines are left (as cheap), the rest left
  // out.
  const std::size_t blocks = m / least;
  const std::size_t last = m % least == 2 * k ? 2 * k : 0;
  if (!whole && last == 0) m = std::min(m, blocks * least + 1);
  std::size_t base = 0;
  auto pair = [&](std::size_t first, std::size_t second) {
    order.push_back(base + first);
    order.push_back(base + second);
  };
  for (std::size_t i = 0; i < blocks; ++i) {
    std::size_t size = (m - last - base) / (blocks - i);  // not whole: 2k + 1, then 2k + 1 or 2k + 2
    if ((i + 1 < blocks || last > 0) && size % 2 == 0) --size;
    if (size % 2 == 1) {
      // Lines j and j + h - 1 for j = p down to 0, the top line, then j + h - 1 and j for j = h -
      // 2 down to p + 1: links span h - 1 or h lines, and the block ends on line p + h, h - 1
      // below the next block's line p.
      const std::size_t h = (size + 1) / 2;
      for (std::size_t j = p + 1; j-- > 0;) pair(j, j + h - 1);
      order.push_back(base + size - 1);
      for (std::size_t j = h - 2; j > p; --j) pair(j, j + h - 1);
    } else {
      // The last block, of even size 2g: lines j and j + g for j = p down to 0, then j + g and j
      // for j = g - 1 down to p + 1 (links span g - 1 or g lines).
      const std::size_t g = size / 2;
      for (std::size_t j = p + 1; j-- > 0;) pair(j, j + g);
      for (std::size_t j = g - 1; j > p; --j) pair(j + g, j);
    }
    base += size;
  }
  // The last 2k lines, entered at their line k - 1 (h - 1 - p + k - 1 >= k lines above the last
  // block's end): lines j and j + k for j = k - 1 down to 0 (links span k or k + 1 lines).
  if (last > 0)
    for (std::size_t j = k; j-- > 0;) pair(j, j + k);
  return order;
}

ParamSpec carPlanParam() {
  return {"car_plan", ParamType::Choice, std::string("headland"), 0, 0, {"headland", "headland_no_fill", "smoothed"}, "",
          "for a car: headland rings and rows in an order its turns can link, then passes through what they left "
          "unpainted (headland), the same without those passes (headland_no_fill), or the path planned for a tool "
          "that turns on the spot, smoothed (smoothed: the baseline); nothing changes for other vehicles"};
}

std::vector<CarRow> carHolePasses(Workspace& ws, std::vector<Ring>& loops, double spacing) {
  std::vector<CarRow> passes;
  std::vector<Ring> kept;
  const bool forward_only = !ws.vehicle().reverse;
  const double rho = ws.vehicle().turn_radius * (1.0 + kCarRadiusSlack);
  for (Ring& ring : loops) {
    std::vector<CarRow> mine;
    bool straight = false;  // an edge long enough for a pass (the ring is replaced by passes)
    if (signedArea(ring) < 0.0)  // a hole's ring (clockwise)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point a = ring[i], b = ring[(i + 1) % ring.size()];
        const double length = distance(a, b);
        if (length < 2.0 * spacing) continue;
        straight = true;
        const Point u = (b - a) * (1.0 / length);
        auto extended = [&](Point from, Point to, Point dir) {
          for (double e : {0.5, 0.35, 0.25, 0.15, 0.08, 0.04})
            if (ws.router().isFree(from, to + dir * e)) return to + dir * e;
          return to;
        };
        Point b2 = extended(a, b, u);
        Point a2 = extended(b2, a, u * -1.0);
        // A forward-only car turns out of a pass beyond its end: not along an edge that runs on
        // into a gap too narrow to turn in (a window tucked into a corner of the wall).
        if (forward_only && !leaveRoomToTurn(ws, a2, b2, rho, distance(a2, a) + rho, distance(b2, b) + rho, 2.0 * spacing))
          continue;
        mine.push_back({a2, b2, 0, false});
      }
    if (!straight) kept.push_back(std::move(ring));
    else passes.insert(passes.end(), mine.begin(), mine.end());
  }
  loops = std::move(kept);
  return passes;
}

Problem asHolonomic(const Problem& problem) {
  Problem holonomic = problem;
  holonomic.vehicle = VehicleModel{};
  holonomic.straight_segments_only = true;
  return holonomic;
}

CarHeadlandLayout carHeadlandLayout(double spacing, double turn_radius) {
  // Rows end (loops - 1 + 0.5) spacings inside F's edge: at least the turn radius.
  CarHeadlandLayout layout;
  const double needed = (turn_radius - 0.5 * spacing) / spacing;
  layout.loops = 1 + static_cast<std::size_t>(std::max(0.0, std::ceil(needed - 1e-9)));
  layout.end_inset = 0.5;
  return layout;
}

HeadlandOptions carHeadlandOptions(const Problem& problem, double spacing, std::size_t loops, double end_inset,
                                   double arc_tolerance, bool along_x) {
  const CarHeadlandLayout car = carHeadlandLayout(spacing, problem.vehicle.turn_radius);
  HeadlandOptions layout;
  layout.spacing = spacing;
  layout.radius = problem.tool.tool_width / 2.0;
  layout.loops = std::max(car.loops, loops);
  layout.end_inset = std::max(car.end_inset, end_inset);
  layout.arc_tolerance = arc_tolerance;
  layout.along_x = along_x;
  return layout;
}

PlanResult carSweepPlan(const CarSweep& sweep, const PathBuilder& rings, std::size_t headland_rings, double angle,
                        std::optional<double> angle_deg, std::size_t free_components) {
  PlanResult result;
  result.status = PlanStatus::Ok;
  result.path = sweep.path;
  rotatePoints(result.path.waypoints, angle);
  result.stats["headland_rings"] = static_cast<double>(headland_rings);
  if (angle_deg) result.stats["sweep_angle_deg"] = *angle_deg;
  recordOutcome(result, rings, free_components, sweep.unreached_rings);
  recordCarSweep(result, sweep);
  result.planned_for_car = true;
  return result;
}

namespace {

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

/// Whether a forward-only car that starts where `path` does is in a pocket: a search of its
/// motions from there finds fewer than kPocketPoses poses.
bool startsInPocket(const Workspace& ws, const Path& path, double rho) {
  if (path.segments() == 0) return false;
  std::size_t found = 0;
  searchCarUntil(ws, Pose{path.waypoints.front(), startHeading(path)}, rho, kPocketPoses, [](Pose, Path&) { return false; }, &found);
  return found < kPocketPoses;
}

/// carSweep without its fill rounds: the rings, then `given` and the ring passes, then the passes
/// `fill` (taken last; one the car does not reach is not a row left out). With `from`, no rings:
/// the sweep goes on from the end of that path (a fill round), which it never cuts back.
CarSweep sweepOnce(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& given,
                   const std::vector<CarRow>& fill, double spacing, const Budget& budget, double line_penalty,
                   const Path* from = nullptr, int rings_as_passes = 0, std::size_t ring_start = 0) {
  const VehicleModel& car = ws.vehicle();
  const double rho = car.turn_radius * (1.0 + kCarRadiusSlack);
  CarSweep out;
  // The rings first, from the outermost, as the car can drive them (smoothForCar).
  std::vector<Ring> thin;
  for (const Ring& ring : loops) thin.push_back(thinned(ws, ring, 0.03 * spacing));
  out.unreached_rings = coverRings(rings, thin, 1.5 * spacing);
  if (rings.path().segments() > 0 && !rings_as_passes) out.headland = smoothForCar(ws, rings.path());
  // The rings start at their lowest vertex (coverRings). Where the car stops on them before it
  // drove half their length (they start in a pocket it cannot turn out of), they start again at
  // the start of that ring's longest edge, kept when the car paints more of them so. With
  // ring_start, they start at that ring's ring_start-th longest edge instead, kept as the car
  // drives them (carSweep: where the car starts in a pocket).
  const bool again = ring_start > 0 || (out.headland.stopped && pathLength(out.headland.path, true) < 0.5 * pathLength(rings.path(), true));
  if (again && rings.path().segments() > 0) {
    const auto at = ringEdgeStart(thin, rings.path().waypoints.front(), ring_start);
    if (at || ring_start == 0) {
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
  }
  if (rings_as_passes && rings.path().segments() > 0) {
    // The car starts along the rings' longest segment (where they start may be a pocket too),
    // driven as the rings drive it (rings_as_passes 1) or the other way (2), and every other
    // painted segment of them is a pass ordered with the rows (below): where the rings lead it
    // into a pocket no row is reached from, the rows come first.
    const Path& planned = rings.path();
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
  out.path = from ? *from : out.headland.path;
  // What the rings' smoothing skipped (a ring bent round a socket tighter than the car turns, a
  // stair's steps) is not lost: each straight stretch of it two spacings or longer (for a
  // forward-only car, also a turn radius or longer: each costs it two loop checks), and each run
  // of shorter pieces along a line (ringStretches), becomes a pass the sweep orders with the
  // rows. A forward-only car's pass ends short of F's edge ahead, by up to a turn radius, so that
  // it can turn out of it.
  std::vector<CarRow> rows = given;
  const double min_pass = car.reverse ? 2.0 * spacing : std::max(2.0 * spacing, rho);
  std::vector<char> run_pass(given.size(), 0);  // the passes made of runs (taken last, below)
  for (const RingStretch& stretch : ringStretches(ws, out.headland.undriven, min_pass, kRunBandSpacings * spacing)) {
    Point a = stretch.a, b = stretch.b;
    const double length = distance(a, b);
    if (length < min_pass) continue;
    if (!car.reverse && !leaveRoomToTurn(ws, a, b, rho, rho, rho, 2.0 * spacing)) continue;
    rows.push_back({a, b, 0, false});
    run_pass.push_back(stretch.run);
    ++out.ring_passes;
  }
  out.rows = rows.size();
  const std::size_t first_fill = rows.size();
  for (const CarRow& pass : fill) {
    rows.push_back(pass);
    run_pass.push_back(1);
  }
  const std::size_t n = rows.size();
  const bool ordered = std::any_of(rows.begin(), rows.end(), [](const CarRow& r) { return r.cell != kAnyCell; });
  std::vector<char> done(n, 0);
  // Rows shorter than a turn radius are left for last: a car that drives into one often has no
  // room to turn out of it (they are what is left between the headlands of two obstacles). So are
  // the passes made of runs: taken with the rows, they drew the sweep away from rows it then did
  // not come back to (first 5 residential walls, boustrophedon, forward-only car: median coverage
  // 0.867 so, 0.899 taken last).
  std::vector<char> last_row(n);
  for (std::size_t i = 0; i < n; ++i) last_row[i] = distance(rows[i].a, rows[i].b) < rho || run_pass[i];
  auto takenLast = [&](std::size_t i) { return last_row[i] != 0; };
  // Ways into a row found to be dead ends (the car got in and no curve took it anywhere): bit 1
  // from a, bit 2 from b.
  std::vector<char> dead(n, 0);
  std::size_t remaining = n;
  auto entryOf = [&](std::size_t i, bool from_a) { return from_a ? rows[i].a : rows[i].b; };
  auto exitOf = [&](std::size_t i, bool from_a) { return from_a ? rows[i].b : rows[i].a; };
  std::vector<double> heading_ab(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) heading_ab[i] = std::atan2(rows[i].b.y - rows[i].a.y, rows[i].b.x - rows[i].a.x);
  auto poseInto = [&](std::size_t i, bool from_a) {
    return Pose{entryOf(i, from_a), from_a ? heading_ab[i] : wrapAngle(heading_ab[i] + M_PI)};
  };
  // What each row was entered after: where to go back to when it proves a dead end.
  struct Step {
    std::size_t row;
    bool from_a;
    std::size_t waypoints;  // the path's size before the link into it
    char how;  // 'c': one curve; 'r': a route smoothed for the car; 's': a searched route
    std::size_t cusps;
  };
  std::vector<Step> steps;
  if (!car.reverse) {
    // A forward-only car that drives through a row and cannot loop from where it comes out (the
    // row ends facing F's edge, or in a strip narrower than its turns) can only end its path
    // there: that way through is a dead end from the start. (A car that reverses backs out.)
    for (std::size_t i = 0; i < n; ++i)
      for (bool from_a : {true, false}) {
        const Pose out_pose{exitOf(i, from_a), poseInto(i, from_a).heading};
        if (!carCanLoop(ws, out_pose, rho, kLoopExpansions)) dead[i] |= from_a ? 1 : 2;
      }
  }

  // The rows of each line, and each row's extent along the lines (`along`: the lines' direction,
  // x for rows along x, as zigzag's).
  std::size_t lines = 0;
  Point along{1.0, 0.0};
  for (const CarRow& r : rows)
    if (r.row) {
      if (lines == 0 && distance(r.a, r.b) > 0.0) along = rowDirection(r);
      lines = std::max(lines, r.line + 1);
    }
  auto along_at = [&](Point p) { return dot(p, along); };
  std::vector<std::vector<std::size_t>> by_line(lines);
  std::vector<double> lo_x(n), hi_x(n);
  for (std::size_t i = 0; i < n; ++i) {
    lo_x[i] = std::min(along_at(rows[i].a), along_at(rows[i].b));
    hi_x[i] = std::max(along_at(rows[i].a), along_at(rows[i].b));
    if (rows[i].row) by_line[rows[i].line].push_back(i);
  }
  std::size_t lowest_line = 0;  // no unpainted row lies below it (set each step)
  // Rows i and j overlap across the lines (lie beside each other).
  auto beside = [&](std::size_t i, std::size_t j) { return lo_x[j] <= hi_x[i] && hi_x[j] >= lo_x[i]; };
  // Per row, a line below which no row beside it is unpainted (rows only get painted between
  // backtracks, which start these over): where lowestBeside looks from next time.
  std::vector<std::size_t> beside_from(n, 0);
  // The lowest unpainted line among the rows beside row i.
  auto lowestBeside = [&](std::size_t i) {
    if (!rows[i].row) return rows[i].line;
    for (std::size_t line = std::max(lowest_line, beside_from[i]); line < rows[i].line; ++line)
      for (std::size_t j : by_line[line])
        if (!done[j] && beside(i, j)) return beside_from[i] = line;
    return beside_from[i] = rows[i].line;
  };
  // Stacks: runs of rows on consecutive lines, each the only row beside the one below it and that
  // one's only row beside it above, their ends within a turn radius of each other (what a wall's
  // open stretch or a cell between windows holds). A car that enters an untouched stack at its
  // bottom or top row takes it in carBlockOrder, each link a U-turn over enough lines for a half
  // circle (`follow`), as long as those curves are free.
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  struct Stack {
    std::vector<std::size_t> rows;  // bottom up
    std::size_t k = 0;              // lines a half-circle U-turn spans at least (0: no block order)
    std::size_t done = 0;           // rows painted
  };
  std::vector<Stack> stacks;
  std::vector<std::size_t> stack_of(n, kNone), stack_pos(n, 0);
  for (std::size_t line = 0; line < lines; ++line)
    for (std::size_t i : by_line[line]) {
      if (takenLast(i)) continue;
      std::size_t below = kNone, count = 0;
      if (line > 0)
        for (std::size_t j : by_line[line - 1])
          if (beside(i, j)) {
            below = j;
            ++count;
          }
      bool joins = count == 1 && stack_of[below] != kNone && rows[i].cell == rows[below].cell && std::fabs(lo_x[i] - lo_x[below]) <= rho &&
                   std::fabs(hi_x[i] - hi_x[below]) <= rho;
      if (joins) joins = std::count_if(by_line[line].begin(), by_line[line].end(), [&](std::size_t j) { return beside(below, j); }) == 1;
      if (joins) {
        stack_of[i] = stack_of[below];
      } else {
        stack_of[i] = stacks.size();
        stacks.emplace_back();
      }
      stack_pos[i] = stacks[stack_of[i]].rows.size();
      stacks[stack_of[i]].rows.push_back(i);
    }
  for (Stack& stack : stacks) {
    const std::size_t m = stack.rows.size();
    if (m < 2) continue;
    const double dy = std::fabs(cross(along, rows[stack.rows.back()].a - rows[stack.rows.front()].a)) / static_cast<double>(m - 1);
    const std::size_t k = dy > 0.0 ? static_cast<std::size_t>(std::ceil(2.0 * rho / dy - 1e-9)) : 0;
    if (!car.reverse && k > 0 && m >= 2 * k + 1) stack.k = k;
  }
  // A row more than k - 1 lines inside a stack no row of which is painted yet: a block order
  // cannot start there.
  auto insideUntouched = [&](std::size_t i) {
    if (stack_of[i] == kNone) return false;
    const Stack& stack = stacks[stack_of[i]];
    return stack.k > 0 && stack.done == 0 && stack_pos[i] >= stack.k && stack.rows.size() - 1 - stack_pos[i] >= stack.k;
  };
  std::vector<std::size_t> follow(n, kNone);  // the row carBlockOrder takes after this one
  // Rows left that are not taken last and may still be entered one way or the other (a row that
  // is a dead end both ways holds none back), and the rows by cell (in the order, then rows of no
  // cell), the first `open_from` of them painted: counted as rows are painted or found dead ends,
  // not each step.
  auto holdsLastBack = [&](std::size_t i) { return !takenLast(i) && dead[i] != 3; };
  std::size_t first_left = 0;
  for (std::size_t i = 0; i < n; ++i) first_left += holdsLastBack(i);
  std::vector<std::size_t> by_cell;
  if (ordered) {
    for (std::size_t i = 0; i < n; ++i) by_cell.push_back(i);
    std::stable_sort(by_cell.begin(), by_cell.end(), [&](std::size_t i, std::size_t j) { return rows[i].cell < rows[j].cell; });
  }
  std::size_t open_from = 0;
  EntryGrid entries(rows, std::max(rho, spacing));  // the unpainted rows' ends
  auto markDone = [&](std::size_t i, bool painted) {
    done[i] = painted ? 1 : 0;
    entries.setPainted(i, painted);
    if (painted) --remaining;
    else ++remaining;
    if (holdsLastBack(i)) first_left = painted ? first_left - 1 : first_left + 1;
    if (!painted) {  // a backtrack: what was known painted below is not any more
      std::fill(beside_from.begin(), beside_from.end(), 0);
      open_from = 0;
    }
    if (stack_of[i] == kNone) return;
    Stack& stack = stacks[stack_of[i]];
    stack.done = painted ? stack.done + 1 : stack.done - 1;
    if (!painted || stack.done != 1 || stack.k == 0) return;
    // The stack's first row: take the rest in its block order from there, counting lines from the
    // nearer end.
    const std::size_t m = stack.rows.size();
    const bool up = stack_pos[i] <= m - 1 - stack_pos[i];
    const std::size_t p = up ? stack_pos[i] : m - 1 - stack_pos[i];
    auto at = [&](const std::vector<std::size_t>& order, std::size_t t) {
      return up ? stack.rows[order[t]] : stack.rows[m - 1 - order[t]];
    };
    // The lines blocks of 2k + 1 leave over are taken into the blocks (each link then spans a
    // little more), unless each of those lines holds another row the car can take them with (a
    // row beside a window: nearest first, the sweep links them to that row's stack).
    std::vector<std::size_t> order = carBlockOrder(m, stack.k, p, false);
    bool shared = true;
    for (std::size_t t = order.size(); t < m && shared; ++t) {
      const std::size_t left = up ? stack.rows[t] : stack.rows[m - 1 - t];
      shared = by_line[rows[left].line].size() > 1;
    }
    if (!shared) order = carBlockOrder(m, stack.k, p, true);
    for (std::size_t r : stack.rows) follow[r] = kNone;  // an order from before a backtrack
    for (std::size_t t = 0; t + 1 < order.size(); ++t) follow[at(order, t)] = at(order, t + 1);
  };
  auto driveRow = [&](std::size_t i, bool from_a) {
    out.path.moveTo(exitOf(i, from_a), true);
    markDone(i, true);
  };
  std::size_t first_row = kNone;  // the row the path starts with, when there are no rings
  if (out.path.waypoints.empty() && n > 0) {
    // Start at the lowest end of the first row (of the first cell, with a cell order).
    std::size_t first = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (std::make_tuple(rows[i].cell, !rows[i].row, rows[i].line, lo_x[i]) <
          std::make_tuple(rows[first].cell, !rows[first].row, rows[first].line, lo_x[first]))
        first = i;
    const bool from_a = along_at(rows[first].a) <= along_at(rows[first].b);
    out.path.moveTo(entryOf(first, from_a), false);
    driveRow(first, from_a);
    ++out.links;
    first_row = first;
  }
  // Gives up the rings' last segments, a turn radius of them (ring not driven, said as such).
  double ring_given_up = 0.0;  // how much of the rings' end was given up (m)
  auto giveUpRingTail = [&]() {
    double cut = 0.0;
    while (out.path.segments() > 1 && cut < rho) {
      const std::size_t k = out.path.segments() - 1;
      cut += segmentLength(out.path, k);
      out.path.waypoints.pop_back();
      out.path.tool_on.pop_back();
      if (out.path.bulge.size() > out.path.tool_on.size()) out.path.bulge.resize(out.path.tool_on.size());
      ++out.headland.skipped;
    }
    ring_given_up += cut;
    out.headland.cut_m += cut;
  };
  // A forward-only car whose rings end in a dead end gives them up until it can loop from their
  // end, up to kRingGiveUpRadii turn radii.
  const Path rings_whole = out.path;  // restored if giving up their end took the car nowhere
  const CarSmoothing headland_whole = out.headland;
  if (!car.reverse && !from)
    while (out.path.segments() > 1 && ring_given_up < kRingGiveUpRadii * rho && !carCanLoop(ws, endPose(out.path), rho, kLoopExpansions))
      giveUpRingTail();
  std::size_t searched_poses = 0;  // by searchCarRoute, over the whole sweep
  const std::size_t max_backtracks = 2 * n + 8;
  std::size_t furthest = 0;  // the most rows the sweep had driven
  // Drives the curve from the car's pose into row i (from end a or b) and the row, if the curve
  // is free; a step of the sweep.
  auto takeCurve = [&](std::size_t i, bool from_a) {
    const Pose pose = endPose(out.path);
    const Path curve = carCurve(pose, poseInto(i, from_a), rho, car.reverse, false);
    if (curve.waypoints.empty() || !pathFree(ws, curve)) return false;
    const std::size_t turned = cusps(curve);
    steps.push_back({i, from_a, out.path.waypoints.size(), 'c', turned});
    furthest = std::max(furthest, steps.size());
    append(out.path, curve);
    driveRow(i, from_a);
    ++out.links;
    out.cusps += turned;
    return true;
  };
  bool desperate = false;    // stuck after going back: routes to many more rows are tried
  bool last_open = false;    // still stuck so: the rows taken last may be taken
  double retreat = 0.0;          // how far the rings' last stretch is cut back
  std::pair<Point, Point> tail;  // that stretch as the rings drove it
  while (remaining > 0) {
    if (budget.expired()) {
      out.timed_out = true;
      break;
    }
    const Pose pose = endPose(out.path);
    while (lowest_line < lines && std::all_of(by_line[lowest_line].begin(), by_line[lowest_line].end(),
                                              [&](std::size_t j) { return done[j] != 0; }))
      ++lowest_line;
    auto admissible = [&](std::size_t i, bool from_a) {
      return !done[i] && !(first_left > 0 && !last_open && takenLast(i)) && !(dead[i] & (from_a ? 1 : 2));
    };
    // With a cell order, the first cell in it that has a row left the car may enter.
    std::size_t cell = kAnyCell;
    if (ordered) {
      while (open_from < n && done[by_cell[open_from]]) ++open_from;
      for (std::size_t t = open_from; t < n; ++t)
        if (admissible(by_cell[t], true) || admissible(by_cell[t], false)) {
          cell = rows[by_cell[t]].cell;
          break;
        }
    }
    // A step of the sweep: a curve, else a route, into a row `keep` admits.
    auto step = [&](auto keep) {
      // In a stack's block order, the next row of the order when its curve is free.
      const std::size_t here = steps.empty() ? first_row : steps.back().row;
      if (here != kNone && follow[here] != kNone && !done[follow[here]]) {
        const std::size_t j = follow[here];
        const bool from_a = distance(pose.at, rows[j].a) <= distance(pose.at, rows[j].b);
        if (keep(j, from_a) && takeCurve(j, from_a)) return true;
      }
      // Taken nearest first, in a fixed order (ties by row and end), from the grid of rows' ends:
      // most are never looked at.
      EntryGrid::NearestFirst<decltype(keep)> nearest(entries, pose.at, keep);
      std::size_t admitted = 0;  // every way on is tried where the rings end (below)
      if (steps.empty() && out.links == 0)
        for (std::size_t i = 0; i < n; ++i) admitted += keep(i, true) + keep(i, false);
      std::vector<Candidate> taken;  // nearest first
      // Best first by cost (curve length plus the line penalty), evaluated lazily: a curve is never
      // shorter than the straight distance, so a candidate enters the heap with that distance plus
      // its penalty as its key, and its curve is measured only if it comes to the top.
      struct Scored {
        double cost;
        std::size_t index;  // into taken
        bool measured;      // cost is the curve's length plus the penalty (else a bound on it)
        bool operator>(const Scored& o) const { return std::tie(cost, index, measured) > std::tie(o.cost, o.index, o.measured); }
      };
      std::priority_queue<Scored, std::vector<Scored>, std::greater<>> heap;
      std::vector<double> penalty;  // per taken candidate
      std::size_t next = 0, checks = 0;
      bool found = false;
      // Where the rings end, every way on is tried (once): the car may face F's edge there.
      const std::size_t max_checks = steps.empty() && out.links == 0 ? admitted : kMaxCurveChecks;
      while (!found && checks < max_checks) {
        while (true) {
          if (next == taken.size()) {
            const std::optional<Candidate> more = nearest.next();
            if (!more) break;
            taken.push_back(*more);
          }
          if (!heap.empty() && taken[next].bound >= heap.top().cost) break;
          const Candidate& c = taken[next];
          penalty.push_back(line_penalty * spacing * static_cast<double>(rows[c.row].line - lowestBeside(c.row)) +
                            (insideUntouched(c.row) ? kInsideStackPenalty * rho : 0.0));
          // A curve is no shorter than the straight distance, nor than the turn its headings
          // differ by (a Reeds-Shepp length costs the most to measure): the larger, a hair less
          // for rounding, is its key until it is measured.
          const double turn = std::fabs(wrapAngle(poseInto(c.row, c.from_a).heading - pose.heading));
          heap.push({std::max(c.bound, rho * turn * (1.0 - 1e-9)) + penalty.back(), next, false});
          ++next;
        }
        if (heap.empty()) break;
        if (!heap.top().measured) {
          const std::size_t k = heap.top().index;
          heap.pop();
          const double length = carCurveLength(pose, poseInto(taken[k].row, taken[k].from_a), rho, car.reverse);
          if (std::isfinite(length)) heap.push({length + penalty[k], k, true});
          continue;
        }
        const Candidate c = taken[heap.top().index];
        heap.pop();
        ++checks;
        found = takeCurve(c.row, c.from_a);
      }
      // No curve is free (an obstacle between): a route round it, smoothed for the car, starting
      // straight on from where the car is and ending along the row.
      const std::size_t routed_tries = steps.empty() || desperate ? 8 * kMaxRoutedTries : kMaxRoutedTries;
      for (std::size_t t = 0; !found && t < routed_tries; ++t) {
        if (t == taken.size()) {
          const std::optional<Candidate> more = nearest.next();
          if (!more) break;
          taken.push_back(*more);
        }
        const Candidate c = taken[t];
        Path link;  // from the car through the row
        std::size_t turned = 0;
        double cut = 0.0;
        const Point ahead = pose.at + Point{std::cos(pose.heading), std::sin(pose.heading)} * 1e-3;
        const bool facing_free = ws.router().isFree(pose.at, ahead);
        if (facing_free) {
          if (const auto route = ws.route(ahead, entryOf(c.row, c.from_a))) {
            Path input;
            input.moveTo(pose.at, false);
            for (const Point& p : *route) input.moveTo(p, false);
            input.moveTo(exitOf(c.row, c.from_a), true);
            CarSmoothing smoothed = smoothForCar(ws, input);
            if (!smoothed.stopped && smoothed.path.segments() > 0 &&
                distance(smoothed.path.waypoints.back(), exitOf(c.row, c.from_a)) <= 1e-9 && startsAlong(smoothed.path, pose, car.reverse)) {
              link = std::move(smoothed.path);
              turned = smoothed.cusps;
              cut = smoothed.cut_m;
            }
          }
        }
        // The smoothed route does not take the car there (it would turn tighter than it can, or
        // the car faces F's edge): a search over the car's own motions, for the nearest rows.
        bool searched = false;
        if (link.segments() == 0 && t < kSearchTries && searched_poses < kSearchBudget) {
          link = searchCarRoute(ws, pose, poseInto(c.row, c.from_a), rho, car.reverse,
                                std::min(kSearchExpansions, kSearchBudget - searched_poses), &searched_poses);
          if (link.segments() > 0) {
            link.moveTo(exitOf(c.row, c.from_a), true);
            turned = cusps(link);
            searched = true;
          }
        }
        if (link.segments() == 0) {
          if (!facing_free && t + 1 >= kSearchTries) break;
          continue;
        }
        steps.push_back({c.row, c.from_a, out.path.waypoints.size(), searched ? 's' : 'r', turned});
        furthest = std::max(furthest, steps.size());
        append(out.path, link);
        markDone(c.row, true);
        ++(searched ? out.searched : out.routed);
        out.cusps += turned;
        out.undriven_m += cut;
        found = true;
      }
      return found;
    };
    // With a cell order, that cell's rows (and passes of no cell) first, then any.
    const bool found = (cell != kAnyCell && step([&](std::size_t i, bool from_a) {
                         return admissible(i, from_a) && (rows[i].cell == cell || rows[i].cell == kAnyCell);
                       })) || step(admissible);
    if (found && desperate) {
      desperate = false;
      furthest = steps.size();
    }
    if (found) continue;
    // Stuck where the rings end (facing F's edge closer than a turn): stop their last straight
    // stretch short, by a quarter of a turn radius more each time, up to three radii.
    if (!from && steps.empty() && out.links == 0 && out.path.segments() > 0 && out.path.bulgeOf(out.path.segments() - 1) == 0.0) {
      const std::size_t k = out.path.segments() - 1;
      if (retreat == 0.0) tail = {out.path.waypoints[k], out.path.waypoints[k + 1]};
      retreat += 0.25 * rho;
      const double length = distance(tail.first, tail.second);
      if (retreat < length && retreat <= 3.0 * rho + 1e-12) {
        out.path.waypoints[k + 1] = tail.second + (tail.first - tail.second) * (retreat / length);
        continue;
      }
    }
    // Still stuck there: the rings end in a dead end no curve, route or search leaves (a strip
    // narrower than a turn, an obstacle's corner). Give up their last segments and try again.
    if (!from && steps.empty() && out.links == 0 && out.path.segments() > 1 && ring_given_up < kRingGiveUpRadii * rho) {
      giveUpRingTail();
      retreat = 0.0;  // the straight cut-back starts over on the new last stretch
      continue;
    }
    // Stuck at this row's end: go back to before it, and never enter it that way again; at most
    // kMaxBacktracks rows back from the furthest the sweep got (then the rest is left out).
    if (steps.empty() || out.backtracks >= max_backtracks || steps.size() + kMaxBacktracks <= furthest) {
      // Once more, trying routes to many more rows; then once more with the rows taken last,
      // though rows not taken last are left (none of them was reached); then the rest is left out.
      if (desperate) {
        bool last_left = false;
        for (std::size_t i = 0; i < n && !last_left; ++i) last_left = takenLast(i) && !done[i];
        if (last_open || !last_left) break;
        last_open = true;
        continue;
      }
      desperate = true;
      continue;
    }
    const Step last = steps.back();
    steps.pop_back();
    out.path.waypoints.resize(last.waypoints);
    out.path.tool_on.resize(last.waypoints - 1);
    if (!out.path.bulge.empty()) out.path.bulge.resize(last.waypoints - 1);
    markDone(last.row, false);
    lowest_line = 0;
    dead[last.row] |= last.from_a ? 1 : 2;
    if (!takenLast(last.row) && dead[last.row] == 3) --first_left;
    ++out.backtracks;
    (last.how == 'c' ? out.links : last.how == 'r' ? out.routed : out.searched) -= 1;
    out.cusps -= last.cusps;
  }
  if (steps.empty() && out.links == 0 && ring_given_up > 0.0) {
    // No row was reached from anywhere the rings' end was cut back to: they are driven whole.
    out.path = rings_whole;
    out.headland = headland_whole;
  }
  if (remaining > 0 && !car.reverse && !out.timed_out && out.path.segments() > 0) {
    // A forward-only car may end its path in a dead end: the nearest row left whose curve is free,
    // though it cannot come out of it.
    const Pose pose = endPose(out.path);
    std::vector<std::tuple<double, std::size_t, bool>> left;  // curve length, row, from a
    for (std::size_t i = 0; i < n; ++i)
      for (bool from_a : {true, false})
        if (!done[i]) left.emplace_back(carCurveLength(pose, poseInto(i, from_a), rho, false), i, from_a);
    std::sort(left.begin(), left.end());
    for (const auto& [length, i, from_a] : left) {
      if (!std::isfinite(length)) break;
      const Path curve = carCurve(pose, poseInto(i, from_a), rho, false, false);
      if (curve.waypoints.empty() || !pathFree(ws, curve)) continue;
      out.dead_end_from = out.path.waypoints.size();
      out.dead_end_row = rows[i];
      out.dead_end_fill = i >= first_fill;
      append(out.path, curve);
      driveRow(i, from_a);
      ++out.links;
      out.ended_in_dead_end = true;
      break;
    }
  }
  for (std::size_t i = first_fill; i < n; ++i) {
    if (done[i]) ++out.fill_passes;
    else --remaining;
  }
  out.unreached = remaining;
  for (std::size_t i = 0; i < first_fill; ++i) out.dead_both_ways += !done[i] && dead[i] == 3;
  checkDrivable(out.path, car, "the car's sweep");
  return out;
}

/// Whether `cells` (unpainted cells of the reach, cells of the reach) has some reach and at least
/// `share` of it unpainted.
bool enoughOpen(std::pair<std::size_t, std::size_t> cells, double share) {
  return cells.second > 0 && static_cast<double>(cells.first) >= share * static_cast<double>(cells.second);
}

/// Calls chord(p, q) for each piece of segment i of the path: the segment when it is straight,
/// else chords within `tolerance` of its arc.
template <class Chord>
void forEachChordOf(const Path& path, std::size_t i, double tolerance, Chord&& chord) {
  const Point a = path.waypoints[i], b = path.waypoints[i + 1];
  Point from = a;
  if (effectiveBulge(a, b, path.bulgeOf(i)) != 0.0) {
    const ArcGeometry arc = arcGeometry(a, b, path.bulgeOf(i));
    const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - tolerance / arc.radius));
    const int k = std::max(1, static_cast<int>(std::ceil(std::fabs(arc.sweep) / step)));
    const double start = std::atan2(a.y - arc.centre.y, a.x - arc.centre.x);
    for (int j = 1; j < k; ++j) {
      const double t = start + arc.sweep * j / k;
      const Point to = arc.centre + Point{std::cos(t), std::sin(t)} * arc.radius;
      chord(from, to);
      from = to;
    }
  }
  chord(from, b);
}

/// Calls chord(p, q) for each piece of what the path paints from segment `first` on: its straight
/// segments, and chords within `tolerance` of its arcs.
template <class Chord>
void forEachChord(const Path& path, double tolerance, std::size_t first, bool painted_only, Chord&& chord) {
  for (std::size_t i = first; i < path.segments(); ++i)
    if (!painted_only || path.tool_on[i]) forEachChordOf(path, i, tolerance, chord);
}

template <class Chord>
void forEachPaintedChord(const Path& path, double tolerance, std::size_t first, Chord&& chord) {
  forEachChord(path, tolerance, first, true, chord);
}

/// The poses a path passes through, by cells `cell` wide and 15-degree headings (poseKey): a car
/// that comes back to one of them has driven a loop (it can go on forever).
class PathPoses {
 public:
  explicit PathPoses(double cell) : cell_(cell) {}
  void add(const Path& path, std::size_t first) {
    forEachChord(path, 0.1 * cell_, first, false, [&](Point p, Point q) {
      const double len = distance(p, q);
      if (len <= 0.0) return;
      const double heading = std::atan2(q.y - p.y, q.x - p.x);
      const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * cell_))));
      for (int i = 0; i < n; ++i) {
        const Pose at{p + (q - p) * (static_cast<double>(i) / n), heading};
        poses_.emplace(key(at), at);
      }
    });
  }
  /// A pose the path drove through in p's cell and heading, if any.
  const Pose* near(Pose p) const {
    const auto it = poses_.find(key(p));
    return it == poses_.end() ? nullptr : &it->second;
  }

 private:
  std::int64_t key(Pose p) const { return poseKey(p, cell_, 24); }
  double cell_;
  std::unordered_map<std::int64_t, Pose> poses_;
};

/// A raster of F and of its painted reach (what lies within a tool radius of F), and what a path
/// paints of it: what the fill rounds look for passes in. Cells of `h` metres; a cell is in F, or
/// painted, when its centre is, and in the reach when its centre lies within a tool radius of the
/// centre of a cell of F. Same path, same cells.
class PaintGrid {
 public:
  PaintGrid(const Workspace& ws, double h) : h_(h), r_(ws.tool().radius()) {
    Box box = boundingBox(ws.free());
    origin_ = {box.min_x - r_ - h, box.min_y - r_ - h};
    nx_ = std::max(1, static_cast<int>(std::ceil((box.max_x - box.min_x + 2.0 * (r_ + h)) / h)));
    ny_ = std::max(1, static_cast<int>(std::ceil((box.max_y - box.min_y + 2.0 * (r_ + h)) / h)));
    cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 0);
    std::vector<double> ys(static_cast<std::size_t>(ny_));
    for (int j = 0; j < ny_; ++j) ys[static_cast<std::size_t>(j)] = origin_.y + (j + 0.5) * h;
    const auto crossings = scanlineCrossings(allRings(ws.free()), ys);
    for (int j = 0; j < ny_; ++j) {
      const auto& line = crossings[static_cast<std::size_t>(j)];
      for (std::size_t k = 0; k + 1 < line.size(); k += 2) mark(j, line[k].x, line[k + 1].x, kFree | kReach);
    }
    // The reach: a disk of the tool's radius round each cell of F on its edge.
    const int d = static_cast<int>(std::floor(r_ / h_));
    std::vector<std::pair<int, int>> disk;
    for (int dj = -d; dj <= d; ++dj)
      for (int di = -d; di <= d; ++di)
        if ((di * di + dj * dj) * h_ * h_ <= r_ * r_) disk.emplace_back(di, dj);
    // A cell on F's edge: in F, with a 4-neighbour outside it (a row at a time, without branches).
    std::vector<std::uint8_t> edge(static_cast<std::size_t>(nx_), 0);
    for (int j = 1; j + 1 < ny_; ++j) {
      const std::uint8_t* row = &cells_[index(0, j)];
      const std::uint8_t *below = row - nx_, *above = row + nx_;
      for (int i = 1; i + 1 < nx_; ++i)
        edge[static_cast<std::size_t>(i)] = row[i] & static_cast<std::uint8_t>(~(row[i - 1] & row[i + 1] & below[i] & above[i])) & kFree;
      for (int i = 1; i + 1 < nx_; ++i) {
        if (!edge[static_cast<std::size_t>(i)]) continue;
        for (const auto& [di, dj] : disk)
          if (i + di >= 0 && i + di < nx_ && j + dj >= 0 && j + dj < ny_) cells_[index(i + di, j + dj)] |= kReach;
      }
    }
  }
  /// Marks what `path` paints (its arcs drawn with chords within a tenth of a cell), and only that.
  void paint(const Path& path) {
    for (auto& cell : cells_) cell &= static_cast<std::uint8_t>(~kPainted);
    paintMore(path, 0);
  }
  /// Marks what `path` paints from segment `first` on, besides what is marked (a path painted
  /// before, which this one goes on from: what a path paints is the union of its segments').
  void paintMore(const Path& path, std::size_t first) {
    forEachPaintedChord(path, 0.1 * h_, first, [&](Point p, Point q) { capsule(p, q); });
  }
  /// Marks what segment i of `path` paints, besides what is marked.
  void paintSegment(const Path& path, std::size_t i) {
    forEachChordOf(path, i, 0.1 * h_, [&](Point p, Point q) { capsule(p, q); });
  }
  /// The cells of the reach left unpainted, and all cells of the reach, in the capsule of the
  /// tool's radius round p-q.
  std::pair<std::size_t, std::size_t> openIn(Point p, Point q) const {
    std::size_t open_cells = 0, reach_cells = 0;
    capsuleRows(p, q, [&](int j, double x0, double x1) {
      const int i0 = std::max(0, static_cast<int>(std::ceil((x0 - origin_.x) / h_ - 0.5)));
      const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((x1 - origin_.x) / h_ - 0.5)));
      for (int i = i0; i <= i1; ++i) {
        const std::size_t c = index(i, j);
        reach_cells += (cells_[c] & kReach) != 0;
        open_cells += open(c);
      }
    });
    return {open_cells, reach_cells};
  }
  /// Whether at least `share` of the reach's cells that segment i of `path` would paint are
  /// unpainted (counted chord by chord, as paintMore draws it), and there are some.
  bool openAlong(const Path& path, std::size_t i, double share) const {
    std::pair<std::size_t, std::size_t> cells{0, 0};
    forEachChordOf(path, i, 0.1 * h_, [&](Point p, Point q) {
      const auto [o, r] = openIn(p, q);
      cells.first += o;
      cells.second += r;
    });
    return enoughOpen(cells, share);
  }
  /// The reach's area, counted in cells (m²).
  double reach() const {
    std::size_t count = 0;
    for (std::uint8_t cell : cells_) count += (cell & kReach) != 0;
    return static_cast<double>(count) * h_ * h_;
  }
  /// The painted area, counted in cells of the reach (m²).
  double painted() const {
    std::size_t count = 0;
    for (std::uint8_t cell : cells_) count += (cell & kReach) && (cell & kPainted);
    return static_cast<double>(count) * h_ * h_;
  }
  /// Passes through each piece of the reach left unpainted (4-connected cells) of at least
  /// `min_area`: lines along the piece's long axis (the principal axis of its cells; across it when
  /// that gives no pass), a spacing apart and centred on it, as many as its width across them
  /// needs (a piece one line wide whose middle line gives none: that line moved across); each
  /// stretch of a line whose points lie in F and within half a tool radius of the piece is a pass,
  /// kept when it runs at least `min_pass` and the workspace finds it free (its ends moved in by up
  /// to 3 cells otherwise), and for a forward-only car when it leaves room to turn out of both
  /// ends (leaveRoomToTurn).
  std::vector<CarRow> passes(Workspace& ws, double spacing, double min_area, double rho, bool forward_only, double min_pass) {
    std::vector<CarRow> out;
    std::vector<int> piece(cells_.size(), -1);
    std::vector<std::size_t> stack, members;
    int pieces = 0;
    for (std::size_t seed = 0; seed < cells_.size(); ++seed) {
      if (!open(seed) || piece[seed] >= 0) continue;
      members.clear();
      piece[seed] = pieces;
      stack.assign(1, seed);
      while (!stack.empty()) {
        const std::size_t c = stack.back();
        stack.pop_back();
        members.push_back(c);
        const int i = static_cast<int>(c % static_cast<std::size_t>(nx_)), j = static_cast<int>(c / static_cast<std::size_t>(nx_));
        for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          if (i + di < 0 || i + di >= nx_ || j + dj < 0 || j + dj >= ny_) continue;
          const std::size_t d = index(i + di, j + dj);
          if (open(d) && piece[d] < 0) {
            piece[d] = pieces;
            stack.push_back(d);
          }
        }
      }
      const int id = pieces++;
      if (static_cast<double>(members.size()) * h_ * h_ < min_area) continue;
      // The principal axis of the piece's cells.
      double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
      for (std::size_t c : members) {
        const Point p = centre(c) - origin_;
        sx += p.x, sy += p.y, sxx += p.x * p.x, syy += p.y * p.y, sxy += p.x * p.y;
      }
      const double n = static_cast<double>(members.size()), cx = sx / n, cy = sy / n;
      const double axis = 0.5 * std::atan2(2.0 * (sxy / n - cx * cy), (sxx / n - cx * cx) - (syy / n - cy * cy));
      const std::size_t before = out.size();
      for (int turn = 0; turn < 2 && out.size() == before; ++turn) {
        const double theta = axis + turn * M_PI / 2.0;
        const Point u{std::cos(theta), std::sin(theta)}, v{-u.y, u.x};
        double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
        for (std::size_t c : members) {
          const Point p = centre(c);
          lo_u = std::min(lo_u, dot(p, u)), hi_u = std::max(hi_u, dot(p, u));
          lo_v = std::min(lo_v, dot(p, v)), hi_v = std::max(hi_v, dot(p, v));
        }
        lo_v -= h_ / 2.0, hi_v += h_ / 2.0;
        const int lines = std::max(1, static_cast<int>(std::ceil((hi_v - lo_v) / spacing - 1e-9)));
        const int near = static_cast<int>(std::ceil(0.5 * r_ / h_));
        // A piece one line wide whose middle line gives no pass (it lies beyond F's edge, along a
        // wall or an obstacle): that line moved across by half a tool radius, then a whole one.
        const int tries = lines == 1 ? 5 : lines;
        for (int line = 0; line < tries; ++line) {
          if (lines == 1 && out.size() > before) break;
          const double shift = lines == 1 ? (line == 0 ? 0.0 : (line % 2 ? 1.0 : -1.0) * ((line + 1) / 2) * 0.5 * r_) : 0.0;
          const double at_v = (lo_v + hi_v) / 2.0 + (lines == 1 ? shift : (line - (lines - 1) / 2.0) * spacing);
          // Samples every half cell from a tool radius before the piece to a tool radius after it.
          const double step = h_ / 2.0;
          const int samples = static_cast<int>(std::ceil((hi_u - lo_u + 2.0 * r_) / step)) + 1;
          int first = -1;
          for (int k = 0; k <= samples; ++k) {
            const Point p = u * (lo_u - r_ + k * step) + v * at_v;
            const bool in = k < samples && inFree(p) && nearPiece(p, piece, id, near);
            if (in && first < 0) first = k;
            if (in || first < 0) continue;
            Point a = u * (lo_u - r_ + first * step) + v * at_v, b = u * (lo_u - r_ + (k - 1) * step) + v * at_v;
            first = -1;
            for (int shrink = 0; shrink < 3 && distance(a, b) >= min_pass && !ws.router().isFree(a, b); ++shrink) {
              a = a + u * h_;
              b = b - u * h_;
            }
            if (distance(a, b) < min_pass || dot(b - a, u) <= 0.0 || !ws.router().isFree(a, b)) continue;
            if (forward_only && !leaveRoomToTurn(ws, a, b, rho, rho, rho, min_pass)) continue;
            out.push_back({a, b, 0, false});
          }
        }
      }
    }
    return out;
  }

 private:
  static constexpr std::uint8_t kReach = 1, kFree = 2, kPainted = 4;
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i); }
  Point centre(std::size_t c) const {
    return origin_ + Point{(static_cast<double>(c % static_cast<std::size_t>(nx_)) + 0.5) * h_,
                           (static_cast<double>(c / static_cast<std::size_t>(nx_)) + 0.5) * h_};
  }
  bool open(std::size_t c) const { return (cells_[c] & kReach) && !(cells_[c] & kPainted); }
  bool cellOf(Point p, int& i, int& j) const {
    i = static_cast<int>(std::floor((p.x - origin_.x) / h_));
    j = static_cast<int>(std::floor((p.y - origin_.y) / h_));
    return i >= 0 && i < nx_ && j >= 0 && j < ny_;
  }
  bool inFree(Point p) const {
    int i = 0, j = 0;
    return cellOf(p, i, j) && (cells_[index(i, j)] & kFree);
  }
  /// Whether a cell of piece `id` lies within `near` cells of p's.
  bool nearPiece(Point p, const std::vector<int>& piece, int id, int near) const {
    int i = 0, j = 0;
    cellOf(p, i, j);
    for (int dj = -near; dj <= near; ++dj)
      for (int di = -near; di <= near; ++di)
        if (i + di >= 0 && i + di < nx_ && j + dj >= 0 && j + dj < ny_ && piece[index(i + di, j + dj)] == id) return true;
    return false;
  }
  /// Sets `bit` on the cells of row j whose centres lie in [x0, x1].
  void mark(int j, double x0, double x1, std::uint8_t bit) {
    const int i0 = std::max(0, static_cast<int>(std::ceil((x0 - origin_.x) / h_ - 0.5)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((x1 - origin_.x) / h_ - 0.5)));
    for (int i = i0; i <= i1; ++i) cells_[index(i, j)] |= bit;
  }
  /// Paints the capsule of the tool's radius round the segment p-q.
  void capsule(Point p, Point q) {
    capsuleRows(p, q, [&](int j, double lo, double hi) { mark(j, lo, hi, kPainted); });
  }
  /// The capsule of the tool's radius round the segment p-q, a row of cells at a time:
  /// `row(j, lo, hi)` with the span of the two end disks and the rectangle between them (their
  /// union is convex).
  template <class Row>
  void capsuleRows(Point p, Point q, Row&& row) const {
    const double len = distance(p, q);
    const Point nrm = len > 0.0 ? Point{-(q.y - p.y) / len, (q.x - p.x) / len} * r_ : Point{0.0, 0.0};
    const Point quad[4] = {p + nrm, q + nrm, q - nrm, p - nrm};
    const int j0 = std::max(0, static_cast<int>(std::ceil((std::min(p.y, q.y) - r_ - origin_.y) / h_ - 0.5)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((std::max(p.y, q.y) + r_ - origin_.y) / h_ - 0.5)));
    for (int j = j0; j <= j1; ++j) {
      const double y = origin_.y + (j + 0.5) * h_;
      double lo = INFINITY, hi = -INFINITY;
      for (const Point& c : {p, q}) {
        const double dy = y - c.y;
        if (std::fabs(dy) > r_) continue;
        const double half = std::sqrt(r_ * r_ - dy * dy);
        lo = std::min(lo, c.x - half), hi = std::max(hi, c.x + half);
      }
      if (len > 0.0)
        for (int e = 0; e < 4; ++e) {
          const Point a = quad[e], b = quad[(e + 1) % 4];
          if ((a.y - y) * (b.y - y) > 0.0 || a.y == b.y) continue;
          const double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
          lo = std::min(lo, x), hi = std::max(hi, x);
        }
      if (lo <= hi) row(j, lo, hi);
    }
  }

  double h_, r_;
  Point origin_;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint8_t> cells_;
};

/// Whether a fill round that paints `gained` m² more for `driven` m more path is kept: it paints
/// at least kFillMinYield of a band one spacing wide along what it adds (and something).
bool worthIt(double gained, double driven, double spacing) {
  return gained > 0.0 && gained >= kFillMinYield * spacing * std::max(driven, 0.0);
}

/// The sweep's reason: rows left out, the rings' skipped segments, a dead end at the end.
void describe(CarSweep& out) {
  char buf[240];
  if (out.unreached > 0) {
    const std::size_t not_reached = out.unreached - out.dead_both_ways;
    std::snprintf(buf, sizeof buf, "%s%zu of %zu rows left out", out.timed_out ? "time ran out; " : "", out.unreached, out.rows);
    out.reason = buf;
    if (out.dead_both_ways > 0) {
      std::snprintf(buf, sizeof buf, ": %zu dead ends both ways (from neither end did the car find a way on)%s", out.dead_both_ways,
                    not_reached > 0 ? "," : "");
      out.reason += buf;
    }
    if (not_reached > 0) {
      std::snprintf(buf, sizeof buf, "%s%zu no curve or route of the car reached", out.dead_both_ways > 0 ? " " : ": ", not_reached);
      out.reason += buf;
    }
  }
  if (out.headland.skipped > 0) {
    std::snprintf(buf, sizeof buf, "%sthe headland's rings: %zu segments replaced by the car's turns or skipped (%.3g m of ring not driven as planned)",
                  out.reason.empty() ? "" : "; ", out.headland.skipped, out.headland.cut_m);
    out.reason += buf;
  }
  if (out.headland.stopped)
    out.reason += std::string(out.reason.empty() ? "" : "; ") + "the rings stop where no curve the car can drive reaches further (the rest of them left out)";
  if (out.rings_as_passes > 0)
    out.reason += std::string(out.reason.empty() ? "" : "; ") +
                  "no row was reached from the rings' end: the rings were taken as passes with the rows";
  if (out.ended_in_dead_end) out.reason += std::string(out.reason.empty() ? "" : "; ") + "the path ends in a dead end the car cannot come out of";
  if (out.rounds_timed_out)
    out.reason += std::string(out.reason.empty() ? "" : "; ") +
                  "time ran out before the sweep's retries, fill rounds and strokes (passes through what it leaves unpainted) were done";
}

/// Strokes (a forward-only car, after the fill rounds): passes through what the path leaves
/// unpainted, each reached from where the path ends by a search over the car's motions
/// (searchCarUntil) to the nearest pose with a spacing of mostly unpainted reach (kStrokeOpen;
/// kStrokeOpenLast where none has) ahead: straight, or else on an arc of radius rho, left or
/// right; driven on while each half spacing finds enough unpainted (kStrokeOpenOn). The route
/// there paints where it passes over enough unpainted (kStrokeOpenOn). A stroke ends where the car
/// can come back to a pose it drove (an exact curve onto it that lies in F): then it drove a loop
/// through the path, and can go on. A circle it could drive there is not enough: it may circle in
/// a pocket with no way out. A sweep that ended in a dead-end row strokes from before it and takes
/// that row again last, when a search reaches it (and it paints more; else the row is left out,
/// unless the strokes painted all it would); else the last stroke, the straight one with the most
/// unpainted reach a search finds, may end in a dead end. Each stroke is kept when it paints more,
/// and all of them when what they paint is worth the path they add (worthIt, as a fill round).
/// `grid` shows what out.path paints (`painted_before`), before and after.
void strokes(Workspace& ws, CarSweep& out, PaintGrid& grid, double painted_before, double spacing, double rho, const Budget& budget) {
  Path path = out.ended_in_dead_end ? upTo(out.path, out.dead_end_from) : out.path;
  std::optional<Pose> row_from;  // the dead-end row's first pose, when the sweep ended in one
  if (out.ended_in_dead_end) {
    const std::size_t n = out.path.waypoints.size();
    const Point a = out.path.waypoints[n - 2], b = out.path.waypoints[n - 1];
    row_from = Pose{a, std::atan2(b.y - a.y, b.x - a.x)};
    grid.paint(path);
  }
  PathPoses driven(rho / 4.0);
  driven.add(path, 0);
  std::size_t poses = 0, count = 0;
  // Whether the car can go on from `at`: come back onto the path.
  auto goesOn = [&](Pose at) {
    return searchCarUntil(ws, at, rho, kStrokeLoopExpansions, [&](Pose q, Path& last) {
      const Pose* on = driven.near(q);
      return on && carCurveInto(q, *on, rho, false, false, last) && pathFree(ws, last);
    }, &poses).segments() > 0;
  };
  auto lineFree = [&](Point a, Point b) { return ws.router().isFree(a, b); };
  const double step = spacing / 2.0;
  bool dead_end_stroke = false;  // the stroke searched for may end in a dead end
  double open_share = kStrokeOpen;
  // The arc of radius rho from p, `length` along it (turning left when `left`; at most half a
  // circle), as a path of one segment (tool on), and the pose at its end.
  Path arc;
  auto arcTo = [&](Pose p, bool left, double length) {
    const double k = (left ? 1.0 : -1.0) / rho, h = p.heading + k * length;
    const Pose end{{p.at.x + (std::sin(h) - std::sin(p.heading)) / k, p.at.y - (std::cos(h) - std::cos(p.heading)) / k}, h};
    arc = Path{};
    arc.moveTo(p.at, true);
    arc.arcTo(end.at, std::tan(k * length / 4.0), true);
    return end;
  };
  auto arcStroke = [&](Pose p, Path& last) {
    for (const bool left : {true, false}) {
      double length = spacing;
      Pose end = arcTo(p, left, length);
      if (!grid.openAlong(arc, 0, open_share) || !pathFree(ws, arc)) continue;
      for (; length + step <= M_PI * rho; length += step) {
        const Pose next = arcTo(end, left, step);
        if (!grid.openAlong(arc, 0, kStrokeOpenOn) || !pathFree(ws, arc)) break;
        end = next;
      }
      for (; length >= spacing - 1e-9 && !goesOn(end); length -= step) end = arcTo(p, left, length - step);
      if (length < spacing - 1e-9) continue;
      arcTo(p, left, length);
      last = arc;
      return true;
    }
    return false;
  };
  auto stroke = [&](Pose p, Path& last) {
    const Point dir{std::cos(p.heading), std::sin(p.heading)};
    Point b = p.at + dir * spacing;
    if (!enoughOpen(grid.openIn(p.at, b), open_share) || !lineFree(p.at, b)) return !dead_end_stroke && arcStroke(p, last);
    for (int k = 0; k < kStrokeSteps; ++k) {
      const Point c = b + dir * step;
      if (!enoughOpen(grid.openIn(b, c), kStrokeOpenOn) || !lineFree(b, c)) break;
      b = c;
    }
    if (!dead_end_stroke)
      while (!goesOn({b, p.heading})) {
        b = b - dir * step;
        if (distance(p.at, b) < spacing - 1e-9) return arcStroke(p, last);
      }
    last = Path{};
    last.moveTo(p.at, true);
    last.moveTo(b, true);
    return true;
  };
  // The route to the nearest stroke and the stroke: the search at cells of R/2, and where it finds
  // none, at cells twice and four times finer (kStrokeFinestSearch), while the budget lasts.
  auto searchStroke = [&] {
    Path route;
    for (int fineness = 1; fineness <= kStrokeFinestSearch && route.segments() == 0 && poses < kStrokeBudget; fineness *= 2)
      route = searchCarUntil(ws, endPose(path), rho, std::min(kStrokeExpansions, kStrokeBudget - poses), stroke, &poses, fineness);
    return route;
  };
  // ...and where there is none, the nearest at kStrokeOpenLast.
  auto findStroke = [&] {
    Path route = searchStroke();
    if (route.segments() == 0) {
      open_share = kStrokeOpenLast;
      route = searchStroke();
      open_share = kStrokeOpen;
    }
    return route;
  };
  // Appends `route` when it paints more: its last segment (the stroke) painted, and each segment
  // before it that passes over enough unpainted (kStrokeOpenOn). False (and the path as it was)
  // otherwise.
  auto take = [&](Path& route) {
    if (route.segments() == 0) return false;
    for (std::size_t k = 0; k + 1 < route.segments(); ++k) route.tool_on[k] = grid.openAlong(route, k, kStrokeOpenOn);
    route.tool_on.back() = true;
    const double before = grid.painted();
    const std::size_t first = path.segments();
    append(path, route);
    grid.paintMore(path, first);
    if (!(grid.painted() > before)) {
      path = upTo(path, first + 1);
      grid.paint(path);
      return false;
    }
    driven.add(path, first);
    return true;
  };
  // The time limit ends the strokes where it is found to have passed (the plan is then partial).
  bool timed_out = false;
  auto expired = [&] { return timed_out = timed_out || budget.expired(); };
  for (; count < kStrokes && poses < kStrokeBudget && !expired(); ++count) {
    Path route = findStroke();
    if (!take(route)) break;
  }
  // The dead-end row again, or a last stroke that may end in a dead end.
  bool row_reached = false, row_again = false, dead_end = false;
  const std::size_t before_end = path.waypoints.size();
  if (row_from && !expired()) {
    Path route = searchCarRoute(ws, endPose(path), *row_from, rho, false, kSearchExpansions, &poses);
    if (route.segments() > 0) {
      route.moveTo(out.path.waypoints.back(), true);
      row_reached = true;
      row_again = dead_end = take(route);  // not taken: the strokes painted all it would
    }
  }
  if (!row_again && !expired()) {
    // The stroke with the most unpainted reach of all the search finds (it looks at every pose it
    // reaches), then the same search again, stopped at that stroke.
    dead_end_stroke = true;
    std::size_t most = 0;
    std::optional<Pose> best;
    int fineness = 1;
    for (; fineness <= kStrokeFinestSearch && poses < kStrokeBudget; fineness *= 2) {
      searchCarUntil(ws, endPose(path), rho, std::min(kStrokeExpansions, kStrokeBudget - poses), [&](Pose q, Path& last) {
        if (stroke(q, last)) {
          const std::size_t open_cells = grid.openIn(last.waypoints.front(), last.waypoints.back()).first;
          if (open_cells > most) most = open_cells, best = q;
        }
        return false;
      }, &poses, fineness);
      if (best) break;
    }
    Path route;
    if (best)
      route = searchCarUntil(ws, endPose(path), rho, kStrokeExpansions, [&](Pose q, Path& last) {
        return q.at == best->at && q.heading == best->heading && stroke(q, last);
      }, &poses, fineness);
    if (take(route)) {
      ++count;
      dead_end = true;
    }
  }
  if (!worthIt(grid.painted() - painted_before, pathLength(path) - pathLength(out.path), spacing)) {
    grid.paint(out.path);
    if (timed_out) out.rounds_timed_out = true;
    return;
  }
  if (row_from && !row_reached) {
    // The dead-end row is left out: a row left out (no route reached it from the strokes' end),
    // or one fill pass fewer.
    if (out.dead_end_fill) --out.fill_passes;
    else ++out.unreached;
  }
  if (dead_end && !row_again) {
    const std::size_t n = path.waypoints.size();
    out.dead_end_row = {path.waypoints[n - 2], path.waypoints[n - 1], 0, false, kAnyCell};
  }
  out.path = std::move(path);
  out.strokes = count;
  out.ended_in_dead_end = dead_end;
  if (dead_end) out.dead_end_from = before_end;
  if (!row_again) out.dead_end_fill = false;
  if (timed_out) out.rounds_timed_out = true;
  checkDrivable(out.path, ws.vehicle(), "the car's strokes");
}

/// A car's transits paint where they pass over enough unpainted reach (kStrokeOpenOn), as a
/// stroke's route does: the path's tool-off segments in order, each against
/// what the path paints and the transits turned on before it. `grid` shows what the path paints.
void paintTransits(CarSweep& out, PaintGrid& grid) {
  Path& path = out.path;
  for (std::size_t i = 0; i < path.segments(); ++i) {
    if (path.tool_on[i] || !grid.openAlong(path, i, kStrokeOpenOn)) continue;
    path.tool_on[i] = true;
    grid.paintSegment(path, i);
    ++out.painted_transits;
  }
}

}  // namespace

CarSweep carSweep(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& given, double spacing,
                  const Budget& budget, bool fill, double line_penalty) {
  CarSweep out = sweepOnce(ws, rings, loops, given, {}, spacing, budget, line_penalty);
  const VehicleModel& car = ws.vehicle();
  const double rho = car.turn_radius * (1.0 + kCarRadiusSlack);
  // Cells of a fifth of a spacing, at most about kFillMaxCells of them.
  const Box box = boundingBox(ws.free());
  const double cell = std::max(spacing / 5.0, std::sqrt((box.max_x - box.min_x + 1.0) * (box.max_y - box.min_y + 1.0) / kFillMaxCells));
  std::optional<PaintGrid> grid;
  // No row reached from where the rings end (a pocket the car cannot turn out of, and giving up
  // their end did not get it out): the sweep again with the rings as passes ordered with the
  // rows (sweepOnce's rings_as_passes), kept when it paints more.
  if (out.rows > 0 && out.unreached == out.rows && !loops.empty()) {
    std::optional<double> painted;  // what out.path paints, measured once
    for (int way = 1; way <= 2 && out.rings_as_passes == 0 && !out.timed_out; ++way) {
      if (budget.expired()) {
        out.rounds_timed_out = true;
        break;
      }
      PathBuilder other(ws);
      CarSweep passes_first = sweepOnce(ws, other, loops, given, {}, spacing, budget, line_penalty, nullptr, way);
      if (passes_first.timed_out) out.rounds_timed_out = true;
      if (passes_first.timed_out || passes_first.unreached == passes_first.rows) continue;
      if (!grid) grid.emplace(ws, cell);
      if (!painted) {
        grid->paint(out.path);
        painted = grid->painted();
      }
      grid->paint(passes_first.path);
      if (grid->painted() > *painted) {
        rings = other;
        out = std::move(passes_first);
      }
    }
    if (grid && out.rings_as_passes == 0) grid->paint(out.path);  // the fill rounds start from out.path's paint
  }
  // A forward-only car that leaves most rows out and starts in a pocket (startsInPocket: as on
  // random-s7-0001, a pocket of 1.7 m x 1.2 m that a slot narrower than its turns closes, where
  // every planner painted 0.05 of R): the sweep again with the rings started at their first
  // ring's next longest edges (up to kRingStarts), until one starts out of a pocket, kept when it
  // paints more.
  if (!car.reverse && out.rings_as_passes == 0 && !loops.empty() && !out.timed_out && 2 * out.unreached > out.rows &&
      startsInPocket(ws, out.path, rho)) {
    for (std::size_t e = 1; e < kRingStarts; ++e) {
      if (budget.expired()) {
        out.rounds_timed_out = true;
        break;
      }
      PathBuilder other(ws);
      CarSweep again = sweepOnce(ws, other, loops, given, {}, spacing, budget, line_penalty, nullptr, 0, e);
      if (again.timed_out) {
        out.rounds_timed_out = true;
        break;
      }
      if (again.ring_start != e) break;  // the first ring has no more edges
      if (startsInPocket(ws, again.path, rho)) continue;
      if (!grid) grid.emplace(ws, cell);
      grid->paint(out.path);
      const double before = grid->painted();
      grid->paint(again.path);
      if (grid->painted() > before) {
        rings = other;
        out = std::move(again);
      } else {
        grid->paint(out.path);
      }
      break;
    }
  }
  // Fill rounds: passes through what the path leaves unpainted (PaintGrid::passes), driven from
  // where it ends (before its last row, when that is a dead end: that row is taken again with
  // them), or, where the car reaches none of them so, the whole sweep planned again with every
  // round's passes taken last. A round is kept when what it paints more is worth the path it adds
  // (worthIt); the rounds stop at the first that is not kept.
  std::vector<CarRow> all;  // every round's passes
  bool grid_shows_out = grid.has_value();  // the grid shows what out.path paints
  std::optional<double> out_painted;       // what out.path paints, when measured
  int resweeps = 0;
  for (int round = 0; fill && round < kFillRounds && !out.timed_out && out.path.segments() > 0; ++round) {
    if (budget.expired()) {
      out.rounds_timed_out = true;
      break;
    }
    // The grid shows what out.path paints from the second round on (below).
    if (!grid) {
      grid.emplace(ws, cell);
      grid->paint(out.path);
      grid_shows_out = true;
    }
    const double painted = grid->painted();
    out_painted = painted;
    const std::vector<CarRow> passes = grid->passes(ws, spacing, kFillMinArea * spacing * spacing, rho, !car.reverse, kFillMinPass * spacing);
    if (passes.empty()) break;
    all.insert(all.end(), passes.begin(), passes.end());
    Path start = out.ended_in_dead_end ? upTo(out.path, out.dead_end_from) : out.path;
    std::vector<CarRow> again;
    if (out.ended_in_dead_end) {
      again.push_back(out.dead_end_row);
      again.back().row = false;
    }
    PathBuilder none(ws);
    const CarSweep more = sweepOnce(ws, none, {}, again, passes, spacing, budget, line_penalty, &start);
    if (more.timed_out) {
      out.rounds_timed_out = true;
      break;
    }
    const bool reached = more.fill_passes > 0;
    bool reached_but_not_worth = false;
    if (reached) {
      // The continuation is out.path and more, unless it left out the dead-end last row.
      if (again.empty()) grid->paintMore(more.path, out.path.segments());
      else grid->paint(more.path);
      grid_shows_out = false;
      if (!worthIt(grid->painted() - painted, pathLength(more.path) - pathLength(out.path), spacing)) {
        // Not worth it from there: the whole sweep again (it costs as much as the first), once,
        // and only where much is left (PaintGrid::reach).
        if (resweeps > 0 || painted > (1.0 - kFillResweepLeft) * grid->reach()) break;
        reached_but_not_worth = true;
      }
    }
    if (reached && !reached_but_not_worth) {
      // The dead-end last row taken again (the continuation's one given row) and left out: a row
      // left out, or, when it was a fill pass, one fill pass fewer.
      const bool again_fill = !again.empty() && out.dead_end_fill;
      const bool again_left = !again.empty() && more.unreached > 0;
      if (again_left && again_fill) {
        --out.fill_passes;
      } else {
        out.unreached += more.unreached;
        out.dead_both_ways += more.dead_both_ways;
      }
      out.path = more.path;
      grid_shows_out = true;
      out_painted.reset();
      out.links = out.links + more.links - (again.empty() ? 0 : 1);  // the link into the row taken again
      out.routed += more.routed;
      out.searched += more.searched;
      out.cusps += more.cusps;
      out.backtracks += more.backtracks;
      out.undriven_m += more.undriven_m;
      out.fill_passes += more.fill_passes;
      out.ended_in_dead_end = more.ended_in_dead_end;
      out.dead_end_from = more.dead_end_from;
      out.dead_end_row = more.dead_end_row;
      // The continuation's only row that is no fill pass is the row taken again (it has no rings).
      out.dead_end_fill = more.ended_in_dead_end && (more.dead_end_fill || again_fill);
      continue;
    }
    ++resweeps;
    PathBuilder other(ws);
    CarSweep again_whole = sweepOnce(ws, other, loops, given, all, spacing, budget, line_penalty, nullptr, out.rings_as_passes, out.ring_start);
    if (again_whole.timed_out) out.rounds_timed_out = true;
    if (again_whole.timed_out || again_whole.fill_passes == 0) break;
    grid->paint(again_whole.path);
    grid_shows_out = false;
    if (!worthIt(grid->painted() - painted, pathLength(again_whole.path) - pathLength(out.path), spacing)) break;
    rings = other;
    out = std::move(again_whole);
    grid_shows_out = true;
    out_painted.reset();
  }
  // Where the path leaves more than kStrokeMinLeft of the reach unpainted: strokes through what is
  // left (a forward-only car; strokes()), and the transits paint where they pass over it
  // (paintTransits).
  if (fill && !out.timed_out && out.path.segments() > 0) {
    if (!grid) grid.emplace(ws, cell);
    if (!out_painted) {
      if (!grid_shows_out) grid->paint(out.path);
      grid_shows_out = true;
      out_painted = grid->painted();
    }
    if (*out_painted < (1.0 - kStrokeMinLeft) * grid->reach()) {
      if (!grid_shows_out) grid->paint(out.path);
      if (!car.reverse) strokes(ws, out, *grid, *out_painted, spacing, rho, budget);
      paintTransits(out, *grid);
    }
  }
  describe(out);
  return out;
}

void recordCarSweep(PlanResult& result, const CarSweep& sweep) {
  result.stats["car_rows"] = static_cast<double>(sweep.rows);
  result.stats["car_rows_unreached"] = static_cast<double>(sweep.unreached);
  result.stats["car_rows_dead_both_ways"] = static_cast<double>(sweep.dead_both_ways);
  result.stats["car_links"] = static_cast<double>(sweep.links);
  result.stats["car_routed_links"] = static_cast<double>(sweep.routed);
  result.stats["car_searched_links"] = static_cast<double>(sweep.searched);
  result.stats["car_ends_in_dead_end"] = sweep.ended_in_dead_end ? 1.0 : 0.0;
  result.stats["car_rings_stopped"] = sweep.headland.stopped ? 1.0 : 0.0;
  result.stats["car_rings_as_passes"] = sweep.rings_as_passes > 0 ? 1.0 : 0.0;
  result.stats["car_backtracks"] = static_cast<double>(sweep.backtracks);
  result.stats["car_cusps"] = static_cast<double>(sweep.cusps + sweep.headland.cusps);
  result.stats["car_ring_fillets"] = static_cast<double>(sweep.headland.fillets);
  result.stats["car_ring_turns"] = static_cast<double>(sweep.headland.turns);
  result.stats["car_skipped_segments"] = static_cast<double>(sweep.headland.skipped);
  result.stats["car_ring_searched_skips"] = static_cast<double>(sweep.headland.searched);
  result.stats["car_ring_passes"] = static_cast<double>(sweep.ring_passes);
  result.stats["car_fill_passes"] = static_cast<double>(sweep.fill_passes);
  result.stats["car_strokes"] = static_cast<double>(sweep.strokes);
  result.stats["car_painted_transits"] = static_cast<double>(sweep.painted_transits);
  result.stats["car_undriven_m"] = sweep.headland.cut_m + sweep.undriven_m;
  if (sweep.unreached > 0 || sweep.timed_out || sweep.rounds_timed_out || sweep.headland.stopped) {
    if (result.status == PlanStatus::Ok) result.status = PlanStatus::Partial;
  }
  if (!sweep.reason.empty()) result.reason += (result.reason.empty() ? "" : "; ") + sweep.reason;
}

}  // namespace coverbench
