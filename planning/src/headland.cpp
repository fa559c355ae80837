#include "coverbench/headland.hpp"

#include <algorithm>
#include <cmath>

#include "coverbench/input_error.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

/// Chords of the painted capsules: coarse (they only decide which pieces need a pass), and lying
/// inside the true capsules, so a piece is never missed.
constexpr double kPaintArcTolerance = 5e-4;

/// The parts of `region` that lie in `part` (each lies wholly inside F and so in one part of it;
/// its first vertex, strictly inside F, tells which).
Region within(const Region& region, const Region& part) {
  Region out;
  for (const PolygonWithHoles& poly : region)
    for (const PolygonWithHoles& p : part)
      if (pointInPolygon(p, poly.outer.front())) {
        out.push_back(poly);
        break;
      }
  return out;
}

}  // namespace

Headland headland(const Workspace& ws, const Region& free, const HeadlandOptions& o) {
  Headland h;
  if (o.loops == 0) {
    h.inner = h.ends = free;
    h.row_span = boundingBox(free);
    return h;
  }
  Region last = free;
  for (std::size_t k = 0; k < o.loops; ++k) {
    if (k > 0) last = offsetRegion(free, -static_cast<double>(k) * o.spacing, o.arc_tolerance);
    for (Ring& ring : allRings(last)) h.loops.push_back(std::move(ring));
  }
  // The rows' regions are F drawn deeper inside, straight from the wall (cheap: the obstacles as
  // given, not F's many arc vertices), with chords of `tol` (few vertices). A chord may cut up to
  // `tol` into an obstacle's rounded margin; every region is drawn at least `tol` deeper than the
  // planners' F, so it still lies inside F.
  const double tol = o.arc_tolerance;
  const double depth = kFreeSpaceMargin + static_cast<double>(o.loops - 1) * o.spacing;  // of the last loop
  auto inside = [&](double d) { return within(freeRegion(ws.wall(), ws.tool(), depth + d, tol), free); };
  const Region base = inside(tol);
  // `inner` only places the first and last rows, so it is drawn from the outer rings alone: the
  // holes would cost most of the offset and move its extent only where obstacles span the wall.
  Region outline;
  for (const PolygonWithHoles& poly : base) outline.push_back({poly.outer, {}});
  h.inner = offsetRegion(outline, -(o.spacing - tol), tol);
  // A row answers for the strip half a spacing either side of it: it runs as far as the ends
  // region reaches anywhere in that strip (past a slanted edge, under an obstacle just above),
  // and never out of F.
  const Point half = o.along_x ? Point{0.0, o.spacing / 2.0} : Point{o.spacing / 2.0, 0.0};
  // (At least `tol` deep, as every region here: an inset of 0 ends rows on the loop's line.)
  Region reach = inside(std::fmax(o.end_inset * o.spacing, tol));
  if (o.end_inset > 0.5) {
    // Thin parts: F half a spacing deep (where rows can end without leaving anything unpainted)
    // that the deeper region, opened back out by the difference, does not reach: a corridor too
    // narrow for the deeper inset, such as the one between a window's loop and the wall's. Rows
    // there end half a spacing inside the loop, so the corridor is still painted. The slivers an
    // opening leaves at convex corners are far below kMinLeftoverArea and are left out.
    const Region full = inside(0.5 * o.spacing);
    const Region opened = offsetRegion(reach, (o.end_inset - 0.5) * o.spacing + tol, tol);
    Region thin;
    for (PolygonWithHoles& piece : subtract(full, opened))
      if (area(piece) >= kMinLeftoverArea * o.spacing * o.spacing) thin.push_back(std::move(piece));
    if (!thin.empty()) reach = unite(reach, thin);
  }
  h.ends = intersect(sweepAlong(reach, half), base);
  // Rows span `inner` across their direction; where F has thin parts beyond it (a corridor
  // between a door and a radiator, a strip too thin for `inner` anywhere), the rows' span grows
  // to reach them. `reach` always extends half a spacing beyond `inner`, and beyond a corner of
  // interior angle a by (s/2) / sin(a/2): 0.11 m for the sharpest gable ridge generated (54
  // degrees) at s = 0.1; a part reaching farther than 1.5 spacings is a thin part.
  const Box in = boundingBox(h.inner), far = boundingBox(reach);
  h.row_span = in.empty() ? far : in;
  if (!in.empty() && !far.empty()) {
    const double grace = 1.5 * o.spacing;
    if (o.along_x) {
      if (far.min_y < in.min_y - grace) h.row_span.min_y = far.min_y;
      if (far.max_y > in.max_y + grace) h.row_span.max_y = far.max_y;
    } else {
      if (far.min_x < in.min_x - grace) h.row_span.min_x = far.min_x;
      if (far.max_x > in.max_x + grace) h.row_span.max_x = far.max_x;
    }
  }
  if (o.with_unpainted) h.unpainted = inside(o.radius);
  return h;
}

ParamSpec rowEndInsetParam() {
  return {"row_end_inset", ParamType::Number, HeadlandOptions{}.end_inset, 0.0, 1.0, {}, "",
          "where rows end, in spacings inside the boundary loop: 0.5 paints everything; more paints less "
          "twice but leaves scallops between row ends (docs/planner_quality.md); less runs them into the "
          "loop's band, 0 to its line (a sprayed coat's evenness: docs/deposition.md). Only with a loop; a car's "
          "rows end at least 0.5 in (its turns), a line or rectangle tool's rows at F's edge"};
}

ParamSpec fillLeftoversParam() {
  return {"fill_leftovers", ParamType::Bool, false, 0, 0, {}, "",
          "after the rows, find what loops and rows left unpainted (exactly) and give each piece a pass; "
          "slower (docs/planner_quality.md)"};
}

ParamSpec coatRippleParam() {
  return {"coat_ripple", ParamType::Number, 0.0, 0.0, 0.5, {}, "",
          "0: rows `overlap` apart; else the coat's allowed ripple between rows (a fraction of its mean): rows "
          "at the widest spacing whose summed flux profile stays that even (needs a tool with a flux profile; "
          "docs/deposition.md)"};
}

std::string evenCoatOverlap(const ToolParams& tool, double coat_ripple, double& overlap) {
  if (!(coat_ripple > 0.0)) return "";
  if (!tool.profile.set())
    return "coat_ripple needs a tool with a flux profile (tool.profile in a config, --profile on the command line)";
  if (overlap != 0.0) return "coat_ripple sets the rows' overlap from the flux profile: leave overlap at 0";
  // One search per thread and tool: every sweep direction, and every run of the same tool, reuses it.
  thread_local struct {
    FluxProfile profile;
    double s = 0.0, ripple = 0.0, spacing = 0.0;
  } last;
  const FluxProfile& p = tool.profile;
  if (!(last.s == tool.tool_width && last.ripple == coat_ripple && last.profile.kind == p.kind &&
        last.profile.sigma == p.sigma && last.profile.beta == p.beta)) {
    last = {p, tool.tool_width, coat_ripple, evenSpacing(p, tool.tool_width, coat_ripple)};
  }
  if (!(last.spacing > 0.0))
    return "no row spacing down to s/10 keeps the " + toString(p.kind) + " profile's coat within " +
           shortNumber(coat_ripple * 100.0) + " % of its mean";
  overlap = 1.0 - last.spacing / tool.tool_width;
  return "";
}

void recordLeftovers(PlanResult& result, const Leftovers& left) {
  result.stats["leftover_passes"] = static_cast<double>(left.pieces);
  result.stats["leftover_small_pieces"] = static_cast<double>(left.small_pieces);
  result.stats["leftover_small_area_m2"] = left.small_area;
}

Leftovers coverLeftovers(Workspace& ws, PathBuilder& builder, const Region& unpainted, std::size_t from, double spacing,
                         double radius, bool along_x) {
  Leftovers out;
  if (unpainted.empty()) return out;
  const Path& path = builder.path();
  std::vector<std::vector<Point>> runs;
  for (std::size_t i = from; i < path.segments(); ++i) {
    if (!path.tool_on[i]) continue;
    if (runs.empty() || i == from || !path.tool_on[i - 1]) runs.push_back({path.waypoints[i]});
    std::vector<Point>& run = runs.back();
    const Point next = path.waypoints[i + 1];
    // Straight on through a waypoint: drop it (walks along cell sides repeat many in a line).
    if (run.size() >= 2 && std::fabs(cross(run.back() - run[run.size() - 2], next - run.back())) < 1e-12 &&
        dot(run.back() - run[run.size() - 2], next - run.back()) > 0.0)
      run.back() = next;
    else
      run.push_back(next);
  }
  const Region left = subtract(unpainted, sweptRegion(runs, radius, kPaintArcTolerance));
  const double min_area = kMinLeftoverArea * spacing * spacing;
  std::vector<Ring> rings;
  std::vector<std::pair<Point, Point>> passes;
  for (const PolygonWithHoles& piece : componentsByArea(left)) {
    const double a = area(piece);
    if (a < min_area) {
      ++out.small_pieces;
      out.small_area += a;
      continue;
    }
    ++out.pieces;
    // One pass through the middle when the piece is thinner than the tool across the rows.
    const Box box = boundingBox(piece.outer);
    const double across = along_x ? box.max_y - box.min_y : box.max_x - box.min_x;
    const double mid = along_x ? (box.min_y + box.max_y) / 2.0 : (box.min_x + box.max_x) / 2.0;
    const Point a0 = along_x ? Point{box.min_x, mid} : Point{mid, box.min_y};
    const Point a1 = along_x ? Point{box.max_x, mid} : Point{mid, box.max_y};
    if (across < 2.0 * radius * 0.98 && piece.holes.empty() && ws.router().isFree(a0, a1)) {
      passes.push_back({a0, a1});
      continue;
    }
    rings.push_back(piece.outer);
    for (const Ring& hole : piece.holes) rings.push_back(hole);
  }
  // The passes in greedy nearest order, each from its nearer end.
  std::vector<bool> done(passes.size(), false);
  for (std::size_t n = 0; n < passes.size(); ++n) {
    const auto [best, flip] = takeNearestPass(passes, done, builder.current());
    const auto [p, q] = flip ? std::pair{passes[best].second, passes[best].first} : passes[best];
    if (!builder.moveTo(p, false)) {
      ++out.unreachable;
      continue;
    }
    builder.follow({q}, true);
  }
  out.unreachable += coverRings(builder, rings, 1.01 * spacing);
  return out;
}

}  // namespace coverbench
