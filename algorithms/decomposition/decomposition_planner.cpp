#include "decomposition_planner.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include "cell_ordering.hpp"
#include "shape_cells.hpp"
#include "coverbench/headland.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/sweep_search.hpp"
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/car_sweep.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::decomposition {
namespace {

/// How far the chords of F's rounded corners may cut inside the arcs in the region the cells are
/// cut from (metres). The region is drawn this much farther inside F, so it stays inside F; the
/// band it leaves along F's boundary is what the boundary loop covers.
constexpr double kCellArcTolerance = 2e-3;

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// Where passes may run: `count + 1` evenly spaced x positions from `min` to `max`, no gap wider
/// than the pass spacing, shared by all cells so that thin cells next to each other do not each
/// round their own pass count up.
struct PassGrid {
  double min = 0.0, step = 1.0;
  std::size_t count = 0;
  double at(std::size_t k) const { return min + step * static_cast<double>(k); }
};

/// The x positions of a cell's passes, increasing: the grid positions in [minX, maxX), plus, when
/// no boundary loop covers F's edges, each end of the cell that is not entirely shared with
/// neighbours (an edge of F, which a grid line may miss by up to a spacing). Without the loop, a
/// cell with no position gets one pass at its right end; with it, none: such a cell is a sliver
/// narrower than the grid step between two critical lines, which the passes on either side paint
/// as far as their cells reach (what they miss, only fill_leftovers paints). A pass of its own
/// ran the whole height of the wall beside its neighbours' passes: a full strip painted twice.
std::vector<double> passPositions(const Cell& cell, double shared_left, double shared_right, const PassGrid& grid,
                                  bool boundary_loop, const std::vector<double>& inner_edges) {
  const double x0 = cell.minX(), x1 = cell.maxX();
  const Span left = cell.spanAt(x0), right = cell.spanAt(x1);
  std::vector<double> xs;
  if (!boundary_loop && (left.top - left.bottom) - shared_left > 1e-6) xs.push_back(x0);
  auto k = static_cast<std::size_t>(std::max(0.0, std::floor((x0 - grid.min) / grid.step)));
  for (; k <= grid.count && grid.at(k) < x1; ++k)
    if (grid.at(k) >= x0 && (xs.empty() || grid.at(k) - xs.back() > 1e-9)) xs.push_back(grid.at(k));
  if (!boundary_loop && ((right.top - right.bottom) - shared_right > 1e-6 || xs.empty())) xs.push_back(x1);
  if (!boundary_loop && !inner_edges.empty()) {
    xs.insert(xs.end(), inner_edges.begin(), inner_edges.end());
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end(), [](double a, double b) { return b - a <= 1e-9; }), xs.end());
  }
  return xs;
}

/// Where a joined cell (decompose's slivers) has an edge of F inside it: at a slice boundary where
/// another cell begins or ends beside it, the part of the step in its span that neither the other
/// slice nor a neighbour shares. Without the boundary loop such an edge gets a pass, as a cell's
/// end does (passPositions). Per cell, the x positions, increasing.
std::vector<std::vector<double>> innerEdges(const Decomposition& cells) {
  // (cell, x) -> lengths shared with cells ending at x on its left and beginning at x on its right.
  std::map<std::pair<std::size_t, double>, std::pair<double, double>> shared;
  for (const Contact& c : cells.contacts) {
    if (c.x != cells.cells[c.right].minX()) shared[{c.right, c.x}].first += c.y1 - c.y0;
    if (c.x != cells.cells[c.left].maxX()) shared[{c.left, c.x}].second += c.y1 - c.y0;
  }
  std::vector<std::vector<double>> edges(cells.cells.size());
  for (const auto& [at, lengths] : shared) {
    const auto& slices = cells.cells[at.first].slices;
    const double x = at.second;
    for (std::size_t i = 0; i + 1 < slices.size(); ++i) {
      if (slices[i].x1 != x) continue;
      const double b0 = slices[i].floor.yAt(x), t0 = slices[i].ceiling.yAt(x);
      const double b1 = slices[i + 1].floor.yAt(x), t1 = slices[i + 1].ceiling.yAt(x);
      const double both = std::max(0.0, std::min(t0, t1) - std::max(b0, b1));
      if ((t0 - b0) - both - lengths.second > 1e-6 || (t1 - b1) - both - lengths.first > 1e-6)
        edges[at.first].push_back(x);
    }
  }
  return edges;
}

/// Removes the cells given no pass (and their contacts), renumbering the rest; returns how many.
std::size_t dropCellsWithoutPasses(Decomposition& d, std::vector<std::vector<double>>& passes) {
  std::vector<std::size_t> index(d.cells.size(), d.cells.size());
  std::size_t kept = 0;
  for (std::size_t i = 0; i < d.cells.size(); ++i) {
    if (passes[i].empty()) continue;
    index[i] = kept;
    if (kept != i) {
      d.cells[kept] = std::move(d.cells[i]);
      passes[kept] = std::move(passes[i]);
    }
    ++kept;
  }
  const std::size_t dropped = d.cells.size() - kept;
  d.cells.resize(kept);
  passes.resize(kept);
  std::vector<Contact> contacts;
  for (Contact c : d.contacts) {
    if (index[c.left] == index.size() || index[c.right] == index.size()) continue;
    c.left = index[c.left], c.right = index[c.right];
    contacts.push_back(c);
  }
  d.contacts = std::move(contacts);
  return dropped;
}

/// Sweep events closer than this count as one (decompose joins the sliver cells between them).
/// One corner of the wall is an event on each side of the region the cells are cut from, at the
/// depth that region lies inside the wall's edges across the passes; corners on one line, such as
/// a hole's right side above the next hole's left side, are one event of the wall and twice that
/// depth apart in the region. The depth is r + c plus: without the boundary loop, F's coarser
/// drawing (kFreeSpaceMargin + kCellArcTolerance); with it (`layout`), the loops beyond the first
/// and the rows' ends (the rows' region lies end_inset spacings inside the last loop and reaches
/// half a spacing across, headland.cpp), drawn with chords of kCellArcTolerance. A quarter
/// spacing more covers the chords of F's arcs, whose ends need not lie at an arc's extreme x, and
/// the offsets' rounding. At s = 0.1 m, c = 0.02 m and the defaults: 0.195 m with the loop,
/// 0.171 m without.
double eventMergeWidth(const ToolParams& tool, double spacing, const HeadlandOptions* layout) {
  double depth = tool.radius() + tool.clearance + kFreeSpaceMargin + kCellArcTolerance;
  if (layout != nullptr)
    depth += static_cast<double>(layout->loops - 1) * layout->spacing +
             std::max(0.0, layout->end_inset - 0.5) * layout->spacing + kCellArcTolerance;
  return 2.0 * depth + 0.25 * spacing;
}

/// The pass positions of every cell, on one grid: over the cells' extent, or, when `span` (a
/// headland's row span) is not empty, over its extent (the first and last pass one spacing inside
/// the loops).
std::vector<std::vector<double>> cellPasses(const Decomposition& cells, const Box& span, double spacing,
                                            bool boundary_loop, PassGrid& grid) {
  std::vector<double> shared_left(cells.cells.size(), 0.0), shared_right(cells.cells.size(), 0.0);
  for (const Contact& c : cells.contacts) {  // those at a cell's end (a joined sliver's may lie inside)
    if (c.x == cells.cells[c.right].minX()) shared_left[c.right] += c.y1 - c.y0;
    if (c.x == cells.cells[c.left].maxX()) shared_right[c.left] += c.y1 - c.y0;
  }
  grid = PassGrid{};
  if (!cells.cells.empty()) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Cell& c : cells.cells) lo = std::min(lo, c.minX()), hi = std::max(hi, c.maxX());
    if (boundary_loop && !span.empty()) {
      lo = span.min_x;
      hi = span.max_x;
    }
    grid.min = lo;
    grid.count = static_cast<std::size_t>(std::max(1.0, std::ceil((hi - lo) / spacing - 1e-9)));
    grid.step = (hi - lo) / static_cast<double>(grid.count);
  }
  const std::vector<std::vector<double>> inner = innerEdges(cells);
  std::vector<std::vector<double>> passes(cells.cells.size());
  for (std::size_t i = 0; i < cells.cells.size(); ++i)
    passes[i] = passPositions(cells.cells[i], shared_left[i], shared_right[i], grid, boundary_loop, inner[i]);
  return passes;
}

/// Entry and exit of a cell for its four orientations (see CellEnds).
CellEnds cellEnds(const Cell& cell, const std::vector<double>& xs) {
  const auto pass = [&](double x) {
    const Span s = cell.spanAt(x);
    return PassEnds{{x, s.bottom}, {x, s.top}};
  };
  return alternatingEnds(pass(xs.front()), pass(xs.back()), xs.size(), cell.centre());
}

/// A move from p (on the floor or ceiling of cell `from`) to q (on the floor or ceiling of cell
/// `to`) through the segment the two cells share: along `from`'s side to the shared line, along
/// the line, along `to`'s side to q. Every point lies in one of the two cells, so the move is free.
std::vector<Point> throughContact(const Cell& from, Point p, const Cell& to, Point q, const Contact& c) {
  const auto onTop = [](const Cell& cell, Point at) {
    const Span s = cell.spanAt(at.x);
    return std::fabs(at.y - s.top) < std::fabs(at.y - s.bottom);
  };
  std::vector<Point> walk = from.boundaryWalk(p.x, c.x, onTop(from, p));
  const double y = std::clamp(walk.back().y, c.y0, c.y1);
  walk.push_back({c.x, y});
  const std::vector<Point> rest = to.boundaryWalk(c.x, q.x, onTop(to, q));
  walk.insert(walk.end(), rest.begin(), rest.end());
  return walk;
}

/// The planners' parameters (paramTable declares them).
struct DecompositionParams {
  SweepDirection sweep;
  Order order = Order::Tsp;
  double overlap = 0.0;
  double coat_ripple = 0.0;
  double trigger_speed = 0.0;
  bool boundary_loop = true;
  double row_end_inset = 0.6;
  bool fill_leftovers = false;
  bool merge_events = false;
  CarPlan car_plan = CarPlan::Headland;
};

const ParamTable<DecompositionParams>& paramTable() {
  static const ParamTable<DecompositionParams> table =
      ParamTable<DecompositionParams>()
          .include(&DecompositionParams::sweep, sweepDirectionParams())
          .add({"order", ParamType::Choice, std::string("tsp"), 0, 0, {}, "",
                "cell order: 2-opt-improved TSP tour, depth-first over the cell graph, or greedy nearest entry"},
               &DecompositionParams::order, {{"tsp", Order::Tsp}, {"dfs", Order::Dfs}, {"greedy", Order::Greedy}})
          .add({"overlap", ParamType::Number, 0.0, 0.0, 0.9, {}, "", "fraction of the tool width adjacent passes overlap"},
               &DecompositionParams::overlap)
          .add(coatRippleParam(), &DecompositionParams::coat_ripple)
          .add(triggerSpeedParam(), &DecompositionParams::trigger_speed)
          .add({"boundary_loop", ParamType::Bool, true, 0, 0, {}, "",
                "one loop around the wall and each obstacle after the cells (covers corners the passes miss)"},
               &DecompositionParams::boundary_loop)
          .add(rowEndInsetParam(), &DecompositionParams::row_end_inset)
          .add(fillLeftoversParam(), &DecompositionParams::fill_leftovers)
          .add({"merge_events", ParamType::Bool, false, 0, 0, {}, "",
                "sweep events closer than twice the cells' depth inside the wall (+ s/4) count as one: no sliver "
                "cells where the wall has corners on one line (README: merge width); off by default, it costs "
                "length and overlap (steps inside joined cells are walked with the tool on)"},
               &DecompositionParams::merge_events)
          .add(carPlanParam(), &DecompositionParams::car_plan, carPlanChoices());
  return table;
}

/// The non-car plan of one sweep direction once F is known, in the working frame (passes run along
/// +y): the headland and the cells (decompose), every cell's passes and the loops as stops of one
/// tour (prepare), then, for an order found under a move cost, the passes and loops in that order
/// (plan).
class CellSweep {
 public:
  using Clock = std::chrono::steady_clock;

  CellSweep(PlanFrame& frame, const DecompositionParams& params, const Budget& budget)
      : frame_(&frame), params_(&params), budget_(&budget),
        spacing_(frame.problem().tool.tool_width * (1.0 - params.overlap)) {}

  /// With the boundary loop, passes keep one spacing clear of it across their direction and end
  /// half a spacing from it along it (headland.hpp); without, they run from edge to edge of F
  /// drawn with coarser arcs (fewer vertices, fewer slabs), 2 mm inside F. `decomposition_ms`
  /// counts from `t_start`.
  void decompose(Kind kind, Clock::time_point t_start) {
    const Problem& problem = frame_->problem();
    const Region& main = frame_->covered();
    const bool boundary_loop = params_->boundary_loop;
    HeadlandOptions layout;
    layout.spacing = spacing_;
    layout.radius = problem.tool.tool_width / 2.0;
    layout.end_inset = params_->row_end_inset;
    layout.arc_tolerance = kCellArcTolerance;
    layout.along_x = false;
    layout.with_unpainted = params_->fill_leftovers;
    if (boundary_loop) h_ = headland(frame_->ws(), main, layout);
    const Region cell_region = boundary_loop ? h_.ends
                                             : freeRegion(frame_->ws().wall(), problem.tool,
                                                          kCellArcTolerance + kFreeSpaceMargin, kCellArcTolerance);
    // The headland comes from the part of F covered; the coarser F lies inside F, so each of its
    // parts lies in one part of F, and a vertex tells which.
    const double merge_width =
        params_->merge_events ? eventMergeWidth(problem.tool, spacing_, boundary_loop ? &layout : nullptr) : 0.0;
    cells_ = decomposeParts(cell_region, kind, merge_width, [&](const PolygonWithHoles& poly) {
      return boundary_loop || std::any_of(main.begin(), main.end(), [&](const PolygonWithHoles& part) {
               return pointInPolygon(part, poly.outer.front());
             });
    });
    decomposition_ms_ = msSince(t_start);
  }

  /// Passes per cell, on one grid of positions for all cells; the cells' ends and links for the
  /// ordering, with the boundary loops as stops of the same tour.
  void prepare() {
    const auto t_order = Clock::now();
    PassGrid grid;
    passes_ = cellPasses(cells_, h_.row_span, spacing_, params_->boundary_loop, grid);
    passless_cells_ = dropCellsWithoutPasses(cells_, passes_);
    ends_.resize(cells_.cells.size());
    for (std::size_t i = 0; i < cells_.cells.size(); ++i) {
      ends_[i] = cellEnds(cells_.cells[i], passes_[i]);
      pass_count_ += passes_[i].size();
    }
    for (const Contact& c : cells_.contacts) links_.push_back({c.left, c.right});
    addLoopStops();
    for (std::size_t k = 0; k < cells_.contacts.size(); ++k) {
      const Contact& c = cells_.contacts[k];
      contacts_between_[std::minmax(c.left, c.right)].push_back(k);
    }
    preparation_ms_ = msSince(t_order);
  }

  /// The plan for one cell order, found under `move_cost`.
  PlanResult plan(const MoveCost& move_cost) const {
    const auto t_ordering = Clock::now();
    // With a start or an end, the order knows them: its cost includes the moves from the start
    // to the first cell and from the last cell to the end.
    const Wall& wall = frame_->ws().wall();
    const Budget& budget = *budget_;
    Ordering ordering =
        orderCells(ends_, links_, params_->order, [&] { return !budget.expired(); }, TourCost{move_cost, wall.start, wall.end});
    const double ordering_ms = preparation_ms_ + msSince(t_ordering);
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the cell ordering");

    const auto t_synthesis = Clock::now();
    PathBuilder builder(frame_->ws());
    Moves moves;
    if (!cover(ordering.visits, builder, moves))
      return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the passes");
    // What the passes and loops left inside the loops (when asked: see fillLeftoversParam).
    Leftovers left;
    const bool fill = params_->boundary_loop && params_->fill_leftovers;
    if (fill) {
      left = coverLeftovers(frame_->ws(), builder, h_.unpainted, 0, spacing_, frame_->problem().tool.tool_width / 2.0, false);
      moves.unreachable += left.unreachable;
    }
    const double synthesis_ms = msSince(t_synthesis);

    if (builder.empty())
      return PlanResult::failure(PlanStatus::NoReachableArea,
                                 "no cell: F drawn 1 mm inside itself is empty (F is thinner than 2 mm); enable "
                                 "boundary_loop to cover F's boundary instead");
    PlanResult result = frame_->finish(builder, moves.unreachable);
    result.stats["cells"] = static_cast<double>(cells_.cells.size());
    result.stats["cells_without_pass"] = static_cast<double>(passless_cells_);
    result.stats["cell_contacts"] = static_cast<double>(cells_.contacts.size());
    result.stats["contact_transits"] = static_cast<double>(moves.contact);
    result.stats["slabs"] = static_cast<double>(cells_.slabs);
    result.stats["passes"] = static_cast<double>(pass_count_);
    result.stats[std::string("order_estimate_") + move_cost.unit()] = ordering.estimated_cost;
    if (fill) recordLeftovers(result, left);
    result.timings_ms["decomposition"] = decomposition_ms_;
    result.timings_ms["ordering"] = ordering_ms;
    result.timings_ms["synthesis"] = synthesis_ms;
    result.stats["routed_transits"] += static_cast<double>(moves.routed);  // followed, not built by moveTo
    return result;
  }

 private:
  /// What covering the visits counted.
  struct Moves {
    std::size_t unreachable = 0;  ///< cells and loops no move reached
    std::size_t contact = 0;      ///< moves into a touching cell through the side they share
    std::size_t routed = 0;       ///< moves into a touching cell along a shorter routed transit
  };

  /// The boundary loops are stops of the same tour, so each is painted between the cells nearest
  /// to it instead of after all of them: entered and left at one of its four extreme vertices
  /// (lowest, rightmost, highest, leftmost: the loop's four "orientations").
  void addLoopStops() {
    for (const Ring& ring : h_.loops) {
      std::array<std::size_t, 4> at{0, 0, 0, 0};  // lowest, rightmost, highest, leftmost
      for (std::size_t k = 1; k < ring.size(); ++k) {
        if (ring[k].y < ring[at[0]].y) at[0] = k;
        if (ring[k].x > ring[at[1]].x) at[1] = k;
        if (ring[k].y > ring[at[2]].y) at[2] = k;
        if (ring[k].x < ring[at[3]].x) at[3] = k;
      }
      CellEnds e;
      for (int o = 0; o < 4; ++o) e.entry[o] = e.exit[o] = ring[at[o]], e.reverse[o] = o;
      const Box b = boundingBox(ring);
      e.centre = {(b.min_x + b.max_x) / 2.0, (b.min_y + b.max_y) / 2.0};
      ends_.push_back(e);
      loop_starts_.push_back(at);
    }
  }

  /// Covers the cells and loops in the order of `visits`. False: the budget ran out.
  bool cover(const std::vector<Visit>& visits, PathBuilder& builder, Moves& moves) const {
    const std::size_t cell_count = cells_.cells.size();
    std::size_t previous = cell_count;
    for (const Visit& visit : visits) {
      if (budget_->expired()) return false;
      if (visit.cell >= cell_count) {  // a boundary loop
        const Ring& ring = h_.loops[visit.cell - cell_count];
        const std::size_t start = loop_starts_[visit.cell - cell_count][static_cast<std::size_t>(visit.orientation)];
        if (!builder.moveTo(ring[start], !builder.empty() && distance(builder.current(), ring[start]) <= 1.01 * spacing_)) {
          ++moves.unreachable;
          continue;
        }
        std::vector<Point> loop;
        for (std::size_t k = 1; k <= ring.size(); ++k) loop.push_back(ring[(start + k) % ring.size()]);
        builder.follow(loop, true);
        previous = cell_count;
        continue;
      }
      if (!enter(visit, previous, builder, moves)) {
        ++moves.unreachable;
        continue;
      }
      previous = visit.cell;
      const Cell& cell = cells_.cells[visit.cell];
      std::vector<double> xs = passes_[visit.cell];
      if ((visit.orientation & 1) != 0) std::reverse(xs.begin(), xs.end());  // leftward
      bool up = (visit.orientation & 2) == 0;
      for (std::size_t k = 0; k < xs.size(); ++k) {
        // Step over along the side the last pass ended on, then run the pass.
        if (k > 0) builder.follow(cell.boundaryWalk(xs[k - 1], xs[k], !up), true);
        const Span span = cell.spanAt(xs[k]);
        builder.follow({{xs[k], up ? span.bottom : span.top}, {xs[k], up ? span.top : span.bottom}}, true);
        up = !up;
      }
    }
    return true;
  }

  /// Moves to the entry of the visit's cell: into a touching cell (the `previous` one) through
  /// the segment they share when a straight move is not free, or along the shortest route when
  /// that is shorter; else by PathBuilder::moveTo. False: the entry is unreachable.
  bool enter(const Visit& visit, std::size_t previous, PathBuilder& builder, Moves& moves) const {
    Workspace& ws = frame_->ws();
    const Point entry = ends_[visit.cell].entry[visit.orientation];
    const auto touching = previous < cells_.cells.size() ? contacts_between_.find(std::minmax(previous, visit.cell))
                                                         : contacts_between_.end();
    // (A vehicle that lifts its tool crosses straight instead: PathBuilder::moveTo.)
    if (touching == contacts_between_.end() || ws.vehicle().liftsTool() || ws.router().isFree(builder.current(), entry))
      return builder.moveTo(entry, !builder.empty() && distance(builder.current(), entry) <= 1.01 * spacing_);
    std::vector<Point> best;
    for (std::size_t k : touching->second) {
      std::vector<Point> walk =
          throughContact(cells_.cells[previous], builder.current(), cells_.cells[visit.cell], entry, cells_.contacts[k]);
      if (best.empty() || polylineLength(walk) < polylineLength(best)) best = std::move(walk);
    }
    // The shortest collision-free route when it is shorter than the walk through the cells.
    const auto route = ws.route(builder.current(), entry);
    if (route && polylineLength(*route) < polylineLength(best)) {
      builder.follow(*route, false);
      ++moves.routed;
    } else {
      builder.follow(best, false);
      ++moves.contact;
    }
    return true;
  }

  PlanFrame* frame_;
  const DecompositionParams* params_;
  const Budget* budget_;
  double spacing_;
  Headland h_;
  Decomposition cells_;
  std::vector<std::vector<double>> passes_;
  std::size_t passless_cells_ = 0, pass_count_ = 0;
  std::vector<CellEnds> ends_;  ///< the cells', then the boundary loops'
  std::vector<CellLink> links_;
  std::vector<std::array<std::size_t, 4>> loop_starts_;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> contacts_between_;  ///< contact indices
  double decomposition_ms_ = 0.0, preparation_ms_ = 0.0;
};

/// Of two plans of one direction, each from its own cell order (under length and under the time
/// model), the one the clock rates faster, provided it paints the same parts; both plans' timings.
PlanResult fasterOf(PlanResult by_length, PlanResult by_time, const Problem& problem, const SweepDirection& sweep) {
  const bool take_timed = by_time.hasPath() && by_time.status == by_length.status &&
                          by_time.unreachable_parts == by_length.unreachable_parts &&
                          objectiveCost(by_time.path, problem, sweep) < objectiveCost(by_length.path, problem, sweep);
  PlanResult& other = take_timed ? by_length : by_time;
  PlanResult& kept = take_timed ? by_time : by_length;
  for (const auto& [name, ms] : other.timings_ms) kept.timings_ms[name] += ms;  // both were planned
  kept.stats["order_plans"] = 2.0;
  kept.stats["order_by_time"] = take_timed ? 1.0 : 0.0;
  return std::move(kept);
}

class DecompositionPlanner final : public TypedPlanner<DecompositionParams> {
 public:
  explicit DecompositionPlanner(Kind kind) : TypedPlanner(paramTable()), kind_(kind) {}

 protected:
  PlanResult planWith(const Problem& problem, const DecompositionParams& given, const Budget& budget) override {
    DecompositionParams params = given;
    // A car comes only with car_plan headland or headland_no_fill: for smoothed, runPlanner gives
    // a tool that turns on the spot and smooths the path.
    return planRows(problem, params.coat_ripple, params.overlap, params.trigger_speed, params.sweep, budget,
                    [&](double angle_deg) { return planAt(problem, params, budget, angle_deg); });
  }

 private:
  /// For a car (car_plan: headland): as many rings as its turns need, the cells cut from what they
  /// leave, and every cell's passes handed to the car's sweep with the cells' tour as its order
  /// (car_sweep.hpp, CarRow::cell): the car takes the first cell of the tour it has passes left in
  /// (each stack of passes in its block order) before the others, as long as it reaches it.
  PlanResult planForCar(const Problem& problem, const DecompositionParams& params, const Budget& budget, double turn,
                        PlanFrame& frame) {
    Workspace& ws = frame.ws();
    const double spacing = problem.tool.tool_width * (1.0 - params.overlap);
    const HeadlandOptions layout = carHeadlandOptions(problem, spacing, 1, params.row_end_inset, kCellArcTolerance, false);
    Headland h = headland(ws, frame.covered(), layout);
    std::vector<CarRow> rows = carHolePasses(ws, h.loops, spacing);
    Decomposition cells = decomposeParts(h.ends, kind_, params.merge_events ? eventMergeWidth(problem.tool, spacing, &layout) : 0.0,
                                         [](const PolygonWithHoles&) { return true; });
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the decomposition");
    PassGrid grid;
    std::vector<std::vector<double>> passes = cellPasses(cells, h.row_span, spacing, true, grid);
    const std::size_t passless_cells = dropCellsWithoutPasses(cells, passes);
    std::vector<CellEnds> ends(cells.cells.size());
    for (std::size_t i = 0; i < cells.cells.size(); ++i) ends[i] = cellEnds(cells.cells[i], passes[i]);
    std::vector<CellLink> links;
    for (const Contact& c : cells.contacts) links.push_back({c.left, c.right});
    const Ordering ordering = orderCells(ends, links, params.order, [&] { return !budget.expired(); });
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the cell ordering");
    std::size_t pass_count = 0;
    for (std::size_t rank = 0; rank < ordering.visits.size(); ++rank) {
      const std::size_t c = ordering.visits[rank].cell;
      for (double x : passes[c]) {
        const Span span = cells.cells[c].spanAt(x);
        const auto line = static_cast<std::size_t>(std::llround((x - grid.min) / grid.step));
        rows.push_back({{x, span.bottom}, {x, span.top}, line, true, rank});
        ++pass_count;
      }
    }
    PathBuilder builder(ws);
    const CarSweep sweep = carSweep(ws, builder, h.loops, rows, spacing, budget, params.car_plan == CarPlan::Headland);
    PlanResult result = carSweepPlan(sweep, builder, h.loops.size(), turn, frame.components().size());
    result.stats["cells"] = static_cast<double>(cells.cells.size());
    result.stats["cells_without_pass"] = static_cast<double>(passless_cells);
    result.stats["cell_contacts"] = static_cast<double>(cells.contacts.size());
    result.stats["slabs"] = static_cast<double>(cells.slabs);
    result.stats["passes"] = static_cast<double>(pass_count);
    return result;
  }

  /// A line or rectangle tool on a gantry or a holonomic robot: its own rows (shape_rows.hpp) painted cell by cell
  /// (shape_cells.hpp), in the order found under the sweep's objective (the time model's move
  /// costs for `time`, else lengths); `boundary_loop` allows the loops run first.
  PlanResult planShapeCells(const Problem& problem, const DecompositionParams& params, const Budget& budget,
                            double angle_deg) {
    Problem disk = problem;
    disk.tool = circumscribedDisk(problem.tool);
    PlanFrame frame(disk, angle_deg * M_PI / 180.0);  // rows along x
    ShapeRowsOptions options;
    options.spacing = problem.tool.tool_width * (1.0 - params.overlap);
    options.loops = params.boundary_loop ? 1 : 0;
    options.end_inset = params.row_end_inset;
    options.arc_tolerance = kCellArcTolerance;
    MoveCost move;
    if (params.sweep.objective == SweepDirection::Objective::Time) move.clock = problem.motion;
    ShapeCellOrder cells;
    PlanResult result = planShapeRows(problem, frame, options, angle_deg, budget,
                                      [&](const ShapeRowPieces& rows, Point from, bool after_loops) {
                                        const Wall& wall = frame.ws().wall();
                                        const TourCost tour{move, after_loops ? std::optional<Point>(from) : wall.start, wall.end};
                                        cells = orderByCells(rows, kind_, params.order, tour, [&] { return !budget.expired(); });
                                        return cells.order;
                                      });
    if (!result.hasPath()) return result;
    result.stats["cells"] = static_cast<double>(cells.cells);
    result.stats["cell_contacts"] = static_cast<double>(cells.contacts);
    result.stats["pieces_outside_cells"] = static_cast<double>(cells.outside);
    result.stats[std::string("order_estimate_") + move.unit()] = cells.estimated_cost;
    return result;
  }

  PlanResult planAt(const Problem& problem, const DecompositionParams& params, const Budget& budget, double angle_deg) {
    if (problem.tool.turnsWithHeading() && !problem.vehicle.isCar()) return planShapeCells(problem, params, budget, angle_deg);
    const auto t_start = CellSweep::Clock::now();
    // Passes run along `angle_deg`; in the working frame they are vertical (along +y), so the
    // working frame is the world turned by 90 - angle degrees.
    const double turn = (angle_deg - 90.0) * M_PI / 180.0;
    PlanFrame frame(problem, turn);
    if (frame.empty()) return PlanFrame::fitsNowhere();
    if (problem.vehicle.isCar()) return planForCar(problem, params, budget, turn, frame);
    CellSweep sweep(frame, params, budget);
    sweep.decompose(kind_, t_start);
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the decomposition");
    sweep.prepare();
    PlanResult result = sweep.plan(MoveCost{});
    if (params.sweep.objective != SweepDirection::Objective::Time || !result.hasPath()) return result;
    // For the clock: the order found under the time model's move costs is planned too, and the
    // plan the clock rates faster kept, provided it paints the same parts (the moves' straight
    // estimates miss their routes' stops, so the clock, not the estimate, decides).
    MoveCost by_time;
    by_time.clock = problem.motion;
    return fasterOf(std::move(result), sweep.plan(by_time), problem, params.sweep);
  }

  Kind kind_;
};

}  // namespace

PlannerInfo plannerInfo(Kind kind, PlannerInfo info) {
  info.min_coverage_reachable = 0.99;
  info.plans_for_car = true;
  info.plans_shapes = true;
  return typedPlannerInfo<DecompositionPlanner>(std::move(info), paramTable(), kind);
}

}  // namespace coverbench::decomposition
