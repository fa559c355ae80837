// What a forward-only car could paint at best: viable poses on a lattice (car_ceiling.hpp,
// docs/metrics.md).
#include "coverbench/car_ceiling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "coverbench/clearance.hpp"

namespace coverbench {
namespace {

/// Samples along each motion at which its cell must be free (the last is where it ends).
constexpr std::size_t kSamples = 4;
/// A motion is about this many cells long: long enough that rounding each to the lattice bends
/// it little, short enough that it does not jump over an obstacle's corner between its samples.
constexpr double kStepCells = 5.0;

struct Lattice {
  double x0 = 0.0, y0 = 0.0, g = 0.0;
  long nx = 0, ny = 0;
  std::size_t h = 0;
  long turns = 0;  // a motion turns the heading by -turns..turns steps
  std::vector<char> free;
  // offsets[(j * (2 * turns + 1) + k + turns) * kSamples + q]: the cell offset of sample q of the
  // motion turning by k steps from heading j.
  std::vector<std::array<int, 2>> offsets;

  std::size_t motions() const { return static_cast<std::size_t>(2 * turns + 1); }
  const std::array<int, 2>& offset(std::size_t j, long k, std::size_t q) const {
    return offsets[(j * motions() + static_cast<std::size_t>(k + turns)) * kSamples + q];
  }
  bool freeAt(long x, long y) const { return x >= 0 && y >= 0 && x < nx && y < ny && free[static_cast<std::size_t>(y * nx + x)]; }
  /// The motion turning by k from heading j, starting at cell (x, y), stays on free cells.
  bool motionFree(long x, long y, std::size_t j, long k) const {
    for (std::size_t q = 0; q < kSamples; ++q) {
      const auto& o = offset(j, k, q);
      if (!freeAt(x + o[0], y + o[1])) return false;
    }
    return true;
  }
  std::size_t heading(long j) const {
    const long n = static_cast<long>(h);
    return static_cast<std::size_t>(((j % n) + n) % n);
  }
  /// The pose motion k leads to from (x, y, j) (ahead), or comes from into it (not ahead); false
  /// when that motion is not free.
  bool neighbour(long x, long y, std::size_t j, long k, bool ahead, long& to_x, long& to_y, std::size_t& to_j) const {
    return reaches(x, y, j, k, ahead, to_x, to_y, to_j) && joined(x, y, j, k, ahead, to_x, to_y, to_j);
  }
  /// The pose motion k would lead to, or come from, as neighbour() says, and whether it lies on the
  /// lattice; not whether the motion is free (joined()).
  bool reaches(long x, long y, std::size_t j, long k, bool ahead, long& to_x, long& to_y, std::size_t& to_j) const {
    to_j = ahead ? heading(static_cast<long>(j) + k) : heading(static_cast<long>(j) - k);
    const auto& o = offset(ahead ? j : to_j, k, kSamples - 1);
    to_x = ahead ? x + o[0] : x - o[0];
    to_y = ahead ? y + o[1] : y - o[1];
    return to_x >= 0 && to_y >= 0 && to_x < nx && to_y < ny;
  }
  /// Whether the motion between (x, y, j) and the pose reaches() gave is free.
  bool joined(long x, long y, std::size_t j, long k, bool ahead, long to_x, long to_y, std::size_t to_j) const {
    return ahead ? motionFree(x, y, j, k) : freeAt(to_x, to_y) && motionFree(to_x, to_y, to_j, k);
  }
};

/// Chains longer than this many poses are not told apart (chain lengths are kept in a byte a pose).
constexpr unsigned kLongChain = 255;
/// A piece of F's largest viable components are each a candidate of their own; the rest one
/// together.
constexpr std::size_t kComponents = 8;

/// Clears `alive` bit `bit` of every pose that has no motion on to (forward) or in from
/// (backward) a pose that keeps the bit: the greatest such set, by removing poses one at a time
/// and counting down their neighbours. The poses removed have no such motion among them that
/// ever comes back (a cycle would keep its poses), so they are ordered: each is removed after
/// every pose it leads to (forward; comes from, backward). `chain` gets, for each, the most poses
/// a car passes through among them from it on (forward) or up to it (backward), itself included
/// (kLongChain for that many or more).
void viable(const Lattice& lat, std::vector<std::uint8_t>& alive, std::uint8_t bit, bool forward, std::vector<std::uint8_t>& chain) {
  const std::size_t h = lat.h;
  // While a pose keeps the bit: its ways on (in) that keep it. Once removed: its chain.
  std::vector<std::uint8_t>& count = chain;
  count.assign(alive.size(), 0);
  std::vector<std::uint32_t> stack;
  // The chain of a pose being removed: one more than the longest of its ways on (in), every one
  // of them removed already.
  auto chainOf = [&](std::size_t s) {
    const std::size_t j = s % h, cell = s / h;
    const long x = static_cast<long>(cell) % lat.nx, y = static_cast<long>(cell) / lat.nx;
    unsigned longest = 0;
    for (long k = -lat.turns; k <= lat.turns; ++k) {
      long nx, ny;
      std::size_t nj;
      if (lat.neighbour(x, y, j, k, forward, nx, ny, nj)) longest = std::max<unsigned>(longest, count[static_cast<std::size_t>(ny * lat.nx + nx) * h + nj]);
    }
    return static_cast<std::uint8_t>(std::min(kLongChain, longest + 1));
  };
  for (long y = 0; y < lat.ny; ++y)
    for (long x = 0; x < lat.nx; ++x) {
      if (!lat.freeAt(x, y)) continue;
      for (std::size_t j = 0; j < h; ++j) {
        const std::size_t s = static_cast<std::size_t>(y * lat.nx + x) * h + j;
        std::uint8_t n = 0;
        for (long k = -lat.turns; k <= lat.turns; ++k) {
          long nx, ny;
          std::size_t nj;
          n += lat.neighbour(x, y, j, k, forward, nx, ny, nj);
        }
        count[s] = n;
        if (n == 0) {
          alive[s] &= static_cast<std::uint8_t>(~bit);
          count[s] = 1;  // no way on (in): a chain of itself
          stack.push_back(static_cast<std::uint32_t>(s));
        }
      }
    }
  // A removed pose takes one from the count of every pose that had it as a way on (in), and
  // removes those left with none.
  while (!stack.empty()) {
    const std::size_t s = stack.back();
    stack.pop_back();
    const std::size_t j = s % h, cell = s / h;
    const long x = static_cast<long>(cell) % lat.nx, y = static_cast<long>(cell) / lat.nx;
    for (long k = -lat.turns; k <= lat.turns; ++k) {
      // The poses whose motion k reaches s (forward) or leaves from s (backward): the other
      // direction's neighbours.
      long px, py;
      std::size_t pj;
      if (!lat.neighbour(x, y, j, k, !forward, px, py, pj)) continue;
      const std::size_t p = static_cast<std::size_t>(py * lat.nx + px) * h + pj;
      if (!(alive[p] & bit)) continue;
      if (--count[p] == 0) {
        alive[p] &= static_cast<std::uint8_t>(~bit);
        count[p] = chainOf(p);
        stack.push_back(static_cast<std::uint32_t>(p));
      }
    }
  }
}

/// The viable poses' components: poses joined by a motion between two viable poses, either way
/// (`alive` 3; each is marked 4 as it is reached). A path's poses from the first viable one to the
/// last are all viable (each has the path's past and its future), so they lie in one component:
/// it cannot paint from two. Returns each component's cells, each once; the most cells first.
std::vector<std::vector<std::uint32_t>> viableComponents(const Lattice& lat, std::vector<std::uint8_t>& alive) {
  const std::size_t h = lat.h;
  std::vector<std::vector<std::uint32_t>> out;
  // The component (its number + 1) that last listed each cell.
  std::vector<std::uint32_t> listed_by(static_cast<std::size_t>(lat.nx * lat.ny), 0);
  std::vector<std::uint32_t> layer, next;
  for (std::size_t s0 = 0; s0 < alive.size(); ++s0) {
    if (alive[s0] != 3) continue;
    out.emplace_back();
    std::vector<std::uint32_t>& cells = out.back();
    const auto id = static_cast<std::uint32_t>(out.size());
    alive[s0] |= 4;
    layer.assign(1, static_cast<std::uint32_t>(s0));
    while (!layer.empty()) {
      next.clear();
      for (const std::uint32_t s : layer) {
        const std::size_t j = s % h, cell = s / h;
        if (listed_by[cell] != id) {
          listed_by[cell] = id;
          cells.push_back(static_cast<std::uint32_t>(cell));
        }
        const long x = static_cast<long>(cell) % lat.nx, y = static_cast<long>(cell) / lat.nx;
        for (long k = -lat.turns; k <= lat.turns; ++k)
          for (const bool ahead : {true, false}) {
            long nx, ny;
            std::size_t nj;
            if (!lat.reaches(x, y, j, k, ahead, nx, ny, nj)) continue;
            const std::size_t n = static_cast<std::size_t>(ny * lat.nx + nx) * h + nj;
            if (alive[n] != 3 || !lat.joined(x, y, j, k, ahead, nx, ny, nj)) continue;
            alive[n] |= 4;
            next.push_back(static_cast<std::uint32_t>(n));
          }
      }
      layer.swap(next);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return out;
}

/// The lattice for `wall` (cells of options.resolution, raised where the wall would need more
/// than options.max_states poses), F on it (cells whose centre a tool of radius r may be on), and
/// the motions (arcs of one length turning by -turns..turns heading steps, the sharpest at the
/// turn radius, each rounded to the lattice at its samples). `step`: the motions' length.
Lattice makeLattice(const Wall& wall, const ToolParams& tool, const CarCeilingOptions& options, double r, double& step) {
  Lattice lat;
  double x1 = wall.boundary.front().x, y1 = wall.boundary.front().y;
  lat.x0 = x1;
  lat.y0 = y1;
  for (const Point& p : wall.boundary) {
    lat.x0 = std::min(lat.x0, p.x);
    lat.y0 = std::min(lat.y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  lat.h = options.headings;
  lat.g = options.resolution;
  const double cells_allowed = static_cast<double>(options.max_states) / static_cast<double>(lat.h);
  if ((x1 - lat.x0) * (y1 - lat.y0) / (lat.g * lat.g) > cells_allowed) lat.g = std::sqrt((x1 - lat.x0) * (y1 - lat.y0) / cells_allowed) * 1.01;
  lat.nx = static_cast<long>(std::ceil((x1 - lat.x0) / lat.g)) + 1;
  lat.ny = static_cast<long>(std::ceil((y1 - lat.y0) / lat.g)) + 1;
  if (static_cast<double>(lat.nx) * static_cast<double>(lat.ny) * static_cast<double>(lat.h) >= 4.0e9)
    throw std::invalid_argument("car ceiling: the wall needs too many poses");
  auto centre = [&](long x, long y) { return Point{lat.x0 + (static_cast<double>(x) + 0.5) * lat.g, lat.y0 + (static_cast<double>(y) + 0.5) * lat.g}; };

  // F on the lattice: cells whose centre a tool may be on.
  const ClearanceField field(wall);
  lat.free.assign(static_cast<std::size_t>(lat.nx * lat.ny), 0);
  for (long y = 0; y < lat.ny; ++y)
    for (long x = 0; x < lat.nx; ++x) {
      const Point p = centre(x, y);
      const SegmentClearance m = field.measure(p, p, r + tool.clearance);
      lat.free[static_cast<std::size_t>(y * lat.nx + x)] = m.inside && m.boundary_distance >= r && m.obstacle_distance >= r + tool.clearance;
    }

  // Motions: arcs of one length turning by -turns..turns heading steps, the sharpest at the turn
  // radius, each rounded to the lattice at its samples.
  const double dh = 2.0 * M_PI / static_cast<double>(lat.h);
  lat.turns = std::max(1L, std::lround(kStepCells * lat.g / (dh * options.turn_radius)));
  step = static_cast<double>(lat.turns) * dh * options.turn_radius;
  lat.offsets.resize(lat.h * lat.motions() * kSamples);
  for (std::size_t j = 0; j < lat.h; ++j)
    for (long k = -lat.turns; k <= lat.turns; ++k)
      for (std::size_t q = 0; q < kSamples; ++q) {
        const double t = static_cast<double>(q + 1) / kSamples, turn = static_cast<double>(k) * dh;
        double dx = step * t, dy = 0.0;
        if (k != 0) {
          const double rho = step / turn;
          dx = rho * std::sin(turn * t);
          dy = rho * (1.0 - std::cos(turn * t));
        }
        const double th = static_cast<double>(j) * dh;
        const double wx = dx * std::cos(th) - dy * std::sin(th), wy = dx * std::sin(th) + dy * std::cos(th);
        lat.offsets[(j * lat.motions() + static_cast<std::size_t>(k + lat.turns)) * kSamples + q] = {
            static_cast<int>(std::lround(wx / lat.g)), static_cast<int>(std::lround(wy / lat.g))};
      }
  return lat;
}

/// What a dead end adds to the paint, and what a path's head or tail there can add: at most
/// what its longest chain paints.
struct End {
  double added = 0.0, head = 0.0, tail = 0.0;
};

/// The most a head and a tail add in dead ends: the head in one dead end and the tail in another
/// (the best two of each suffice), or both in one.
double bestEnds(const std::vector<End>& ends) {
  double extra = 0.0;
  std::array<std::size_t, 2> heads{ends.size(), ends.size()}, tails{ends.size(), ends.size()};
  auto keepBest = [&](std::array<std::size_t, 2>& top, std::size_t i, double End::*v) {
    if (top[0] == ends.size() || ends[i].*v > ends[top[0]].*v) top = {i, top[0]};
    else if (top[1] == ends.size() || ends[i].*v > ends[top[1]].*v) top[1] = i;
  };
  for (std::size_t i = 0; i < ends.size(); ++i) {
    extra = std::max(extra, std::min(ends[i].added, ends[i].head + ends[i].tail));
    keepBest(heads, i, &End::head);
    keepBest(tails, i, &End::tail);
  }
  for (std::size_t h : heads)
    for (std::size_t t : tails)
      if (h != ends.size() && t != ends.size() && h != t) extra = std::max(extra, ends[h].head + ends[t].tail);
  return extra;
}

/// What the tool paints on the lattice (cells whose centre lies within r of a centre the tool is
/// on), and the estimate's search over F's pieces: a path never leaves F, so it stays in one of
/// F's pieces (8-connected free cells), and its viable poses in one component: the estimate is the
/// best piece's, with the best component there. For a candidate (the cells of a component, or of
/// several: an interior), what the tool paints from them (marked with a fresh `base`), and the
/// dead ends (pieces of the piece of F outside the interior, each with a mark of its own) where a
/// head and a tail paint more.
class PieceSearch {
 public:
  /// `tail_here`, `head_here`: per cell, the longest tail and head chain from (up to) a pose there.
  PieceSearch(const Lattice& lat, double r, double step, std::vector<std::uint8_t> tail_here, std::vector<std::uint8_t> head_here)
      : lat_(lat), r_(r), step_(step), cells_(static_cast<std::size_t>(lat.nx * lat.ny)), tail_here_(std::move(tail_here)),
        head_here_(std::move(head_here)) {
    const long reach = static_cast<long>(std::ceil(r / lat.g));
    for (long dy = -reach; dy <= reach; ++dy)
      for (long dx = -reach; dx <= reach; ++dx)
        if (static_cast<double>(dx * dx + dy * dy) * lat.g * lat.g <= r * r * (1.0 + 1e-12)) disk_.push_back({static_cast<int>(dx), static_cast<int>(dy)});
  }

  /// The cells the tool paints from every free cell (R on the lattice).
  std::size_t reachable() const {
    std::size_t count = 0;
    std::vector<int> all(cells_, 0);
    for (std::size_t c = 0; c < cells_; ++c)
      if (lat_.free[c]) stamp(all, static_cast<long>(c) % lat_.nx, static_cast<long>(c) / lat_.nx, 1, 1, count);
    return count;
  }

  /// Each piece of F, with the viable components in it (`components`, the most cells first), as
  /// candidates; counts the pieces in out.pieces.
  void searchPieces(const std::vector<std::vector<std::uint32_t>>& components, CarCeiling& out) {
    paint_.assign(cells_, 0);
    piece_of_f_.assign(cells_, 0);
    dead_end_.assign(cells_, 0);
    piece_reach_.assign(cells_, 0);
    interior_.assign(cells_, 0);
    for (std::size_t c0 = 0; c0 < cells_; ++c0) {
      if (!lat_.free[c0] || piece_of_f_[c0]) continue;
      ++out.pieces;
      const int piece = static_cast<int>(out.pieces);
      const std::vector<std::size_t> here = flood(c0, piece_of_f_, piece, [](std::size_t) { return true; });
      std::size_t piece_r = 0;
      for (const std::size_t c : here) stamp(piece_reach_, static_cast<long>(c) % lat_.nx, static_cast<long>(c) / lat_.nx, piece, piece, piece_r);
      best_piece = std::max(best_piece, piece_r);
      // The piece's components, the largest first: the first kComponents each alone, the rest
      // together (their union bounds each of them); none (a piece without a viable pose).
      std::vector<const std::vector<std::uint32_t>*> mine;
      for (const auto& comp : components)
        if (piece_of_f_[comp.front()] == piece) mine.push_back(&comp);
      for (std::size_t i = 0; i < std::min(mine.size(), kComponents); ++i) candidate(here, {mine[i]});
      if (mine.size() > kComponents) candidate(here, std::vector<const std::vector<std::uint32_t>*>(mine.begin() + static_cast<std::ptrdiff_t>(kComponents), mine.end()));
      if (mine.empty()) candidate(here, {});
    }
  }

  std::size_t best_interior = 0;  ///< cells the best candidate's interior paints
  std::size_t best_piece = 0;     ///< R of the piece of F that holds the most of it, in cells
  double best_with_ends = 0.0;    ///< the best candidate's interior and ends, in cells

 private:
  /// Marks the cells the tool paints about cell (x, y) with `mark`; counts those it marks anew
  /// (those not marked `mark` or `base` already).
  void stamp(std::vector<int>& paint, long x, long y, int mark, int base, std::size_t& added) const {
    for (const auto& d : disk_) {
      const long px = x + d[0], py = y + d[1];
      if (px < 0 || py < 0 || px >= lat_.nx || py >= lat_.ny) continue;
      int& v = paint[static_cast<std::size_t>(py * lat_.nx + px)];
      if (v == base || v == mark) continue;
      v = mark;
      ++added;
    }
  }
  /// What a chain of `poses` poses paints at most, in cells: a tool's disk, and a band of its
  /// width along each motion (the band's rasters counted a cell wide and long more); nothing
  /// without a pose (a piece with no pose of a head, or of a tail); no bound for chains of
  /// kLongChain poses or more.
  double chainPaint(unsigned poses) const {
    if (poses == 0) return 0.0;
    if (poses >= kLongChain) return static_cast<double>(cells_);
    const double length = static_cast<double>(poses - 1) * step_;
    return static_cast<double>(disk_.size()) + (2.0 * r_ + lat_.g) * (length + lat_.g) / (lat_.g * lat_.g);
  }
  /// The free cells 8-connected to c that `admit` admits and `label` has not labelled, labelled
  /// `mark`, c first.
  template <class Admit>
  std::vector<std::size_t> flood(std::size_t c0, std::vector<int>& label, int mark, Admit admit) const {
    std::vector<std::size_t> found{c0}, todo{c0};
    label[c0] = mark;
    while (!todo.empty()) {
      const std::size_t c = todo.back();
      todo.pop_back();
      const long x = static_cast<long>(c) % lat_.nx, y = static_cast<long>(c) / lat_.nx;
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const long nx = x + dx, ny = y + dy;
          if (!lat_.freeAt(nx, ny)) continue;
          const std::size_t n = static_cast<std::size_t>(ny * lat_.nx + nx);
          if (label[n] || !admit(n)) continue;
          label[n] = mark;
          todo.push_back(n);
          found.push_back(n);
        }
    }
    return found;
  }
  /// The candidate whose interior is the cells of `parts`, in the piece of F whose cells are `here`.
  void candidate(const std::vector<std::size_t>& here, const std::vector<const std::vector<std::uint32_t>*>& parts) {
    for (const auto* part : parts)
      for (const std::uint32_t c : *part) interior_[c] = 1;
    const int base = ++mark_;
    std::size_t painted = 0;
    for (const std::size_t c : here) {
      dead_end_[c] = 0;
      if (interior_[c]) stamp(paint_, static_cast<long>(c) % lat_.nx, static_cast<long>(c) / lat_.nx, base, base, painted);
    }
    std::vector<End> ends;
    for (const std::size_t d0 : here) {
      if (interior_[d0] || dead_end_[d0]) continue;
      ++mark_;
      std::size_t added = 0;
      unsigned head = 0, tail = 0;
      for (const std::size_t c : flood(d0, dead_end_, mark_, [&](std::size_t n) { return !interior_[n]; })) {
        stamp(paint_, static_cast<long>(c) % lat_.nx, static_cast<long>(c) / lat_.nx, mark_, base, added);
        head = std::max<unsigned>(head, head_here_[c]);
        tail = std::max<unsigned>(tail, tail_here_[c]);
      }
      const double a = static_cast<double>(added);
      ends.push_back({a, std::min(a, chainPaint(head)), std::min(a, chainPaint(tail))});
    }
    for (const auto* part : parts)
      for (const std::uint32_t c : *part) interior_[c] = 0;
    best_interior = std::max(best_interior, painted);
    best_with_ends = std::max(best_with_ends, static_cast<double>(painted) + bestEnds(ends));
  }

  const Lattice& lat_;
  const double r_, step_;
  const std::size_t cells_;
  const std::vector<std::uint8_t> tail_here_, head_here_;
  std::vector<std::array<int, 2>> disk_;  // the cells the tool paints about a cell, as offsets
  std::vector<int> paint_, piece_of_f_, dead_end_, piece_reach_;
  std::vector<char> interior_;
  int mark_ = 0;
};

}  // namespace

CarCeiling forwardCarCeiling(const Wall& wall, const ToolParams& tool, const CarCeilingOptions& options) {
  if (!(options.turn_radius > 0.0) || !(options.resolution > 0.0) || options.headings < 8)
    throw std::invalid_argument("car ceiling: turn radius and resolution must be positive, and headings at least 8");
  if (wall.boundary.size() < 3) throw std::invalid_argument("car ceiling: the wall has no boundary");
  const double r = tool.tool_width / 2.0;
  double step = 0.0;
  const Lattice lat = makeLattice(wall, tool, options, r, step);

  const std::size_t cells = static_cast<std::size_t>(lat.nx * lat.ny);
  std::vector<std::uint8_t> alive(cells * lat.h, 0);
  CarCeiling out;
  for (std::size_t c = 0; c < cells; ++c)
    if (lat.free[c]) {
      std::fill_n(alive.begin() + static_cast<std::ptrdiff_t>(c * lat.h), lat.h, std::uint8_t{3});
      out.states += lat.h;
    }
  // Chains of poses without a future (a path's tail) and without a past (its head).
  std::vector<std::uint8_t> tail_chain, head_chain;
  viable(lat, alive, 1, true, tail_chain);
  viable(lat, alive, 2, false, head_chain);

  // Per cell, the longest tail and head chain from (up to) a pose there.
  std::vector<std::uint8_t> tail_here(cells, 0), head_here(cells, 0);
  for (std::size_t c = 0; c < cells; ++c)
    for (std::size_t j = 0; j < lat.h; ++j) {
      const std::size_t s = c * lat.h + j;
      if (!(alive[s] & 1)) tail_here[c] = std::max(tail_here[c], tail_chain[s]);
      if (!(alive[s] & 2)) head_here[c] = std::max(head_here[c], head_chain[s]);
    }
  for (std::size_t s = 0; s < alive.size(); ++s) out.viable += alive[s] == 3;
  const std::vector<std::vector<std::uint32_t>> components = viableComponents(lat, alive);
  out.components = components.size();
  alive = {};
  tail_chain = {};
  head_chain = {};

  PieceSearch search(lat, r, step, std::move(tail_here), std::move(head_here));
  const std::size_t reachable = search.reachable();
  search.searchPieces(components, out);
  const double cell_area = lat.g * lat.g;
  out.resolution = lat.g;
  out.headings = lat.h;
  out.step = step;
  out.reachable_area = static_cast<double>(reachable) * cell_area;
  out.interior_area = static_cast<double>(search.best_interior) * cell_area;
  out.with_ends_area = search.best_with_ends * cell_area;
  out.largest_piece_area = static_cast<double>(search.best_piece) * cell_area;
  if (reachable > 0) {
    out.interior = static_cast<double>(search.best_interior) / static_cast<double>(reachable);
    out.with_ends = std::min(1.0, search.best_with_ends / static_cast<double>(reachable));
    out.largest_piece = static_cast<double>(search.best_piece) / static_cast<double>(reachable);
  }
  return out;
}

}  // namespace coverbench
