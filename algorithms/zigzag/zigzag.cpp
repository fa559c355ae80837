#include "zigzag.hpp"

#include <algorithm>
#include <cmath>

#include "coverbench/headland.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/shape_rows.hpp"
#include "coverbench/sweep_search.hpp"
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/car_sweep.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::zigzag {
namespace {

/// How far the chords of the rows' regions may cut inside their arcs (metres): coarse, so they
/// have few vertices (rows end at most this much short of where they could).
constexpr double kRowArcTolerance = 1e-3;

/// Where a row crosses a ring edge of the row region.
using Crossing = RingCrossing;

using Interval = RowInterval;

/// The shorter walk along a ring from a point on edge e1 to a point on edge e2.
std::vector<Point> ringWalk(const Ring& ring, Point from, std::size_t e1, Point to, std::size_t e2) {
  if (e1 == e2) return {from, to};
  const std::size_t n = ring.size();
  std::vector<Point> forward{from}, backward{from};
  for (std::size_t e = e1; e != e2; e = (e + 1) % n) forward.push_back(ring[(e + 1) % n]);
  forward.push_back(to);
  for (std::size_t e = e1; e != e2; e = (e + n - 1) % n) backward.push_back(ring[e]);
  backward.push_back(to);
  return polylineLength(forward) <= polylineLength(backward) ? forward : backward;
}

/// The planner's parameters (paramTable declares them).
struct ZigzagParams {
  SweepDirection sweep;
  double overlap = 0.0;
  double coat_ripple = 0.0;
  double trigger_speed = 0.0;
  long long boundary_passes = 1;
  double row_end_inset = 0.6;
  bool fill_leftovers = false;
  CarPlan car_plan = CarPlan::Headland;
};

const ParamTable<ZigzagParams>& paramTable() {
  static const ParamTable<ZigzagParams> table =
      ParamTable<ZigzagParams>()
          .include(&ZigzagParams::sweep, sweepDirectionParams())
          .add({"overlap", ParamType::Number, 0.0, 0.0, 0.9, {}, "", "fraction of the tool width adjacent rows overlap"},
               &ZigzagParams::overlap)
          .add(coatRippleParam(), &ZigzagParams::coat_ripple)
          .add(triggerSpeedParam(), &ZigzagParams::trigger_speed)
          .add({"boundary_passes", ParamType::Integer, 1LL, 0, 10, {}, "",
                "boundary-following loops around the wall and each obstacle before the rows"},
               &ZigzagParams::boundary_passes)
          .add(rowEndInsetParam(), &ZigzagParams::row_end_inset)
          .add(fillLeftoversParam(), &ZigzagParams::fill_leftovers)
          .add(carPlanParam(), &ZigzagParams::car_plan, carPlanChoices());
  return table;
}

class ZigzagPlanner final : public TypedPlanner<ZigzagParams> {
 public:
  ZigzagPlanner() : TypedPlanner(paramTable()) {}

 protected:
  PlanResult planWith(const Problem& problem, const ZigzagParams& given, const Budget& budget) override {
    ZigzagParams params = given;
    // A car comes only with car_plan headland or headland_no_fill: for smoothed, runPlanner gives
    // a tool that turns on the spot and smooths the path.
    return planRows(problem, params.coat_ripple, params.overlap, params.trigger_speed, params.sweep, budget,
                    [&](double angle_deg) { return planAt(problem, params, budget, angle_deg); });
  }

 private:
  /// For a car (car_plan: headland): as many rings as its turns need, then the rows in an order
  /// its curves link (car_sweep.hpp).
  PlanResult planForCar(const Problem& problem, const ZigzagParams& params, const Budget& budget, double angle,
                        PlanFrame& frame) {
    const double spacing = problem.tool.tool_width * (1.0 - params.overlap);
    Workspace& ws = frame.ws();
    Headland h = headland(ws, frame.covered(),
                          carHeadlandOptions(problem, spacing, static_cast<std::size_t>(params.boundary_passes),
                                             params.row_end_inset, kRowArcTolerance, true));
    std::vector<CarRow> rows = carHolePasses(ws, h.loops, spacing);
    const Box box = h.row_span;
    const std::vector<double> heights = box.empty() ? std::vector<double>{} : rowHeights(box.min_y, box.max_y, spacing);
    if (!heights.empty())
      for (const auto& line : rowIntervals(allRings(h.ends), heights))
        for (const Interval& iv : line) rows.push_back({iv.lowEnd(), iv.highEnd(), iv.row});
    PathBuilder builder(ws);
    const CarSweep sweep = carSweep(ws, builder, h.loops, rows, spacing, budget, params.car_plan == CarPlan::Headland);
    PlanResult result = carSweepPlan(sweep, builder, h.loops.size(), angle, frame.components().size());
    result.stats["rows"] = static_cast<double>(heights.size());
    result.stats["row_spacing"] = heights.size() > 1 ? heights[1] - heights[0] : 0.0;
    result.stats["intervals"] = static_cast<double>(rows.size());
    return result;
  }

  /// A line or rectangle tool on a gantry or a holonomic robot: its own rows (shape_rows.hpp), not
  /// its circumscribed disk's, each time the nearest end next. `frame` is the circumscribed disk's.
  PlanResult planLineRows(const Problem& problem, const ZigzagParams& params, double spacing, const Budget& budget,
                          PlanFrame& frame, double angle_deg) {
    ShapeRowsOptions options;
    options.spacing = spacing;
    options.loops = static_cast<std::size_t>(params.boundary_passes);
    options.end_inset = params.row_end_inset;
    options.arc_tolerance = kRowArcTolerance;
    return planShapeRows(problem, frame, options, angle_deg, budget,
                         [](const ShapeRowPieces& rows, Point from, bool) { return nearestEndOrder(rows.pieces, from); });
  }

  PlanResult planAt(const Problem& problem, const ZigzagParams& params, const Budget& budget, double angle_deg) {
    const double angle = angle_deg * M_PI / 180.0;
    const double spacing = problem.tool.tool_width * (1.0 - params.overlap);
    const auto passes = static_cast<std::size_t>(params.boundary_passes);

    // Work in a frame where rows are horizontal; the result is turned back at the end.
    if (problem.tool.turnsWithHeading() && !problem.vehicle.isCar()) {
      Problem disk = problem;
      disk.tool = circumscribedDisk(problem.tool);
      PlanFrame disk_frame(disk, angle);
      return planLineRows(problem, params, spacing, budget, disk_frame, angle_deg);
    }
    PlanFrame frame(problem, angle);
    if (frame.empty()) return PlanFrame::fitsNowhere();
    if (problem.vehicle.isCar()) return planForCar(problem, params, budget, angle, frame);
    Workspace& ws = frame.ws();

    // Loops along F's boundary first, then rows clear of their paint (headland.hpp), then, with
    // fill_leftovers, a pass for each piece both left.
    HeadlandOptions layout;
    layout.spacing = spacing;
    layout.radius = problem.tool.tool_width / 2.0;
    layout.loops = passes;
    layout.end_inset = params.row_end_inset;
    layout.arc_tolerance = kRowArcTolerance;
    layout.with_unpainted = params.fill_leftovers;
    const Headland h = headland(ws, frame.covered(), layout);
    PathBuilder builder(ws);
    std::size_t unreachable = coverRings(builder, h.loops, 1.01 * spacing);
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in boundary passes");
    const std::size_t rows_from = builder.path().segments();
    const std::vector<Ring> rings = allRings(h.ends);
    const Box box = h.row_span;
    // The rows' span may hold several parts of F (pinched by obstacles), so a row may be empty.
    const std::vector<double> heights = box.empty() ? std::vector<double>{} : rowHeights(box.min_y, box.max_y, spacing);
    std::vector<std::vector<Interval>> rows;
    if (!heights.empty()) rows = rowIntervals(rings, heights);
    const double row_gap = heights.size() > 1 ? heights[1] - heights[0] : 0.0;

    std::size_t remaining = 0, pieces = 0;
    for (const auto& row : rows) remaining += row.size();
    const std::size_t interval_count = remaining;
    while (remaining > 0) {
      if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in rows");
      // Start a new piece at the unvisited interval end nearest to where we are.
      Interval* cur = nullptr;
      bool rightward = true;
      double best = INFINITY;
      for (auto& row : rows)
        for (Interval& iv : row) {
          if (iv.done) continue;
          const double dl = builder.empty() ? iv.y * 1e6 + iv.lo.x : distance(builder.current(), iv.lowEnd());
          const double dh = builder.empty() ? INFINITY : distance(builder.current(), iv.highEnd());
          if (dl < best) best = dl, cur = &iv, rightward = true;
          if (dh < best) best = dh, cur = &iv, rightward = false;
        }
      const Point entry = rightward ? cur->lowEnd() : cur->highEnd();
      cur->done = true;
      --remaining;
      if (!builder.moveTo(entry, !builder.empty() && distance(builder.current(), entry) <= 1.01 * row_gap)) {
        ++unreachable;
        continue;
      }
      ++pieces;
      int vertical = 0;  // +1 up, -1 down, 0 not chosen yet
      while (true) {
        builder.moveTo(rightward ? cur->highEnd() : cur->lowEnd(), true);
        const Crossing& exit = rightward ? cur->hi : cur->lo;
        const Point exit_point{exit.x, cur->y};
        Interval* next = nullptr;
        std::vector<Point> link;
        for (int dir : {1, -1}) {
          if (vertical != 0 && dir != vertical) continue;
          const long j = static_cast<long>(cur->row) + dir;
          if (j < 0 || j >= static_cast<long>(rows.size())) continue;
          // Candidates: unvisited intervals overlapping this one, nearest entry first.
          std::vector<Interval*> candidates;
          for (Interval& iv : rows[static_cast<std::size_t>(j)])
            if (!iv.done && iv.lo.x <= cur->hi.x && iv.hi.x >= cur->lo.x) candidates.push_back(&iv);
          std::sort(candidates.begin(), candidates.end(), [&](Interval* p, Interval* q) {
            const double xp = rightward ? p->hi.x : p->lo.x, xq = rightward ? q->hi.x : q->lo.x;
            return std::fabs(xp - exit.x) < std::fabs(xq - exit.x);
          });
          for (Interval* c : candidates) {
            const Crossing& in = rightward ? c->hi : c->lo;
            const Point entry_point{in.x, c->y};
            if (ws.router().isFree(exit_point, entry_point)) {
              link = {entry_point};
            } else if (in.ring == exit.ring) {
              // Follow the region's own boundary between the rows: it lies in F.
              std::vector<Point> walk = ringWalk(rings[exit.ring], exit_point, exit.edge, entry_point, in.edge);
              if (polylineLength(walk) <= 2.0 * spacing + 2.0 * distance(exit_point, entry_point)) link = walk;
            }
            if (!link.empty()) {
              next = c;
              vertical = dir;
              break;
            }
          }
          if (next) break;
        }
        if (!next) break;
        builder.follow(link, true);
        cur = next;
        cur->done = true;
        --remaining;
        rightward = !rightward;
      }
    }
    // What the loops and rows left, when asked (see fillLeftoversParam).
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in rows");
    const bool fill = params.fill_leftovers;
    const Leftovers left =
        fill ? coverLeftovers(ws, builder, h.unpainted, rows_from, spacing, problem.tool.tool_width / 2.0, true)
             : Leftovers{};
    unreachable += left.unreachable;

    PlanResult result = frame.finish(builder, unreachable);
    result.stats["rows"] = static_cast<double>(rows.size());
    result.stats["row_spacing"] = row_gap;
    result.stats["intervals"] = static_cast<double>(interval_count);
    result.stats["pieces"] = static_cast<double>(pieces);
    if (fill) recordLeftovers(result, left);
    return result;
  }
};

}  // namespace

PlannerInfo info() {
  return typedPlannerInfo<ZigzagPlanner>(
      {.name = "zigzag", .version = "18", .code_folders = {"zigzag"},
       .summary = "Boustrophedon rows over the free region, alternating direction, with boundary-following passes",
       .reference = "Galceran & Carreras, A survey on coverage path planning for robotics, RAS 2013",
       .min_coverage_reachable = 0.995, .plans_for_car = true, .plans_shapes = true},
      paramTable());
}

}  // namespace coverbench::zigzag
