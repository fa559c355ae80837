// Deposition of a sprayed coat on a raster (definitions: deposition.hpp, docs/deposition.md).
#include "coverbench/deposition.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "coverbench/input_error.hpp"
#include "coverbench/metrics.hpp"

namespace coverbench {
namespace {

/// A straight piece of a tool-on segment: the segment itself, or one chord of an arc, with the
/// stretch [s0, s1] of the segment's speed profile it stands for.
struct Piece {
  Point a, b;
  const SegmentSpeed* speed;
  double s0, s1;
};

std::vector<Piece> pieces(const Path& path, const std::vector<SegmentSpeed>& speeds, double cell) {
  std::vector<Piece> out;
  for (std::size_t i = 0; i < path.segments(); ++i) {
    if (!path.tool_on[i] || !(speeds[i].length > 0.0)) continue;
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    const double bulge = path.bulgeOf(i);
    if (bulge == 0.0) {
      out.push_back({a, b, &speeds[i], 0.0, speeds[i].length});
      continue;
    }
    const ArcGeometry arc = arcGeometry(a, b, bulge);
    const std::size_t n = static_cast<std::size_t>(std::max(1.0, std::ceil(arcChords(arc, cell / 100.0))));
    const Point d = a - arc.centre;
    const double start = std::atan2(d.y, d.x);
    Point prev = a;
    for (std::size_t k = 1; k <= n; ++k) {
      const double f = static_cast<double>(k) / static_cast<double>(n);
      const double angle = start + f * arc.sweep;
      const Point next = k == n ? b : Point{arc.centre.x + arc.radius * std::cos(angle), arc.centre.y + arc.radius * std::sin(angle)};
      out.push_back({prev, next, &speeds[i], (f - 1.0 / static_cast<double>(n)) * speeds[i].length, f * speeds[i].length});
      prev = next;
    }
  }
  return out;
}

}  // namespace

double depositionCell(const ToolParams& tool, const FluxProfile& profile) {
  return std::fmin(tool.tool_width / 40.0, profile.spread(tool.radius()) / 5.0);
}

void DepositionGrid::range(double lo, double hi, double origin, std::size_t count, std::size_t& first, std::size_t& last) const {
  const double per = gauss ? 2.0 : 1.0;  // samples per cell along an axis
  const double a = std::floor((lo - origin) / cell) - 1.0, b = std::ceil((hi - origin) / cell) + 1.0;
  first = static_cast<std::size_t>(std::clamp(a * per, 0.0, static_cast<double>(count)));
  last = static_cast<std::size_t>(std::clamp(b * per, 0.0, static_cast<double>(count)));
}

void depositionField(const Path& path, const ToolParams& tool, const FluxProfile& profile,
                     const std::vector<SegmentSpeed>& speeds, double cruise, DepositionGrid& grid) {
  grid.thickness.assign(grid.nx * grid.ny, 0.0);
  const double r = tool.radius(), depth = profile.depthFor(tool.tool_width), h = grid.cell;
  const double scale = profile.rate / depth;  // Q / l
  const FluxDensity density(profile, r);
  const bool per_metre = profile.flow == FluxProfile::Flow::Speed;
  if (per_metre && !(cruise > 0.0 && std::isfinite(cruise)))
    throw std::invalid_argument("depositionField: a flow that follows the speed needs a finite time model speed");
  for (const Piece& p : pieces(path, speeds, h)) {
    const Point d = p.b - p.a;
    const double len = norm(d);
    if (!(len > 0.0)) continue;
    const Point u{d.x / len, d.y / len}, n{-u.y, u.x};
    const double reach = r + depth / 2.0;  // no cell farther from the chord is touched
    std::size_t i0, i1, j0, j1;
    grid.range(std::fmin(p.a.x, p.b.x) - reach, std::fmax(p.a.x, p.b.x) + reach, grid.x0, grid.nx, i0, i1);
    grid.range(std::fmin(p.a.y, p.b.y) - reach, std::fmax(p.a.y, p.b.y) + reach, grid.y0, grid.row0 + grid.ny, j0, j1);
    j0 = std::max(j0, grid.row0) - grid.row0;  // the band's rows
    j1 = std::max(j1, grid.row0) - grid.row0;
    const double ratio = (p.s1 - p.s0) / len;  // segment distance per chord distance
    // f at the last lateral offset: along a raster row of a piece along x (n.x = 0) the offset is
    // the same at every sample, so is f; a piece along y is walked column by column for the same.
    double last_x = NAN, last_f = 0.0;
    const auto add = [&](std::size_t i, std::size_t j) {
      const Point q = grid.centre(i, j) - p.a;
      const double x = q.x * n.x + q.y * n.y;
      if (!(std::fabs(x) <= r)) return;
      const double t = q.x * u.x + q.y * u.y;
      const double lo = std::fmax(0.0, t - depth / 2.0), hi = std::fmin(len, t + depth / 2.0);
      if (!(hi > lo)) return;
      if (x != last_x) {
        last_x = x;
        last_f = density(x);
      }
      // The time the fan's depth spends over the sample, or (a flow that follows the speed) the
      // distance over it at the time model's speed.
      const double tau = per_metre ? (hi - lo) * ratio / cruise
                                   : p.speed->timeAt(p.s0 + hi * ratio) - p.speed->timeAt(p.s0 + lo * ratio);
      grid.thickness[j * grid.nx + i] += scale * last_f * tau;
    };
    // (Each sample gains at most once from a piece, so the walk's order leaves every sum as it is.)
    if (n.y == 0.0) {
      for (std::size_t i = i0; i < i1; ++i)
        for (std::size_t j = j0; j < j1; ++j) add(i, j);
    } else {
      for (std::size_t j = j0; j < j1; ++j)
        for (std::size_t i = i0; i < i1; ++i) add(i, j);
    }
  }
}

std::vector<char> rasterMask(const Region& region, const DepositionGrid& grid) {
  std::vector<char> mask(grid.nx * grid.ny, 0);
  std::vector<double> crossings;
  for (std::size_t j = 0; j < grid.ny; ++j) {
    const double y = grid.centre(0, j).y;
    crossings.clear();
    for (const PolygonWithHoles& polygon : region) {
      const auto add = [&](const Ring& ring) {
        for (std::size_t k = 0; k < ring.size(); ++k) {
          const Point a = ring[k], b = ring[(k + 1) % ring.size()];
          if ((a.y <= y) != (b.y <= y)) crossings.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
      };
      add(polygon.outer);
      for (const Ring& hole : polygon.holes) add(hole);
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {  // inside between pairs (even-odd)
      std::size_t first, last;
      grid.range(crossings[k], crossings[k + 1], grid.x0, grid.nx, first, last);
      for (std::size_t i = first; i < last; ++i) {
        const double x = grid.coordinate(grid.x0, i);
        if (x >= crossings[k] && x < crossings[k + 1]) mask[j * grid.nx + i] = 1;
      }
    }
  }
  return mask;
}

namespace {

/// The sums behind Deposition, over one raster or its bands in row order: first() over every
/// sample (the mean), then second() over the same samples in the same order (the spread and the
/// shares of c).
struct CoatTally {
  double sum = 0.0, squares = 0.0;  // squares of (h - mean) / mean: squares of tiny coats (a rate of 1e-170) would underflow
  std::size_t cells = 0, even = 0, thin = 0, thick = 0;
  void first(const DepositionGrid& grid, const std::vector<char>& mask) {
    for (std::size_t k = 0; k < grid.thickness.size(); ++k)
      if (mask[k]) {
        sum += grid.thickness[k];
        ++cells;
      }
  }
  double mean() const { return sum / static_cast<double>(cells); }
  /// A coat past what a double holds has no mean, spread or shares: not scored, never "even".
  void checkFinite() const {
    if (!std::isfinite(sum) || (cells > 0 && !std::isfinite(mean() * 1e6)))
      throw InputError("deposition", "thickness", "is not finite over R (the rate over the speed is past what a double holds)");
  }
  void second(const DepositionGrid& grid, const std::vector<char>& mask, double c) {
    const double m = mean();
    for (std::size_t k = 0; k < grid.thickness.size(); ++k)
      if (mask[k]) {
        const double h = grid.thickness[k];
        if (m > 0.0) squares += (h / m - 1.0) * (h / m - 1.0);
        if (h < 0.9 * c || c == 0.0) ++thin;
        else if (h > 1.1 * c) ++thick;
        else ++even;
      }
  }
  /// The shares' reference, m: the target (um) when there is one, else the mean.
  double reference(double target_um) const { return target_um > 0.0 ? target_um * 1e-6 : mean(); }
  Deposition result(double cell) const {
    Deposition out;
    out.cell = cell;
    out.cells = cells;
    if (cells == 0) return out;
    const double count = static_cast<double>(cells), m = mean();
    out.mean_um = m * 1e6;
    out.cv = m > 0.0 ? std::sqrt(squares / count) : 0.0;
    out.even_share = static_cast<double>(even) / count;
    out.thin_share = static_cast<double>(thin) / count;
    out.thick_share = static_cast<double>(thick) / count;
    return out;
  }
};

}  // namespace

Deposition depositionStats(const DepositionGrid& grid, const std::vector<char>& mask, double target_um) {
  CoatTally tally;
  tally.first(grid, mask);
  tally.checkFinite();
  if (tally.cells > 0) tally.second(grid, mask, tally.reference(target_um));
  return tally.result(grid.cell);
}

Coat coat(const Wall& wall, const ToolParams& tool, const Path& path, const FluxProfile& profile, const MotionLimits& limits,
          const VehicleModel& vehicle, std::size_t block_cells, double cell, std::size_t band_samples) {
  const double h = cell > 0.0 ? cell : depositionCell(tool, profile);
  const Region reachable = reachableRegion(wall, tool);
  const Box box = boundingBox(reachable);
  Coat out;
  if (box.empty()) return out;
  const double nx = 2.0 * std::ceil(box.width() / h), ny = 2.0 * std::ceil(box.height() / h);  // samples
  if (!(nx * ny <= kMaxCoatSamples))
    throw InputError("deposition", "tool.profile",
                     "needs a coat raster of " + shortNumber(nx * ny) + " samples over the reachable region (4 per cell of " + shortNumber(h) +
                         " m, the smaller of s/40 and the profile's spread/5), at most " + shortNumber(kMaxCoatSamples) +
                         ": a wider tool or a smaller wall");
  DepositionGrid grid;
  grid.x0 = box.min_x;
  grid.y0 = box.min_y;
  grid.cell = h;
  grid.gauss = true;
  grid.nx = static_cast<std::size_t>(std::max(2.0, nx));
  const std::size_t rows = static_cast<std::size_t>(std::max(2.0, ny));
  const std::size_t band = std::max<std::size_t>(2, band_samples / grid.nx);
  const std::vector<SegmentSpeed> speeds = segmentSpeeds(path, limits, vehicle);
  std::vector<char> mask;
  const auto fill = [&](std::size_t row0) {
    grid.row0 = row0;
    grid.ny = std::min(band, rows - row0);
    depositionField(path, tool, profile, speeds, limits.speed, grid);
    mask = rasterMask(reachable, grid);
  };
  CoatBlocks& b = out.blocks;
  std::vector<std::size_t> counts;
  if (block_cells > 0) {
    const std::size_t span = 2 * block_cells;  // samples a block is wide
    b.cells = block_cells;
    b.bx = (grid.nx + span - 1) / span;
    b.by = (rows + span - 1) / span;
    b.x0 = grid.x0;
    b.y0 = grid.y0;
    b.side = static_cast<double>(block_cells) * h;
    b.mean.assign(b.bx * b.by, 0.0);
    counts.assign(b.bx * b.by, 0);
  }
  CoatTally tally;
  for (std::size_t row0 = 0; row0 < rows; row0 += band) {
    fill(row0);
    tally.first(grid, mask);
    for (std::size_t j = 0; block_cells > 0 && j < grid.ny; ++j)
      for (std::size_t i = 0; i < grid.nx; ++i)
        if (mask[j * grid.nx + i]) {
          const std::size_t k = (row0 + j) / (2 * block_cells) * b.bx + i / (2 * block_cells);
          b.mean[k] += grid.thickness[j * grid.nx + i];
          ++counts[k];
        }
  }
  tally.checkFinite();
  for (std::size_t k = 0; k < b.mean.size(); ++k) b.mean[k] = counts[k] ? b.mean[k] / static_cast<double>(counts[k]) : NAN;
  if (tally.cells > 0)
    for (std::size_t row0 = 0; row0 < rows; row0 += band) {
      if (band < rows) fill(row0);  // one band is still there
      tally.second(grid, mask, tally.reference(profile.target));
    }
  out.stats = tally.result(h);
  return out;
}

Deposition deposition(const Wall& wall, const ToolParams& tool, const Path& path, const FluxProfile& profile,
                      const MotionLimits& limits, const VehicleModel& vehicle, double cell) {
  return coat(wall, tool, path, profile, limits, vehicle, 0, cell).stats;
}

}  // namespace coverbench
