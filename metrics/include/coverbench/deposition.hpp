#pragma once
/// Deposition: how thick a disk tool that sprays (paint, plaster) lays its coat, from the path and
/// the time model's speed along it. Definitions: docs/deposition.md. Only computed when the tool
/// has a flux profile; a tool without one has none of these metrics.
///
/// The model. The tool sprays Q m^3/s (its rate) as a fan: a strip across the direction of motion,
/// as wide as the tool (2r = s) and `depth` (l) deep along the motion, centred on the tool's
/// centre. Across the fan the flux follows the profile f(x), x the signed distance from the centre
/// across the motion, with f = 0 for |x| > r and the integral of f over [-r, r] equal to 1:
///   uniform:  f(x) = 1 / (2r)
///   gaussian: f(x) = exp(-x^2 / (2 sigma^2)) / (sigma sqrt(2 pi) erf(r / (sigma sqrt 2)))
///             (a Gaussian of standard deviation sigma, truncated at the tool's edge, normalised)
///   beta:     f(x) = (1 - u^2)^(beta - 1) / (r B(1/2, beta)),  u = x / r
/// Along its depth the fan is even: its flux per unit area is Q f(x) / l. While the tool drives a
/// tool-on segment at speed v(s), a point p at lateral offset x from the segment's line and at
/// distance t along it gains
///   h_i(p) = Q f(x) tau_i(p) / l,  tau_i(p) = T_i(min(L_i, t + l/2)) - T_i(max(0, t - l/2)),
/// where T_i(s) is the time model's time to reach s along segment i (SegmentSpeed::timeAt). At
/// constant speed v that is Q f(x) / v (the fan's steady profile); where the tool brakes it is the
/// mean of Q f(x) / v over the fan's depth, so a stop (speed 0 at a segment's end) deposits a
/// finite amount: the ramp to standstill takes finite time. Waits do not deposit: rotations in place
/// (rotation_speed) and a gantry's lowering and lifting are taken with the spray off. A gun whose flow
/// follows the speed (FluxProfile::Flow::Speed) sprays Q v / V at speed v (V the time model's
/// speed): h_i(p) = Q f(x) (min(L_i, t + l/2) - max(0, t - l/2)) / (l V), the steady coat at any
/// speed, so nothing builds up where the tool brakes or stops. Thickness is
/// the sum over tool-on segments; an arc is taken as chords with a sagitta under a hundredth of a
/// raster cell, each carrying its share of the arc's speed profile.
///
/// The raster. Thickness is evaluated at 2 x 2 Gauss-Legendre points of square cells of side
/// depositionCell() over the reachable region R (a point counts when it lies in R); the metrics
/// are means over the points.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "coverbench/flux_profile.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/motion.hpp"
#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// The raster's cell side (m): min(s / 40, spread / 5).
double depositionCell(const ToolParams& tool, const FluxProfile& profile);
/// The most samples of a raster held at once (4 per cell; about 180 MB): a raster with more is
/// computed in bands of rows, twice (its mean first, then its spread and shares), never coarser.
inline constexpr std::size_t kCoatBandSamples = 20000000;
/// The most samples a raster may have (4 per cell): a wall that would need more is refused (field
/// `tool.profile`). Time is the bound: a raster past the band is computed twice, about 35 ns a
/// sample each time here, so about 30 s at the cap, well inside a run's default hard deadline
/// (125 s) even on a machine twice as busy (docs/deposition.md). Every facade of the family at the
/// default width (s = 0.1 m: at most 3.1e8 samples for 16 walls of seed 1) fits.
inline constexpr double kMaxCoatSamples = 4e8;

/// Thickness (m) sampled on a raster of square cells of side `cell` from (x0, y0), the corner of
/// cell (0, 0): nx x ny samples, row-major. With `gauss` each cell holds 2 x 2 samples at the
/// Gauss-Legendre points (the cell's centre +- cell / (2 sqrt 3) on each axis; sample i lies in
/// cell i / 2), which integrate a smooth field to fourth order; without it one sample at each
/// cell's centre (the midpoint rule, second order). Each sample weighs the same.
///
/// A band of a larger raster holds its rows row0 .. row0 + ny - 1: sample (i, j) of the band is
/// sample (i, row0 + j) of the raster, at the same coordinates.
struct DepositionGrid {
  double x0 = 0.0, y0 = 0.0, cell = 0.0;
  std::size_t nx = 0, ny = 0;  ///< samples per row and rows of samples
  std::size_t row0 = 0;        ///< the first row's index in the whole raster
  bool gauss = false;
  std::vector<double> thickness;
  double coordinate(double origin, std::size_t i) const {
    if (!gauss) return origin + (static_cast<double>(i) + 0.5) * cell;
    const double side = (i % 2 ? 0.5 : -0.5) / std::sqrt(3.0);
    return origin + (static_cast<double>(i / 2) + 0.5 + side) * cell;
  }
  Point centre(std::size_t i, std::size_t j) const { return {coordinate(x0, i), coordinate(y0, row0 + j)}; }
  /// The samples whose coordinate may lie in [lo, hi] along an axis from `origin` (a few more at
  /// the ends), clamped to [0, count).
  void range(double lo, double hi, double origin, std::size_t count, std::size_t& first, std::size_t& last) const;
};
/// The thickness field of `path` on the raster `grid` (its thickness is overwritten), with the
/// speeds of segmentSpeeds(path, ...) and `cruise`, the time model's speed V (MotionLimits::speed):
/// a profile whose flow follows the speed (FluxProfile::Flow::Speed) sprays rate x v / V, so a
/// piece of a segment lays Q f(x) / (l V) per metre of it, whatever its speed.
void depositionField(const Path& path, const ToolParams& tool, const FluxProfile& profile,
                     const std::vector<SegmentSpeed>& speeds, double cruise, DepositionGrid& grid);
/// Per sample of `grid`, whether it lies in `region` (scanlines through the samples).
std::vector<char> rasterMask(const Region& region, const DepositionGrid& grid);

/// The deposition metrics over the samples counted (thickness in micrometres). Shares are of the
/// samples counted, against a reference c: even |h - c| <= 0.1 c, thin h < 0.9 c, thick h > 1.1 c
/// (they add up to 1). c is the target (`target_um`, micrometres; FluxProfile::target) when there is
/// one (> 0), else the mean. With nothing deposited (mean 0) cv is 0 and every cell is thin.
struct Deposition {
  double mean_um = 0.0;
  double cv = 0.0;
  double even_share = 0.0, thin_share = 0.0, thick_share = 0.0;
  double cell = 0.0;       ///< m
  std::size_t cells = 0;   ///< samples counted
};
Deposition depositionStats(const DepositionGrid& grid, const std::vector<char>& mask, double target_um = 0.0);

/// What the coat's picture draws: R's mean thickness (m) over each block of `cells` x `cells`
/// raster cells (the mean of its samples in R; NaN where none is), bx x by blocks from the
/// raster's corner (x0, y0), row by row from the bottom, each `side` = cells x cell wide.
struct CoatBlocks {
  std::size_t cells = 0, bx = 0, by = 0;
  double x0 = 0.0, y0 = 0.0, side = 0.0;
  std::vector<double> mean;
};
/// The coat's metrics and, when asked for, its blocks.
struct Coat {
  Deposition stats;
  CoatBlocks blocks;
};

/// The coat of a path over the reachable region R, on cells of side `cell` (0: depositionCell),
/// 2 x 2 Gauss points per cell over R's bounding box, with its blocks of `block_cells` cells (0:
/// none). A raster past `band_samples` is computed band by band (the same samples, values and
/// sums, in the same order: the same bytes as at once). Throws InputError (source "deposition",
/// field `tool.profile`) when R needs more than kMaxCoatSamples samples, before any work.
Coat coat(const Wall& wall, const ToolParams& tool, const Path& path, const FluxProfile& profile,
          const MotionLimits& limits = {}, const VehicleModel& vehicle = {}, std::size_t block_cells = 0, double cell = 0.0,
          std::size_t band_samples = kCoatBandSamples);

/// coat()'s metrics alone.
Deposition deposition(const Wall& wall, const ToolParams& tool, const Path& path, const FluxProfile& profile,
                      const MotionLimits& limits = {}, const VehicleModel& vehicle = {}, double cell = 0.0);

}  // namespace coverbench
