// Deposition of a sprayed coat on a raster (definitions: deposition.hpp, docs/deposition.md).
#include "coverbench/deposition.hpp"

#include <algorithm>
#include <cmath>

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
                     const std::vector<SegmentSpeed>& speeds, DepositionGrid& grid) {
  grid.thickness.assign(grid.nx * grid.ny, 0.0);
  const double r = tool.radius(), depth = profile.depthFor(tool.tool_width), h = grid.cell;
  const double scale = profile.rate / depth;  // Q / l
  for (const Piece& p : pieces(path, speeds, h)) {
    const Point d = p.b - p.a;
    const double len = norm(d);
    if (!(len > 0.0)) continue;
    const Point u{d.x / len, d.y / len}, n{-u.y, u.x};
    const double reach = r + depth / 2.0;  // no cell farther from the chord is touched
    std::size_t i0, i1, j0, j1;
    grid.range(std::fmin(p.a.x, p.b.x) - reach, std::fmax(p.a.x, p.b.x) + reach, grid.x0, grid.nx, i0, i1);
    grid.range(std::fmin(p.a.y, p.b.y) - reach, std::fmax(p.a.y, p.b.y) + reach, grid.y0, grid.ny, j0, j1);
    const double ratio = (p.s1 - p.s0) / len;  // segment distance per chord distance
    for (std::size_t j = j0; j < j1; ++j)
      for (std::size_t i = i0; i < i1; ++i) {
        const Point q = grid.centre(i, j) - p.a;
        const double x = q.x * n.x + q.y * n.y;
        if (!(std::fabs(x) <= r)) continue;
        const double t = q.x * u.x + q.y * u.y;
        const double lo = std::fmax(0.0, t - depth / 2.0), hi = std::fmin(len, t + depth / 2.0);
        if (!(hi > lo)) continue;
        const double tau = p.speed->timeAt(p.s0 + hi * ratio) - p.speed->timeAt(p.s0 + lo * ratio);
        grid.thickness[j * grid.nx + i] += scale * profile.density(x, r) * tau;
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

Deposition depositionStats(const DepositionGrid& grid, const std::vector<char>& mask, double target_um) {
  Deposition out;
  out.cell = grid.cell;
  double sum = 0.0;
  for (std::size_t k = 0; k < grid.thickness.size(); ++k)
    if (mask[k]) {
      sum += grid.thickness[k];
      ++out.cells;
    }
  if (out.cells == 0) return out;
  const double count = static_cast<double>(out.cells), mean = sum / count;
  double squares = 0.0;  // of (h - mean) / mean: squares of tiny coats (a rate of 1e-170) would underflow
  std::size_t even = 0, thin = 0, thick = 0;
  const double c = target_um > 0.0 ? target_um * 1e-6 : mean;  // the shares' reference, m
  for (std::size_t k = 0; k < grid.thickness.size(); ++k)
    if (mask[k]) {
      const double h = grid.thickness[k];
      if (mean > 0.0) squares += (h / mean - 1.0) * (h / mean - 1.0);
      if (h < 0.9 * c || c == 0.0) ++thin;
      else if (h > 1.1 * c) ++thick;
      else ++even;
    }
  out.mean_um = mean * 1e6;
  out.cv = mean > 0.0 ? std::sqrt(squares / count) : 0.0;
  out.even_share = static_cast<double>(even) / count;
  out.thin_share = static_cast<double>(thin) / count;
  out.thick_share = static_cast<double>(thick) / count;
  return out;
}

CoatRaster coatRaster(const Wall& wall, const ToolParams& tool, const Path& path, const FluxProfile& profile,
                      const MotionLimits& limits, const VehicleModel& vehicle, double cell) {
  const double h = cell > 0.0 ? cell : depositionCell(tool, profile);
  const Region reachable = reachableRegion(wall, tool);
  const Box box = boundingBox(reachable);
  CoatRaster out;
  if (box.empty()) return out;
  const double nx = 2.0 * std::ceil(box.width() / h), ny = 2.0 * std::ceil(box.height() / h);  // samples
  if (!(nx * ny <= static_cast<double>(kMaxDepositionCells)))
    throw InputError("deposition", "tool.profile",
                     "needs a coat raster of " + shortNumber(nx * ny) + " samples over the reachable region (4 per cell of " + shortNumber(h) +
                         " m, the smaller of s/40 and the profile's spread/5), at most " + std::to_string(kMaxDepositionCells) +
                         ": a wider tool or a smaller wall");
  DepositionGrid& grid = out.grid;
  grid.x0 = box.min_x;
  grid.y0 = box.min_y;
  grid.cell = h;
  grid.gauss = true;
  grid.nx = static_cast<std::size_t>(std::max(2.0, nx));
  grid.ny = static_cast<std::size_t>(std::max(2.0, ny));
  depositionField(path, tool, profile, segmentSpeeds(path, limits, vehicle), grid);
  out.mask = rasterMask(reachable, grid);
  return out;
}

Deposition deposition(const Wall& wall, const ToolParams& tool, const Path& path, const FluxProfile& profile,
                      const MotionLimits& limits, const VehicleModel& vehicle, double cell) {
  const CoatRaster raster = coatRaster(wall, tool, path, profile, limits, vehicle, cell);
  return depositionStats(raster.grid, raster.mask, profile.target);
}

}  // namespace coverbench
