// Planning for a car from the start: headland rings, then rows in a turn-aware order
// (coverbench/car_sweep.hpp, docs/vehicles.md). carSweep runs the stages that car_sweep_parts.hpp
// lists: the first sweep, its retries, the fill rounds, the strokes; and the plan's record.
#include "coverbench/car_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "car_paint_grid.hpp"
#include "car_sweep_parts.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

using namespace vehicle_detail;

/// The fill rounds (carSweep): at most this many...
constexpr int kFillRounds = 8;
/// ...each giving a pass to every piece left unpainted of at least this many spacings²...
constexpr double kFillMinArea = 0.4;
/// ...where a stretch of at least this many spacings fits (first 5 walls of each family, seed 3,
/// forward-only car: these three chosen by the median coverage of residential and stairwell walls,
/// docs/vehicles.md); a round is kept when worth it (worthIt, kFillMinYield).
constexpr double kFillMinPass = 1.3;
/// A fill round not worth it from where the sweep ended is tried with the whole sweep planned
/// again only when the sweep leaves at least this share of F's reach unpainted (on the canonical
/// facade, 0.7 %, it would double the planning time for nothing).
constexpr double kFillResweepLeft = 0.03;
/// The fill rounds' raster (PaintGrid) has at most about this many cells.
constexpr double kFillMaxCells = 4e6;
/// Strokes are looked for only when the fill rounds leave at least this share of the reach
/// unpainted.
constexpr double kStrokeMinLeft = 0.01;
/// A forward-only car is in a pocket where a search of its motions finds fewer than kPocketPoses
/// poses; where it starts in one, the rings start at up to kRingStarts longest edges of their
/// first ring (carSweep).
constexpr std::size_t kPocketPoses = 5000;
constexpr std::size_t kRingStarts = 8;

/// Whether a forward-only car that starts where `path` does is in a pocket: a search of its
/// motions from there finds fewer than kPocketPoses poses.
bool startsInPocket(const Workspace& ws, const Path& path, double rho) {
  if (path.segments() == 0) return false;
  std::size_t found = 0;
  searchCarUntil(ws, Pose{path.waypoints.front(), startHeading(path)}, rho, kPocketPoses, [](Pose, Path&) { return false; }, &found);
  return found < kPocketPoses;
}

/// What follows carSweep's first sweep: its retries (the rings as passes, the rings started
/// elsewhere), the fill rounds, and the strokes and painting transits. They share the sweep kept
/// so far (`out`) and the raster that measures what it paints.
class SweepRounds {
 public:
  SweepRounds(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& given,
              double spacing, const Budget& budget, double line_penalty, CarSweep& out)
      : ws_(ws), rings_(rings), loops_(loops), given_(given), spacing_(spacing), budget_(budget),
        line_penalty_(line_penalty), out_(out), car_(ws.vehicle()), rho_(car_.turn_radius * (1.0 + kCarRadiusSlack)) {
    // Cells of a fifth of a spacing, at most about kFillMaxCells of them.
    const Box box = boundingBox(ws.free());
    cell_ = std::max(spacing / 5.0, std::sqrt((box.max_x - box.min_x + 1.0) * (box.max_y - box.min_y + 1.0) / kFillMaxCells));
  }

  /// No row reached from where the rings end (a pocket the car cannot turn out of, and giving up
  /// their end did not get it out): the sweep again with the rings as passes ordered with the
  /// rows (sweepOnce's rings_as_passes), kept when it paints more.
  void retryRingsAsPasses() {
    if (!(out_.rows > 0 && out_.unreached == out_.rows && !loops_.empty())) return;
    std::optional<double> painted;  // what out.path paints, measured once
    for (int way = 1; way <= 2 && out_.rings_as_passes == 0 && !out_.timed_out; ++way) {
      if (budget_.expired()) {
        out_.rounds_timed_out = true;
        break;
      }
      PathBuilder other(ws_);
      CarSweep passes_first = sweepOnce(ws_, other, loops_, given_, {}, spacing_, budget_, line_penalty_, nullptr, way);
      if (passes_first.timed_out) out_.rounds_timed_out = true;
      if (passes_first.timed_out || passes_first.unreached == passes_first.rows) continue;
      if (!grid_) grid_.emplace(ws_, cell_);
      if (!painted) {
        grid_->paint(out_.path);
        painted = grid_->painted();
      }
      grid_->paint(passes_first.path);
      if (grid_->painted() > *painted) {
        rings_ = other;
        out_ = std::move(passes_first);
      }
    }
    if (grid_ && out_.rings_as_passes == 0) grid_->paint(out_.path);  // the fill rounds start from out.path's paint
  }

  /// A forward-only car that leaves most rows out and starts in a pocket (startsInPocket: as on
  /// random-s7-0001, a pocket of 1.7 m x 1.2 m that a slot narrower than its turns closes, where
  /// every planner painted 0.05 of R): the sweep again with the rings started at their first
  /// ring's next longest edges (up to kRingStarts), until one starts out of a pocket, kept when it
  /// paints more.
  void retryRingStarts() {
    if (!(!car_.reverse && out_.rings_as_passes == 0 && !loops_.empty() && !out_.timed_out && 2 * out_.unreached > out_.rows &&
          startsInPocket(ws_, out_.path, rho_)))
      return;
    for (std::size_t e = 1; e < kRingStarts; ++e) {
      if (budget_.expired()) {
        out_.rounds_timed_out = true;
        break;
      }
      PathBuilder other(ws_);
      CarSweep again = sweepOnce(ws_, other, loops_, given_, {}, spacing_, budget_, line_penalty_, nullptr, 0, e);
      if (again.timed_out) {
        out_.rounds_timed_out = true;
        break;
      }
      if (again.ring_start != e) break;  // the first ring has no more edges
      if (startsInPocket(ws_, again.path, rho_)) continue;
      if (!grid_) grid_.emplace(ws_, cell_);
      grid_->paint(out_.path);
      const double before = grid_->painted();
      grid_->paint(again.path);
      if (grid_->painted() > before) {
        rings_ = other;
        out_ = std::move(again);
      } else {
        grid_->paint(out_.path);
      }
      break;
    }
  }

  /// Fill rounds: passes through what the path leaves unpainted (PaintGrid::passes), driven from
  /// where it ends (before its last row, when that is a dead end: that row is taken again with
  /// them), or, where the car reaches none of them so, the whole sweep planned again with every
  /// round's passes taken last. A round is kept when what it paints more is worth the path it adds
  /// (worthIt); the rounds stop at the first that is not kept.
  void fillRounds() {
    grid_shows_out_ = grid_.has_value();
    for (int round = 0; round < kFillRounds && !out_.timed_out && out_.path.segments() > 0; ++round)
      if (!fillRound()) break;
  }

  /// Where the path leaves more than kStrokeMinLeft of the reach unpainted: strokes through what is
  /// left (a forward-only car; strokes()), and the transits paint where they pass over it
  /// (paintTransits).
  void strokesAndTransits() {
    if (out_.timed_out || out_.path.segments() == 0) return;
    if (!grid_) grid_.emplace(ws_, cell_);
    if (!out_painted_) {
      if (!grid_shows_out_) grid_->paint(out_.path);
      grid_shows_out_ = true;
      out_painted_ = grid_->painted();
    }
    if (*out_painted_ < (1.0 - kStrokeMinLeft) * grid_->reach()) {
      if (!grid_shows_out_) grid_->paint(out_.path);
      if (!car_.reverse) strokes(ws_, out_, *grid_, *out_painted_, spacing_, rho_, budget_);
      paintTransits(out_, *grid_);
    }
  }

 private:
  /// One fill round; false when the rounds stop.
  bool fillRound() {
    if (budget_.expired()) {
      out_.rounds_timed_out = true;
      return false;
    }
    // The grid shows what out.path paints from the second round on (below).
    if (!grid_) {
      grid_.emplace(ws_, cell_);
      grid_->paint(out_.path);
      grid_shows_out_ = true;
    }
    const double painted = grid_->painted();
    out_painted_ = painted;
    const std::vector<CarRow> passes =
        grid_->passes(ws_, spacing_, kFillMinArea * spacing_ * spacing_, rho_, !car_.reverse, kFillMinPass * spacing_);
    if (passes.empty()) return false;
    all_.insert(all_.end(), passes.begin(), passes.end());
    Path start = out_.ended_in_dead_end ? upTo(out_.path, out_.dead_end_from) : out_.path;
    std::vector<CarRow> again;
    if (out_.ended_in_dead_end) {
      again.push_back(out_.dead_end_row);
      again.back().row = false;
    }
    PathBuilder none(ws_);
    const CarSweep more = sweepOnce(ws_, none, {}, again, passes, spacing_, budget_, line_penalty_, &start);
    if (more.timed_out) {
      out_.rounds_timed_out = true;
      return false;
    }
    const bool reached = more.fill_passes > 0;
    bool reached_but_not_worth = false;
    if (reached) {
      // The continuation is out.path and more, unless it left out the dead-end last row.
      if (again.empty()) grid_->paintMore(more.path, out_.path.segments());
      else grid_->paint(more.path);
      grid_shows_out_ = false;
      if (!worthIt(grid_->painted() - painted, pathLength(more.path) - pathLength(out_.path), spacing_)) {
        // Not worth it from there: the whole sweep again (it costs as much as the first), once,
        // and only where much is left (PaintGrid::reach).
        if (resweeps_ > 0 || painted > (1.0 - kFillResweepLeft) * grid_->reach()) return false;
        reached_but_not_worth = true;
      }
    }
    if (reached && !reached_but_not_worth) {
      takeContinuation(more, !again.empty());
      return true;
    }
    return resweep(painted);
  }

  /// Makes the fill round's continuation `more` the sweep (`row_again`: it took the dead-end last
  /// row again, its one given row).
  void takeContinuation(const CarSweep& more, bool row_again) {
    // The dead-end last row taken again and left out: a row left out, or, when it was a fill
    // pass, one fill pass fewer.
    const bool again_fill = row_again && out_.dead_end_fill;
    const bool again_left = row_again && more.unreached > 0;
    if (again_left && again_fill) {
      --out_.fill_passes;
    } else {
      out_.unreached += more.unreached;
      out_.dead_both_ways += more.dead_both_ways;
    }
    out_.path = more.path;
    grid_shows_out_ = true;
    out_painted_.reset();
    out_.links = out_.links + more.links - (row_again ? 1 : 0);  // the link into the row taken again
    out_.routed += more.routed;
    out_.searched += more.searched;
    out_.cusps += more.cusps;
    out_.backtracks += more.backtracks;
    out_.undriven_m += more.undriven_m;
    out_.fill_passes += more.fill_passes;
    out_.ended_in_dead_end = more.ended_in_dead_end;
    out_.dead_end_from = more.dead_end_from;
    out_.dead_end_row = more.dead_end_row;
    // The continuation's only row that is no fill pass is the row taken again (it has no rings).
    out_.dead_end_fill = more.ended_in_dead_end && (more.dead_end_fill || again_fill);
  }

  /// The whole sweep planned again with every round's passes taken last, kept when worth it
  /// (`painted`: what out.path paints); false when the rounds stop.
  bool resweep(double painted) {
    ++resweeps_;
    PathBuilder other(ws_);
    CarSweep again_whole =
        sweepOnce(ws_, other, loops_, given_, all_, spacing_, budget_, line_penalty_, nullptr, out_.rings_as_passes, out_.ring_start);
    if (again_whole.timed_out) out_.rounds_timed_out = true;
    if (again_whole.timed_out || again_whole.fill_passes == 0) return false;
    grid_->paint(again_whole.path);
    grid_shows_out_ = false;
    if (!worthIt(grid_->painted() - painted, pathLength(again_whole.path) - pathLength(out_.path), spacing_)) return false;
    rings_ = other;
    out_ = std::move(again_whole);
    grid_shows_out_ = true;
    out_painted_.reset();
    return true;
  }

  Workspace& ws_;
  PathBuilder& rings_;
  const std::vector<Ring>& loops_;
  const std::vector<CarRow>& given_;
  const double spacing_;
  const Budget& budget_;
  const double line_penalty_;
  CarSweep& out_;
  const VehicleModel& car_;
  const double rho_;
  double cell_ = 0.0;                    // the raster's cell
  std::optional<PaintGrid> grid_;
  std::vector<CarRow> all_;              // every fill round's passes
  bool grid_shows_out_ = false;          // the grid shows what out.path paints
  std::optional<double> out_painted_;    // what out.path paints, when measured
  int resweeps_ = 0;
};

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

}  // namespace

CarSweep carSweep(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& given, double spacing,
                  const Budget& budget, bool fill, double line_penalty) {
  CarSweep out = sweepOnce(ws, rings, loops, given, {}, spacing, budget, line_penalty);
  SweepRounds rounds(ws, rings, loops, given, spacing, budget, line_penalty, out);
  rounds.retryRingsAsPasses();
  rounds.retryRingStarts();
  if (fill) {
    rounds.fillRounds();
    rounds.strokesAndTransits();
  }
  describe(out);
  return out;
}

PlanResult carSweepPlan(const CarSweep& sweep, const PathBuilder& rings, std::size_t headland_rings, double angle,
                        std::size_t free_components) {
  PlanResult result;
  result.status = PlanStatus::Ok;
  result.path = sweep.path;
  rotatePoints(result.path.waypoints, angle);
  result.stats["headland_rings"] = static_cast<double>(headland_rings);
  recordOutcome(result, rings, free_components, sweep.unreached_rings);
  recordCarSweep(result, sweep);
  result.planned_for_car = true;
  return result;
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
