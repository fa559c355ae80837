// One sweep of the car over the rows (sweepOnce, car_sweep_parts.hpp; docs/vehicles.md): after the
// rings, each step takes the cheapest row a curve reaches, else a route round the obstacles or a
// search over the car's own motions; stuck, the car goes back a row and marks that way in a dead end.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

#include "car_entry_grid.hpp"
#include "car_sweep_parts.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::vehicle_detail {
namespace {

/// Curves checked for freedom per row before the routed links are tried.
constexpr std::size_t kMaxCurveChecks = 64;
/// Rows a stuck car goes back at most, from the furthest it got.
constexpr std::size_t kMaxBacktracks = 4;
/// Rows tried along a route round the obstacles when no curve was free.
constexpr std::size_t kMaxRoutedTries = 8;
/// Of those, the nearest this many are also searched for over the car's own motions
/// (searchCarRoute), each up to kSearchExpansions poses.
constexpr std::size_t kSearchTries = 2;
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

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

/// The piece starts where the car is, heading its way (or, for a car that reverses, backing up).
bool startsAlong(const Path& piece, Pose pose, bool reverse) {
  return piece.segments() > 0 && distance(piece.waypoints.front(), pose.at) <= 1e-12 &&
         headingsJoin(pose.heading, startHeading(piece), reverse);
}

/// A row's direction from a to b (a unit vector; exact for rows along an axis).
Point rowDirection(const CarRow& r) {
  const Point d = r.b - r.a;
  if (d.y == 0.0) return {d.x > 0.0 ? 1.0 : -1.0, 0.0};
  if (d.x == 0.0) return {0.0, d.y > 0.0 ? 1.0 : -1.0};
  return d * (1.0 / std::hypot(d.x, d.y));
}

/// What each row was entered after: where to go back to when it proves a dead end.
struct Step {
  std::size_t row;
  bool from_a;
  std::size_t waypoints;  // the path's size before the link into it
  char how;  // 'c': one curve; 'r': a route smoothed for the car; 's': a searched route
  std::size_t cusps;
};

/// Stacks: runs of rows on consecutive lines, each the only row beside the one below it and that
/// one's only row beside it above, their ends within a turn radius of each other (what a wall's
/// open stretch or a cell between windows holds). A car that enters an untouched stack at its
/// bottom or top row takes it in carBlockOrder, each link a U-turn over enough lines for a half
/// circle (RowSweep::follow_), as long as those curves are free.
struct Stack {
  std::vector<std::size_t> rows;  // bottom up
  std::size_t k = 0;              // lines a half-circle U-turn spans at least (0: no block order)
  std::size_t done = 0;           // rows painted
};

/// A link from the car into a row and through it (RowSweep::routeStep).
struct Link {
  Path path;
  std::size_t cusps = 0;
  double cut = 0.0;  // row length its turns replaced (tool off)
};

/// One sweep over the rows from the end of out.path (sweepOnce): what the rows are (their lines
/// and stacks), what is painted, and the steps taken, shared by the stages of a step.
class RowSweep {
 public:
  RowSweep(Workspace& ws, CarSweep& out, std::vector<CarRow> rows, const std::vector<char>& run_pass, std::size_t first_fill,
           double spacing, const Budget& budget, double line_penalty, bool continuing)
      : ws_(ws), car_(ws.vehicle()), rho_(car_.turn_radius * (1.0 + kCarRadiusSlack)), out_(out), budget_(budget),
        spacing_(spacing), line_penalty_(line_penalty), continuing_(continuing), rows_(std::move(rows)), n_(rows_.size()),
        first_fill_(first_fill), remaining_(n_), entries_(rows_, std::max(rho_, spacing)) {
    ordered_ = std::any_of(rows_.begin(), rows_.end(), [](const CarRow& r) { return r.cell != kAnyCell; });
    done_.assign(n_, 0);
    // Rows shorter than a turn radius are left for last: a car that drives into one often has no
    // room to turn out of it (they are what is left between the headlands of two obstacles). So
    // are the passes made of runs: taken with the rows, they drew the sweep away from rows it then
    // did not come back to (first 5 residential walls, boustrophedon, forward-only car: median
    // coverage 0.867 so, 0.899 taken last).
    last_row_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) last_row_[i] = distance(rows_[i].a, rows_[i].b) < rho_ || run_pass[i];
    dead_.assign(n_, 0);
    heading_ab_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) heading_ab_[i] = std::atan2(rows_[i].b.y - rows_[i].a.y, rows_[i].b.x - rows_[i].a.x);
    if (!car_.reverse) markDeadExits();
    indexLines();
    findStacks();
    follow_.assign(n_, kNone);
    for (std::size_t i = 0; i < n_; ++i) first_left_ += holdsLastBack(i);
    if (ordered_) {
      for (std::size_t i = 0; i < n_; ++i) by_cell_.push_back(i);
      std::stable_sort(by_cell_.begin(), by_cell_.end(), [&](std::size_t i, std::size_t j) { return rows_[i].cell < rows_[j].cell; });
    }
  }
  RowSweep(const RowSweep&) = delete;
  RowSweep& operator=(const RowSweep&) = delete;

  /// The sweep: the first row (without rings), a forward-only car's rings given up until it can
  /// loop from their end, then a step at a time until no row is left or none can be reached.
  void run() {
    if (out_.path.waypoints.empty() && n_ > 0) startOnFirstRow();
    rings_whole_ = out_.path;
    headland_whole_ = out_.headland;
    // A forward-only car whose rings end in a dead end gives them up until it can loop from their
    // end, up to kRingGiveUpRadii turn radii.
    if (!car_.reverse && !continuing_)
      while (out_.path.segments() > 1 && ring_given_up_ < kRingGiveUpRadii * rho_ &&
             !carCanLoop(ws_, endPose(out_.path), rho_, kLoopExpansions))
        giveUpRingTail();
    max_backtracks_ = 2 * n_ + 8;
    while (remaining_ > 0) {
      if (budget_.expired()) {
        out_.timed_out = true;
        break;
      }
      const Pose pose = endPose(out_.path);
      while (lowest_line_ < lines_ && std::all_of(by_line_[lowest_line_].begin(), by_line_[lowest_line_].end(),
                                                  [&](std::size_t j) { return done_[j] != 0; }))
        ++lowest_line_;
      // With a cell order, that cell's rows (and passes of no cell) first, then any.
      const std::size_t cell = firstOpenCell();
      const bool found = (cell != kAnyCell && step(pose, [&](std::size_t i, bool from_a) {
                           return admissible(i, from_a) && (rows_[i].cell == cell || rows_[i].cell == kAnyCell);
                         })) || step(pose, [this](std::size_t i, bool from_a) { return admissible(i, from_a); });
      if (found && desperate_) {
        desperate_ = false;
        furthest_ = steps_.size();
      }
      if (found) continue;
      if (cutRingEndShort() || giveUpRingEnd()) continue;
      if (!goBack()) break;
    }
  }

  /// What the sweep ends with: the rings whole where giving up their end reached no row, a
  /// forward-only car's last row into a dead end, and the rows left out counted.
  void finish() {
    if (steps_.empty() && out_.links == 0 && ring_given_up_ > 0.0) {
      // No row was reached from anywhere the rings' end was cut back to: they are driven whole.
      out_.path = rings_whole_;
      out_.headland = headland_whole_;
    }
    if (remaining_ > 0 && !car_.reverse && !out_.timed_out && out_.path.segments() > 0) endInDeadEnd();
    for (std::size_t i = first_fill_; i < n_; ++i) {
      if (done_[i]) ++out_.fill_passes;
      else --remaining_;
    }
    out_.unreached = remaining_;
    for (std::size_t i = 0; i < first_fill_; ++i) out_.dead_both_ways += !done_[i] && dead_[i] == 3;
  }

 private:
  // --- The rows: ends, poses, lines and stacks (set up once).

  Point entryOf(std::size_t i, bool from_a) const { return from_a ? rows_[i].a : rows_[i].b; }
  Point exitOf(std::size_t i, bool from_a) const { return from_a ? rows_[i].b : rows_[i].a; }
  /// The pose the car enters row i with, from end a or b.
  Pose poseInto(std::size_t i, bool from_a) const {
    return Pose{entryOf(i, from_a), from_a ? heading_ab_[i] : wrapAngle(heading_ab_[i] + M_PI)};
  }
  bool takenLast(std::size_t i) const { return last_row_[i] != 0; }
  double alongAt(Point p) const { return dot(p, along_); }
  /// Rows i and j overlap across the lines (lie beside each other).
  bool beside(std::size_t i, std::size_t j) const { return lo_x_[j] <= hi_x_[i] && hi_x_[j] >= lo_x_[i]; }

  /// A forward-only car that drives through a row and cannot loop from where it comes out (the
  /// row ends facing F's edge, or in a strip narrower than its turns) can only end its path there:
  /// that way through is a dead end from the start. (A car that reverses backs out.)
  void markDeadExits() {
    for (std::size_t i = 0; i < n_; ++i)
      for (bool from_a : {true, false}) {
        const Pose out_pose{exitOf(i, from_a), poseInto(i, from_a).heading};
        if (!carCanLoop(ws_, out_pose, rho_, kLoopExpansions)) dead_[i] |= from_a ? 1 : 2;
      }
  }

  /// The rows of each line, and each row's extent along the lines (`along_`: the lines'
  /// direction, x for rows along x, as zigzag's).
  void indexLines() {
    for (const CarRow& r : rows_)
      if (r.row) {
        if (lines_ == 0 && distance(r.a, r.b) > 0.0) along_ = rowDirection(r);
        lines_ = std::max(lines_, r.line + 1);
      }
    by_line_.resize(lines_);
    lo_x_.resize(n_);
    hi_x_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      lo_x_[i] = std::min(alongAt(rows_[i].a), alongAt(rows_[i].b));
      hi_x_[i] = std::max(alongAt(rows_[i].a), alongAt(rows_[i].b));
      if (rows_[i].row) by_line_[rows_[i].line].push_back(i);
    }
    beside_from_.assign(n_, 0);
  }

  /// The stacks (Stack) and, for those a forward-only car takes in a block order, their k.
  void findStacks() {
    stack_of_.assign(n_, kNone);
    stack_pos_.assign(n_, 0);
    for (std::size_t line = 0; line < lines_; ++line)
      for (std::size_t i : by_line_[line]) {
        if (takenLast(i)) continue;
        std::size_t below = kNone, count = 0;
        if (line > 0)
          for (std::size_t j : by_line_[line - 1])
            if (beside(i, j)) {
              below = j;
              ++count;
            }
        bool joins = count == 1 && stack_of_[below] != kNone && rows_[i].cell == rows_[below].cell &&
                     std::fabs(lo_x_[i] - lo_x_[below]) <= rho_ && std::fabs(hi_x_[i] - hi_x_[below]) <= rho_;
        if (joins)
          joins = std::count_if(by_line_[line].begin(), by_line_[line].end(), [&](std::size_t j) { return beside(below, j); }) == 1;
        if (joins) {
          stack_of_[i] = stack_of_[below];
        } else {
          stack_of_[i] = stacks_.size();
          stacks_.emplace_back();
        }
        stack_pos_[i] = stacks_[stack_of_[i]].rows.size();
        stacks_[stack_of_[i]].rows.push_back(i);
      }
    for (Stack& stack : stacks_) {
      const std::size_t m = stack.rows.size();
      if (m < 2) continue;
      const double dy = std::fabs(cross(along_, rows_[stack.rows.back()].a - rows_[stack.rows.front()].a)) / static_cast<double>(m - 1);
      const std::size_t k = dy > 0.0 ? static_cast<std::size_t>(std::ceil(2.0 * rho_ / dy - 1e-9)) : 0;
      if (!car_.reverse && k > 0 && m >= 2 * k + 1) stack.k = k;
    }
  }

  // --- What is painted and what may be entered.

  /// The lowest unpainted line among the rows beside row i.
  std::size_t lowestBeside(std::size_t i) {
    if (!rows_[i].row) return rows_[i].line;
    for (std::size_t line = std::max(lowest_line_, beside_from_[i]); line < rows_[i].line; ++line)
      for (std::size_t j : by_line_[line])
        if (!done_[j] && beside(i, j)) return beside_from_[i] = line;
    return beside_from_[i] = rows_[i].line;
  }
  /// A row more than k - 1 lines inside a stack no row of which is painted yet: a block order
  /// cannot start there.
  bool insideUntouched(std::size_t i) const {
    if (stack_of_[i] == kNone) return false;
    const Stack& stack = stacks_[stack_of_[i]];
    return stack.k > 0 && stack.done == 0 && stack_pos_[i] >= stack.k && stack.rows.size() - 1 - stack_pos_[i] >= stack.k;
  }
  /// Row i is not taken last and may still be entered one way or the other (a row that is a dead
  /// end both ways holds none back).
  bool holdsLastBack(std::size_t i) const { return !takenLast(i) && dead_[i] != 3; }
  /// Row i may be entered from end a (or b) now.
  bool admissible(std::size_t i, bool from_a) const {
    return !done_[i] && !(first_left_ > 0 && !last_open_ && takenLast(i)) && !(dead_[i] & (from_a ? 1 : 2));
  }
  /// With a cell order, the first cell in it that has a row left the car may enter; else kAnyCell.
  std::size_t firstOpenCell() {
    if (!ordered_) return kAnyCell;
    while (open_from_ < n_ && done_[by_cell_[open_from_]]) ++open_from_;
    for (std::size_t t = open_from_; t < n_; ++t)
      if (admissible(by_cell_[t], true) || admissible(by_cell_[t], false)) return rows_[by_cell_[t]].cell;
    return kAnyCell;
  }

  /// Row i painted (or, on a backtrack, unpainted again), and what follows from that.
  void markDone(std::size_t i, bool painted) {
    done_[i] = painted ? 1 : 0;
    entries_.setPainted(i, painted);
    if (painted) --remaining_;
    else ++remaining_;
    if (holdsLastBack(i)) first_left_ = painted ? first_left_ - 1 : first_left_ + 1;
    if (!painted) {  // a backtrack: what was known painted below is not any more
      std::fill(beside_from_.begin(), beside_from_.end(), 0);
      open_from_ = 0;
    }
    if (stack_of_[i] == kNone) return;
    Stack& stack = stacks_[stack_of_[i]];
    stack.done = painted ? stack.done + 1 : stack.done - 1;
    if (!painted || stack.done != 1 || stack.k == 0) return;
    followBlockOrder(stack, i);
  }
  /// The stack's first row painted is row i: the rest are taken in its block order from there,
  /// counting lines from the nearer end (follow_).
  void followBlockOrder(const Stack& stack, std::size_t i) {
    const std::size_t m = stack.rows.size();
    const bool up = stack_pos_[i] <= m - 1 - stack_pos_[i];
    const std::size_t p = up ? stack_pos_[i] : m - 1 - stack_pos_[i];
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
      shared = by_line_[rows_[left].line].size() > 1;
    }
    if (!shared) order = carBlockOrder(m, stack.k, p, true);
    for (std::size_t r : stack.rows) follow_[r] = kNone;  // an order from before a backtrack
    for (std::size_t t = 0; t + 1 < order.size(); ++t) follow_[at(order, t)] = at(order, t + 1);
  }

  // --- Driving.

  /// Drives row i from end a (or b), from its entry where the car is.
  void driveRow(std::size_t i, bool from_a) {
    out_.path.moveTo(exitOf(i, from_a), true);
    markDone(i, true);
  }
  /// Without rings: the path starts at the lowest end of the first row (of the first cell, with a
  /// cell order), driven.
  void startOnFirstRow() {
    std::size_t first = 0;
    for (std::size_t i = 1; i < n_; ++i)
      if (std::make_tuple(rows_[i].cell, !rows_[i].row, rows_[i].line, lo_x_[i]) <
          std::make_tuple(rows_[first].cell, !rows_[first].row, rows_[first].line, lo_x_[first]))
        first = i;
    const bool from_a = alongAt(rows_[first].a) <= alongAt(rows_[first].b);
    out_.path.moveTo(entryOf(first, from_a), false);
    driveRow(first, from_a);
    ++out_.links;
    first_row_ = first;
  }
  /// Gives up the rings' last segments, a turn radius of them (ring not driven, said as such).
  void giveUpRingTail() {
    double cut = 0.0;
    while (out_.path.segments() > 1 && cut < rho_) {
      const std::size_t k = out_.path.segments() - 1;
      cut += segmentLength(out_.path, k);
      out_.path.waypoints.pop_back();
      out_.path.tool_on.pop_back();
      if (out_.path.bulge.size() > out_.path.tool_on.size()) out_.path.bulge.resize(out_.path.tool_on.size());
      ++out_.headland.skipped;
    }
    ring_given_up_ += cut;
    out_.headland.cut_m += cut;
  }
  /// Drives the curve from the car's pose into row i (from end a or b) and the row, if the curve
  /// is free; a step of the sweep.
  bool takeCurve(std::size_t i, bool from_a) {
    const Pose pose = endPose(out_.path);
    const Path curve = carCurve(pose, poseInto(i, from_a), rho_, car_.reverse, false);
    if (curve.waypoints.empty() || !pathFree(ws_, curve)) return false;
    const std::size_t turned = cusps(curve);
    steps_.push_back({i, from_a, out_.path.waypoints.size(), 'c', turned});
    furthest_ = std::max(furthest_, steps_.size());
    append(out_.path, curve);
    driveRow(i, from_a);
    ++out_.links;
    out_.cusps += turned;
    return true;
  }

  // --- A step of the sweep.

  /// A step of the sweep: a curve, else a route, into a row `keep` admits.
  template <class Keep>
  bool step(Pose pose, const Keep& keep) {
    // In a stack's block order, the next row of the order when its curve is free.
    const std::size_t here = steps_.empty() ? first_row_ : steps_.back().row;
    if (here != kNone && follow_[here] != kNone && !done_[follow_[here]]) {
      const std::size_t j = follow_[here];
      const bool from_a = distance(pose.at, rows_[j].a) <= distance(pose.at, rows_[j].b);
      if (keep(j, from_a) && takeCurve(j, from_a)) return true;
    }
    // Taken nearest first, in a fixed order (ties by row and end), from the grid of rows' ends:
    // most are never looked at.
    EntryGrid::NearestFirst<Keep> nearest(entries_, pose.at, keep);
    std::vector<Candidate> taken;  // nearest first
    return curveStep(pose, keep, nearest, taken) || routeStep(pose, nearest, taken);
  }

  /// The cheapest row a free curve reaches: best first by cost (curve length plus the line
  /// penalty), evaluated lazily: a curve is never shorter than the straight distance, so a
  /// candidate enters the heap with that distance plus its penalty as its key, and its curve is
  /// measured only if it comes to the top. At most kMaxCurveChecks curves are checked (every way
  /// on where the rings end: the car may face F's edge there).
  template <class Keep, class Nearest>
  bool curveStep(Pose pose, const Keep& keep, Nearest& nearest, std::vector<Candidate>& taken) {
    std::size_t admitted = 0;  // every way on is tried where the rings end (below)
    if (steps_.empty() && out_.links == 0)
      for (std::size_t i = 0; i < n_; ++i) admitted += keep(i, true) + keep(i, false);
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
    const std::size_t max_checks = steps_.empty() && out_.links == 0 ? admitted : kMaxCurveChecks;
    while (!found && checks < max_checks) {
      while (true) {
        if (next == taken.size()) {
          const std::optional<Candidate> more = nearest.next();
          if (!more) break;
          taken.push_back(*more);
        }
        if (!heap.empty() && taken[next].bound >= heap.top().cost) break;
        const Candidate& c = taken[next];
        penalty.push_back(line_penalty_ * spacing_ * static_cast<double>(rows_[c.row].line - lowestBeside(c.row)) +
                          (insideUntouched(c.row) ? kInsideStackPenalty * rho_ : 0.0));
        // A curve is no shorter than the straight distance, nor than the turn its headings
        // differ by (a Reeds-Shepp length costs the most to measure): the larger, a hair less
        // for rounding, is its key until it is measured.
        const double turn = std::fabs(wrapAngle(poseInto(c.row, c.from_a).heading - pose.heading));
        heap.push({std::max(c.bound, rho_ * turn * (1.0 - 1e-9)) + penalty.back(), next, false});
        ++next;
      }
      if (heap.empty()) break;
      if (!heap.top().measured) {
        const std::size_t k = heap.top().index;
        heap.pop();
        const double length = carCurveLength(pose, poseInto(taken[k].row, taken[k].from_a), rho_, car_.reverse);
        if (std::isfinite(length)) heap.push({length + penalty[k], k, true});
        continue;
      }
      const Candidate c = taken[heap.top().index];
      heap.pop();
      ++checks;
      found = takeCurve(c.row, c.from_a);
    }
    return found;
  }

  /// No curve is free (an obstacle between): a route round it, smoothed for the car, starting
  /// straight on from where the car is and ending along the row; for the nearest rows, else a route
  /// searched over the car's own motions. Tried for the nearest rows (more when desperate).
  template <class Nearest>
  bool routeStep(Pose pose, Nearest& nearest, std::vector<Candidate>& taken) {
    const std::size_t routed_tries = steps_.empty() || desperate_ ? 8 * kMaxRoutedTries : kMaxRoutedTries;
    for (std::size_t t = 0; t < routed_tries; ++t) {
      if (t == taken.size()) {
        const std::optional<Candidate> more = nearest.next();
        if (!more) break;
        taken.push_back(*more);
      }
      const Candidate c = taken[t];
      const Point ahead = pose.at + Point{std::cos(pose.heading), std::sin(pose.heading)} * 1e-3;
      const bool facing_free = ws_.router().isFree(pose.at, ahead);
      Link link;  // from the car through the row
      if (facing_free) link = smoothedRoute(pose, ahead, c);
      // The smoothed route does not take the car there (it would turn tighter than it can, or
      // the car faces F's edge): a search over the car's own motions, for the nearest rows.
      bool searched = false;
      if (link.path.segments() == 0 && t < kSearchTries && searched_poses_ < kSearchBudget) {
        link = searchedRoute(pose, c);
        searched = link.path.segments() > 0;
      }
      if (link.path.segments() == 0) {
        if (!facing_free && t + 1 >= kSearchTries) break;
        continue;
      }
      steps_.push_back({c.row, c.from_a, out_.path.waypoints.size(), searched ? 's' : 'r', link.cusps});
      furthest_ = std::max(furthest_, steps_.size());
      append(out_.path, link.path);
      markDone(c.row, true);
      ++(searched ? out_.searched : out_.routed);
      out_.cusps += link.cusps;
      out_.undriven_m += link.cut;
      return true;
    }
    return false;
  }
  /// The workspace's route from just ahead of the car to row c's entry, through the row, smoothed
  /// for the car; empty unless it starts along the car's pose and arrives.
  Link smoothedRoute(Pose pose, Point ahead, const Candidate& c) {
    Link link;
    if (const auto route = ws_.route(ahead, entryOf(c.row, c.from_a))) {
      Path input;
      input.moveTo(pose.at, false);
      for (const Point& p : *route) input.moveTo(p, false);
      input.moveTo(exitOf(c.row, c.from_a), true);
      CarSmoothing smoothed = smoothForCar(ws_, input);
      if (!smoothed.stopped && smoothed.path.segments() > 0 &&
          distance(smoothed.path.waypoints.back(), exitOf(c.row, c.from_a)) <= 1e-9 && startsAlong(smoothed.path, pose, car_.reverse)) {
        link.path = std::move(smoothed.path);
        link.cusps = smoothed.cusps;
        link.cut = smoothed.cut_m;
      }
    }
    return link;
  }
  /// A route searched over the car's own motions (searchCarRoute) into row c, through the row;
  /// empty when none was found within the sweep's search budget.
  Link searchedRoute(Pose pose, const Candidate& c) {
    Link link;
    link.path = searchCarRoute(ws_, pose, poseInto(c.row, c.from_a), rho_, car_.reverse,
                               std::min(kSearchExpansions, kSearchBudget - searched_poses_), &searched_poses_);
    if (link.path.segments() > 0) {
      link.path.moveTo(exitOf(c.row, c.from_a), true);
      link.cusps = cusps(link.path);
    }
    return link;
  }

  // --- Stuck.

  /// Stuck where the rings end (facing F's edge closer than a turn): stop their last straight
  /// stretch short, by a quarter of a turn radius more each time, up to three radii. Whether it
  /// was cut shorter.
  bool cutRingEndShort() {
    if (!(!continuing_ && steps_.empty() && out_.links == 0 && out_.path.segments() > 0 &&
          out_.path.bulgeOf(out_.path.segments() - 1) == 0.0))
      return false;
    const std::size_t k = out_.path.segments() - 1;
    if (retreat_ == 0.0) tail_ = {out_.path.waypoints[k], out_.path.waypoints[k + 1]};
    retreat_ += 0.25 * rho_;
    const double length = distance(tail_.first, tail_.second);
    if (retreat_ < length && retreat_ <= 3.0 * rho_ + 1e-12) {
      out_.path.waypoints[k + 1] = tail_.second + (tail_.first - tail_.second) * (retreat_ / length);
      return true;
    }
    return false;
  }
  /// Still stuck there: the rings end in a dead end no curve, route or search leaves (a strip
  /// narrower than a turn, an obstacle's corner). Give up their last segments and try again.
  bool giveUpRingEnd() {
    if (!(!continuing_ && steps_.empty() && out_.links == 0 && out_.path.segments() > 1 && ring_given_up_ < kRingGiveUpRadii * rho_))
      return false;
    giveUpRingTail();
    retreat_ = 0.0;  // the straight cut-back starts over on the new last stretch
    return true;
  }
  /// Stuck at this row's end: go back to before it, and never enter it that way again; at most
  /// kMaxBacktracks rows back from the furthest the sweep got (then tryHarder). False when the
  /// sweep ends (the rest is left out).
  bool goBack() {
    if (steps_.empty() || out_.backtracks >= max_backtracks_ || steps_.size() + kMaxBacktracks <= furthest_) return tryHarder();
    const Step last = steps_.back();
    steps_.pop_back();
    out_.path.waypoints.resize(last.waypoints);
    out_.path.tool_on.resize(last.waypoints - 1);
    if (!out_.path.bulge.empty()) out_.path.bulge.resize(last.waypoints - 1);
    markDone(last.row, false);
    lowest_line_ = 0;
    dead_[last.row] |= last.from_a ? 1 : 2;
    if (!takenLast(last.row) && dead_[last.row] == 3) --first_left_;
    ++out_.backtracks;
    (last.how == 'c' ? out_.links : last.how == 'r' ? out_.routed : out_.searched) -= 1;
    out_.cusps -= last.cusps;
    return true;
  }
  /// Once more, trying routes to many more rows; then once more with the rows taken last, though
  /// rows not taken last are left (none of them was reached); then false: the rest is left out.
  bool tryHarder() {
    if (desperate_) {
      bool last_left = false;
      for (std::size_t i = 0; i < n_ && !last_left; ++i) last_left = takenLast(i) && !done_[i];
      if (last_open_ || !last_left) return false;
      last_open_ = true;
      return true;
    }
    desperate_ = true;
    return true;
  }

  /// A forward-only car may end its path in a dead end: the nearest row left whose curve is free,
  /// though it cannot come out of it.
  void endInDeadEnd() {
    const Pose pose = endPose(out_.path);
    std::vector<std::tuple<double, std::size_t, bool>> left;  // curve length, row, from a
    for (std::size_t i = 0; i < n_; ++i)
      for (bool from_a : {true, false})
        if (!done_[i]) left.emplace_back(carCurveLength(pose, poseInto(i, from_a), rho_, false), i, from_a);
    std::sort(left.begin(), left.end());
    for (const auto& [length, i, from_a] : left) {
      if (!std::isfinite(length)) break;
      const Path curve = carCurve(pose, poseInto(i, from_a), rho_, false, false);
      if (curve.waypoints.empty() || !pathFree(ws_, curve)) continue;
      out_.dead_end_from = out_.path.waypoints.size();
      out_.dead_end_row = rows_[i];
      out_.dead_end_fill = i >= first_fill_;
      append(out_.path, curve);
      driveRow(i, from_a);
      ++out_.links;
      out_.ended_in_dead_end = true;
      break;
    }
  }

  Workspace& ws_;
  const VehicleModel& car_;
  const double rho_;
  CarSweep& out_;
  const Budget& budget_;
  const double spacing_, line_penalty_;
  const bool continuing_;  // the sweep goes on from a path (a fill round): no rings to cut back

  // The rows (given, ring passes, then fill passes from first_fill_ on) and what is known of them.
  const std::vector<CarRow> rows_;
  const std::size_t n_;
  const std::size_t first_fill_;
  bool ordered_ = false;              // some row has a cell of a cell order
  std::vector<char> done_;            // painted
  std::vector<char> last_row_;        // taken last (takenLast)
  // Ways into a row found to be dead ends (the car got in and no curve took it anywhere): bit 1
  // from a, bit 2 from b.
  std::vector<char> dead_;
  std::size_t remaining_;             // rows not painted
  std::vector<double> heading_ab_;    // each row's heading from a to b
  std::size_t lines_ = 0;
  Point along_{1.0, 0.0};
  std::vector<std::vector<std::size_t>> by_line_;
  std::vector<double> lo_x_, hi_x_;   // each row's extent along the lines
  std::size_t lowest_line_ = 0;       // no unpainted row lies below it (set each step)
  // Per row, a line below which no row beside it is unpainted (rows only get painted between
  // backtracks, which start these over): where lowestBeside looks from next time.
  std::vector<std::size_t> beside_from_;
  std::vector<Stack> stacks_;
  std::vector<std::size_t> stack_of_, stack_pos_;
  std::vector<std::size_t> follow_;   // the row carBlockOrder takes after this one
  // Rows left that hold the rows taken last back (holdsLastBack), and the rows by cell (in the
  // order, then rows of no cell), the first `open_from_` of them painted: counted as rows are
  // painted or found dead ends, not each step.
  std::size_t first_left_ = 0;
  std::vector<std::size_t> by_cell_;
  std::size_t open_from_ = 0;
  EntryGrid entries_;                 // the unpainted rows' ends

  // The sweep's progress.
  std::vector<Step> steps_;
  std::size_t first_row_ = kNone;     // the row the path starts with, when there are no rings
  double ring_given_up_ = 0.0;        // how much of the rings' end was given up (m)
  Path rings_whole_;                  // restored if giving up their end took the car nowhere
  CarSmoothing headland_whole_;
  std::size_t searched_poses_ = 0;    // by searchCarRoute, over the whole sweep
  std::size_t max_backtracks_ = 0;
  std::size_t furthest_ = 0;          // the most rows the sweep had driven
  bool desperate_ = false;            // stuck after going back: routes to many more rows are tried
  bool last_open_ = false;            // still stuck so: the rows taken last may be taken
  double retreat_ = 0.0;              // how far the rings' last stretch is cut back
  std::pair<Point, Point> tail_;      // that stretch as the rings drove it
};

}  // namespace

CarSweep sweepOnce(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& given,
                   const std::vector<CarRow>& fill, double spacing, const Budget& budget, double line_penalty,
                   const Path* from, int rings_as_passes, std::size_t ring_start) {
  CarSweep out;
  driveRings(ws, rings, loops, spacing, rings_as_passes, ring_start, out);
  out.path = from ? *from : out.headland.path;
  // The rows: those given, the passes along what the rings' smoothing skipped, then the fill
  // passes (taken last, as are the passes made of runs: run_pass).
  std::vector<CarRow> rows = given;
  std::vector<char> run_pass(given.size(), 0);
  out.ring_passes = addRingPasses(ws, out.headland.undriven, spacing, rows, run_pass);
  out.rows = rows.size();
  const std::size_t first_fill = rows.size();
  for (const CarRow& pass : fill) {
    rows.push_back(pass);
    run_pass.push_back(1);
  }
  RowSweep sweep(ws, out, std::move(rows), run_pass, first_fill, spacing, budget, line_penalty, from != nullptr);
  sweep.run();
  sweep.finish();
  checkDrivable(out.path, ws.vehicle(), "the car's sweep");
  return out;
}

}  // namespace coverbench::vehicle_detail
