#pragma once
/// The metrics engine: pure functions of (wall, tool, path). No I/O, no hidden state. Definitions
/// are normative and written down in docs/metrics.md.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/deposition.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/motion.hpp"
#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

class ClearanceField;  // coverbench/clearance.hpp

/// One violating segment, described for messages: where it is, what it breaks and by how much.
struct Violation {
  std::size_t segment = 0;  ///< segment i joins waypoints i and i + 1
  Point from, to;           ///< its waypoints (an arc's ends)
  /// The tool disk leaves the wall (`lifted`: a gantry's lifted move leaves the wall's bounding box).
  bool outside_boundary = false;
  bool lifted = false;
  bool too_close = false;     ///< the disk comes closer than the clearance to an obstacle
  bool not_drivable = false;  ///< a car cannot drive it (Validity::not_drivable)
  /// The disk's gap (m) to the wall's edge, negative outside it (NaN for a lifted move or a
  /// segment only a car cannot drive).
  double boundary_gap = NAN;
  /// The disk's gap (m) to the nearest obstacle, negative where it overlaps one (NaN where not measured).
  double clearance = NAN;
  /// The nearest obstacle: its index in Wall::obstacles (-1: none measured) and its label ("" if none).
  long obstacle = -1;
  std::string obstacle_label;
};
/// How many violating segments Validity::described details (the first ones, by index).
inline constexpr std::size_t kDescribedViolations = 5;

/// Validity of a path: every segment the tool is on the wall for (every segment for a holonomic
/// vehicle; the tool-on ones for a gantry) must keep the whole tool disk inside the wall and at
/// least `clearance` away from every obstacle. A gantry's tool-off (lifted) segments must keep the
/// disk inside the wall's bounding box.
struct Validity {
  bool valid = true;
  std::size_t violations = 0;        ///< segments breaking a rule (either reason below)
  /// Segments where the tool disk leaves the wall (a gantry's lifted segments: its bounding box).
  std::size_t outside_boundary = 0;
  std::size_t too_close = 0;         ///< segments where the disk comes closer than c to an obstacle
  /// Smallest gap (m) between the tool disk and any obstacle over the segments checked against
  /// the obstacles (all but a gantry's lifted ones); negative when the disk overlaps an obstacle
  /// (down to -r when the centre touches it). Infinite when the wall has no obstacles.
  double min_clearance = INFINITY;
  /// Smallest gap (m) between the tool disk and the wall boundary over the same segments;
  /// negative when it leaves.
  double min_boundary_gap = INFINITY;
  /// Indices of the violating segments (segment i joins waypoints i and i+1), the first
  /// kMaxListedViolations of them: for pictures that mark where a path goes wrong.
  std::vector<std::size_t> violating;
  /// A car's segments it cannot drive (counted in `violations`): an arc tighter than its turn
  /// radius, or a segment starting with another heading than the one before it ended with (for a
  /// reversing car, other than the opposite one at a cusp). Not one of the flattened metrics.
  std::size_t not_drivable = 0;
  /// Depot legs accepted (0-2: from the start, to the end; path.hpp: depot legs): checked by their
  /// own rule and left out of min_clearance and min_boundary_gap.
  std::size_t depot_legs = 0;
  double depot_length = 0.0;  ///< their length (m), part of the path's length

  /// The first kDescribedViolations violating segments (by index), each with what it breaks.
  std::vector<Violation> described;
};
inline constexpr std::size_t kMaxListedViolations = 10000;

/// Whether the straight segment [a, b] may be part of a depot leg (path.hpp: depot legs): not a
/// point, its centre line inside the wall or on its edge (within kValidityTolerance) and with no
/// point in common with any obstacle. The runner builds depot legs with it.
bool depotSegment(const ClearanceField& field, Point a, Point b);

/// An invalid path's message: "N segments violate the wall or the clearance: segment 12 (1.2, 0.4)->
/// (1.8, 0.4) enters obstacle "window" (clearance -0.05 m < 0.02 m); ...; M more" (the described
/// segments; docs/metrics.md). `required_clearance` is the tool's clearance c. "" for a valid path.
std::string describeViolations(const Validity& validity, double required_clearance);
/// The exact judge checks an arc segment as chords whose sagitta is at most this (m), each with the
/// tool grown by a certified bound of it: an arc closer than this to its limit may be refused
/// (planners keep kPlanningMargin to spare). The fast engine measures an arc's distances in closed
/// form (ClearanceField::measureArc); kMaxArcChords bounds the judge's work with this.
inline constexpr double kArcCheckSagitta = 1e-7;
/// The path with every arc replaced by chords whose points lie on it and whose sagitta is at most
/// `sagitta` (m); a path without arcs is returned as it is. Coverage and passes measure arcs on
/// these chords with kMetricArcTolerance.
Path chordalPath(const Path& path, double sagitta);
/// The path as the coverage polygons (an invalid path's coverage, coverageRegions), the scanline
/// pass counts and the pictures' regions measure it: the path itself when it has no arcs, else
/// chordalPath(path, kMetricArcTolerance), made in `storage`. Every function of this header that
/// takes a path measures this one, so none reads an arc as its chord, except passes() and
/// passLevelAreas(), which take arcs as arcs (exact, no chords).
const Path& measuredPath(const Path& path, Path& storage);
/// How many chords of at most `sagitta` (m) chordalPath cuts an arc into.
double arcChords(const ArcGeometry& arc, double sagitta);

/// Checks every segment of the path with closed-form distances in doubles (no sampling), forgiving
/// shortfalls up to kValidityTolerance (1e-9 m). The exact judge (judge/) has no tolerance.
/// A single waypoint is checked as a point. Arcs: in closed form (ClearanceField::measureArc); a car's path also has to
/// be drivable (Validity::not_drivable).
Validity checkValidity(const Wall& wall, const ToolParams& tool, const Path& path,
                       const VehicleModel& vehicle = {});

/// Path lengths in metres.
struct Lengths {
  double total = 0.0;
  double cover = 0.0;    ///< tool on
  double transit = 0.0;  ///< tool off
};
Lengths pathLengths(const Path& path);

/// Arc tolerance of every polygon the coverage metrics build (circles, round offsets, capsule
/// ends): chords lie within 50 micrometres of the true arcs (the spec asks for under 0.1 mm).
inline constexpr double kMetricArcTolerance = 5e-5;

/// Areas (m^2) and coverage ratios, computed on polygons (see docs/metrics.md).
struct Coverage {
  double reachable_area = 0.0;   ///< |R|, R = F dilated by r
  double paintable_area = 0.0;   ///< |P|, P = wall minus obstacles
  double swept_area = 0.0;       ///< |S|, the union of tool-on capsules
  double coverage_reachable = 0.0;  ///< |S and R| / |R|
  double coverage_wall = 0.0;       ///< |S and P| / |P|
};
/// The polygons behind the coverage figures (for pictures and tests).
struct CoverageRegions {
  Region reachable;  ///< R
  Region paintable;  ///< P
  Region swept;      ///< S
};
CoverageRegions coverageRegions(const Wall& wall, const ToolParams& tool, const Path& path);
/// R alone, its arcs as chords within `arc_tolerance` (a picture asks for a fraction of its pixel).
Region reachableRegion(const Wall& wall, const ToolParams& tool, double arc_tolerance = kMetricArcTolerance);
/// Coverage from the polygons: |S and R| and |S and P| by Clipper, S with chords (kMetricArcTolerance).
Coverage coverage(const CoverageRegions& regions);
/// |R| and |P| (m^2) as a valid path's coverage takes them, and how. Every obstacle that is convex,
/// at least 2 r + c inside the wall and at least 2 (r + c) from every other obstacle takes away
/// exactly itself dilated by c from R and itself from P (closed forms, exact up to rounding); the
/// wall with the other obstacles is opened by the tool disk in closed form if it is strictly
/// convex and no obstacle is left, and as polygons (chords within kMetricArcTolerance) otherwise.
struct RegionAreas {
  double reachable = 0.0;  ///< |R|
  double paintable = 0.0;  ///< |P|
  std::size_t obstacles_in_closed_form = 0;  ///< obstacles taken away in closed form
  bool wall_in_closed_form = false;          ///< the wall (and what is left on it) in closed form
};
RegionAreas regionAreas(const Wall& wall, const ToolParams& tool);
/// Coverage of a path whose validity and exact swept area |S| (passLevelAreas) are known: for a valid
/// path S lies in R and in P, so both numerators are |S|, with |R| and |P| from regionAreas(); an
/// invalid path is scored from the polygons.
Coverage coverage(const Wall& wall, const ToolParams& tool, const Path& path, const Validity& validity,
                  double swept_area);
/// The same, checking validity and measuring |S| itself.
Coverage coverage(const Wall& wall, const ToolParams& tool, const Path& path);

/// The fast engine's error against the exact judge (judge/), measured on the default experiment's
/// walls, every planner and tool widths 0.05, 0.1 and 0.2 m (docs/metrics.md, "The fast engine's
/// error bounds"; tests/judge/judge_test.cpp keeps it): coverage ratios within kFastErrorTimesToolWidth / s
/// of the judge's certified interval, and areas within kFastErrorTimesToolWidth / s of it relative
/// to the area. Set when |S| had 50 um chords (an error growing as 1 / s, measured up to
/// 8.5e-7 m / s); with |S| exact, what is left are R's and P's chords (measured: coverage within
/// 2.3e-8, areas within 7.7e-7 of their size, at s = 0.05-0.2 m).
inline constexpr double kFastErrorTimesToolWidth = 1.5e-6;  ///< m
inline double fastErrorBound(double tool_width) { return kFastErrorTimesToolWidth / tool_width; }

/// Pass counts over the swept area, exact: the areas of the sets {q : passes(q) >= k} are line
/// integrals over the boundary of the arrangement of capsules and continuation disks (straight
/// pieces and circular arcs in closed form; an arc segment is one shape, not chords;
/// docs/metrics.md, "Passes and overlap").
struct Passes {
  double overlap = 0.0;           ///< |{q in S : passes(q) >= 2}| / |S|
  std::vector<double> histogram;  ///< histogram[k-1] = |{passes == k}| / |S|; last bin is ">= k"
  double swept_area = 0.0;        ///< |S| = |{passes >= 1}| (m^2), exact up to rounding
};
Passes passes(const Path& path, double radius, std::size_t bins = 4);
/// passes() of the tool's shape: a disk's as above; a line's from its swept shapes as polygons
/// (rectangles, and sectors as chords within line_tool's 1 um; docs/metrics.md#tool-shapes).
Passes passes(const Path& path, const ToolParams& tool, std::size_t bins = 4);
/// The areas |{q : passes(q) >= k}| for k = 1 .. levels (m^2). Waypoints closer than 1 nm are
/// taken as one, and sides running along each other within 1 nm as touching.
std::vector<double> passLevelAreas(const Path& path, double radius, std::size_t levels);

/// The same pass counts on horizontal scanlines `resolution` apart (exact along each line, the
/// midpoint rule across lines): the method behind the overlap pictures, whose strips are one
/// scanline high. Its error is of the order of the spacing; the metrics use passes().
Passes passesOnScanlines(const Path& path, double radius, double resolution, std::size_t bins = 4);
/// The points passed over `min_passes` times or more, as strips one scanline high (for pictures).
Region passRegion(const Path& path, double radius, double resolution, int min_passes);
/// passRegion() of the tool's shape: a line's is exact up to its sectors' chords (no scanlines).
Region passRegion(const Path& path, const ToolParams& tool, double resolution, int min_passes);
/// The points passed over twice or more: passRegion(path, radius, resolution, 2).
Region overlapRegion(const Path& path, double radius, double resolution);
/// Number of passes over one point (the definition, point by point).
int passCount(const Path& path, double radius, Point q);


/// Every metric of one path.
struct PathMetrics {
  Validity validity;
  Lengths lengths;
  Coverage coverage;
  Passes passes;
  Motion motion;
  std::size_t waypoints = 0;
  double length_ratio = 0.0;  ///< length_total / (|R| / s)
  /// The coat's thickness (deposition.hpp): only when the tool has a flux profile and R's raster
  /// fits kMaxCoatSamples.
  std::optional<Deposition> deposition;
  /// Why a tool with a flux profile has no coat metrics: R would need a raster past
  /// kMaxCoatSamples (deposition()'s message, "deposition: tool.profile: needs a coat raster
  /// of ..."). Empty otherwise. flatten() then lists the coat's metrics with no value (NaN).
  std::string coat_not_scored;
};
/// What a run's reason adds when the coat was not scored: "the coat's metrics are not scored
/// (the others are): deposition: tool.profile: needs a coat raster of ...", else "".
std::string coatNotScoredNote(const PathMetrics& m);
/// `reason` with `note` appended ("; " between them); `reason` itself when `note` is empty.
std::string withNote(const std::string& reason, const std::string& note);
/// Scores a path (the coat's thickness too when the tool has a flux profile, unless its raster is
/// too large: coat_not_scored). Throws InputError (field `waypoints`) for a path beyond the
/// scoring limits below, before any work. With `coat` and a tool whose coat was scored, the coat
/// the metrics were computed in is handed out there, with its blocks of `block_cells` cells (for
/// its picture: coatPicture and coatBlockCells in svg.hpp); it is left as it is otherwise.
PathMetrics computeMetrics(const Wall& wall, const ToolParams& tool, const Path& path,
                           const VehicleModel& vehicle = {}, const MotionLimits& limits = {}, Coat* coat = nullptr,
                           std::size_t block_cells = 0);

/// Scoring limits. Exact scoring grows with the path's waypoints (memory: a spanning-tree path of
/// 10^6 waypoints took 18 s and 0.46 GB here) and, much faster, with how often the path crosses
/// itself (3000 random waypoints: 2.6 s), so `coverbench metrics` also has a time limit; longer
/// paths are refused. A coordinate beyond kMaxPathCoordinate cannot be on any wall (walls lie
/// within 10 km of the origin) and would overflow the exact area grid.
inline constexpr std::size_t kMaxScoredWaypoints = 2000000;
inline constexpr double kMaxPathCoordinate = 100000.0;  ///< m
/// The exact judge checks an arc as chords of kArcCheckSagitta, about
/// |phi| sqrt(R / 8e-7) of them: work that grows with the arc's radius, not with the path's
/// waypoints. An arc is scored when it needs at most this many: a half circle of about 800 m
/// radius (a car's turn radius is at most kMaxTurnRadius, 100 m: 35 000 chords at most). An arc of
/// 140 km radius (1.3 million chords) took the fast engine 9-15 s.
inline constexpr std::size_t kMaxArcChords = 100000;
/// Throws InputError(source, field, problem) if `path` is beyond the scoring limits (waypoints,
/// coordinates, an arc's chords), or its coordinates are not finite.
void checkScorable(const Path& path, const std::string& source);
/// Throws InputError if a line or rectangle tool's path cannot be scored yet: a car's (field
/// tool.shape) or one with an arc (field bulge[i]). Both engines score their straight moves only.
void checkLineScorable(const Path& path, const ToolParams& tool, const VehicleModel& vehicle, const std::string& source);

/// One named metric value, in the order metrics are written (plan files, tables).
struct NamedMetric {
  std::string name;
  double value;
};
std::vector<NamedMetric> flatten(const PathMetrics& m);

}  // namespace coverbench
