#pragma once
/// The exact judge: an independent second opinion on a path, built on CGAL's exact kernel.
///
/// It shares no code with the planners or with the fast metrics engine: it reads only the wall,
/// the tool and the path (plain value types) and builds F, R, P and S itself. Every double of the
/// wall and the path is taken as the exact rational it is.
///
/// - Validity is decided exactly: squared distances between segments, points and circles are
///   compared with (r + c)^2 and r^2 in exact rational arithmetic, with no tolerance at all.
/// - Areas are certified intervals: every disk (tool, clearance, round obstacles) is replaced by
///   an inscribed and a circumscribed polygon with rational vertices, the regions are built from
///   them with exact Boolean operations, and the true area of every region lies in
///   [area with inscribed polygons, area with circumscribed ones]. The width of the interval is
///   the price of the arcs; it shrinks as 1 / arc_vertices^2.
///
/// - A line tool (ToolParams::shape, docs/metrics.md#tool-shapes): its rectangles and turns are
///   judged through rational polygons that contain them (judge/src/exact_line.hpp), as arcs are
///   through their chords; its R is the wall minus the obstacles grown by c.
///
/// This header does not include CGAL: CGAL stays inside the judge's own translation units.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench::judge {

/// A certified enclosure of a real number: lower <= true value <= upper.
struct Interval {
  double lower = 0.0;
  double upper = 0.0;
  double width() const { return upper - lower; }
  bool contains(double v) const { return lower <= v && v <= upper; }
  /// v minus the interval's nearest end: negative below it, positive above it, 0 inside it.
  double offset(double v) const { return v < lower ? v - lower : (v > upper ? v - upper : 0.0); }
  /// The distance from v to the interval (0 when v lies inside it).
  double distanceTo(double v) const { return std::fabs(offset(v)); }
};

/// Exact validity of every segment (segment i joins waypoints i and i + 1; a one-waypoint path is
/// checked as a point). Same definitions as the fast engine (docs/metrics.md), but with exact
/// arithmetic and no tolerance: a shortfall of 1e-15 m is a violation here. A gantry's tool-off
/// segments are lifted: the tool disk at both ends must lie in the wall's bounding box. Arcs (a
/// car's path): kArcChordSagitta; a car's path must also be drivable (not_drivable).
struct ExactValidity {
  bool valid = true;
  std::size_t violations = 0;        ///< segments that break either rule below
  std::size_t outside_boundary = 0;  ///< the tool disk leaves the wall (or the centre is outside it; lifted: the box)
  std::size_t too_close = 0;         ///< the tool disk comes closer than c to an obstacle
  std::vector<std::size_t> violating;  ///< the first kMaxListed violating segments
  /// A car's segments it cannot drive (in `violations`): an arc of radius below the turn radius,
  /// or a heading that jumps at the segment's start (exact comparisons; docs/vehicles.md).
  std::size_t not_drivable = 0;
  /// Depot legs accepted by their own rule (0-2; path.hpp: depot legs), decided exactly, and their
  /// length (m, in doubles: a figure, not a verdict).
  std::size_t depot_legs = 0;
  double depot_length = 0.0;
  static constexpr std::size_t kMaxListed = 10000;
};
/// An arc segment is judged as chords whose ends lie exactly on its circle; each is checked with
/// the tool disk grown by a certified bound of how far the arc strays from its chords, so a valid
/// verdict holds for the arc itself. Chords about 1e-3 m from the arc are tried first, then 1e-5 m,
/// then chords about this far (m): a try that passes settles it; when the last fails, the arc is
/// invalid.
inline constexpr double kArcChordSagitta = 1e-7;
/// For areas, arcs are swept as coarser chords (about this far from the arc, m; exact Boolean
/// operations cost by the polygon), with the disk shrunk and grown by the certified stray: the
/// swept-area interval stays certified and widens by about the stray times the arc's length.
inline constexpr double kArcCoverageSagitta = 1e-4;
ExactValidity judgeValidity(const Wall& wall, const ToolParams& tool, const Path& path,
                            const VehicleModel& vehicle = {});

struct CoverageOptions {
  /// Vertices of the polygons that stand in for each disk (inscribed and circumscribed); a
  /// multiple of 8, at least 8. Gap between them: about r (pi / n)^2.
  int arc_vertices = 128;
};

/// Certified areas (m^2) and coverage ratios; the regions are those of docs/metrics.md.
struct ExactCoverage {
  Interval reachable_area;      ///< |R|, R = F dilated by r, F = erode(B, r) minus dilate(O, r + c)
  Interval paintable_area;      ///< |P|, P = B minus O
  Interval swept_area;          ///< |S|, the union of the tool-on capsules
  Interval coverage_reachable;  ///< |S and R| / |R|
  Interval coverage_wall;       ///< |S and P| / |P|
  int arc_vertices = 0;
};
ExactCoverage judgeCoverage(const Wall& wall, const ToolParams& tool, const Path& path,
                            const CoverageOptions& options = {});

/// Everything the exact judge decides about one path.
struct Judgement {
  ExactValidity validity;
  ExactCoverage coverage;
  double seconds_validity = 0.0;  ///< wall-clock time of each part (measured, not a result)
  double seconds_coverage = 0.0;
};
Judgement judgePath(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle = {},
                    const CoverageOptions& options = {});

}  // namespace coverbench::judge
