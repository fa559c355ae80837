#pragma once
/// The metrics engine: pure functions of (wall, tool, path). No I/O, no hidden state. Definitions
/// are normative and written down in docs/metrics.md.

#include <cstddef>
#include <map>
#include <string>

#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// Exact validity of a path: every segment (tool on or off) must keep the whole tool disk inside
/// the wall and at least `clearance` away from every obstacle.
struct Validity {
  bool valid = true;
  std::size_t violations = 0;        ///< segments whose centre leaves F (either reason below)
  std::size_t outside_boundary = 0;  ///< segments where the tool disk leaves the wall
  std::size_t too_close = 0;         ///< segments where the disk comes closer than c to an obstacle
  /// Smallest gap (m) between the tool disk and any obstacle over the whole path; negative when
  /// the disk overlaps an obstacle (down to -r when the centre touches it). Infinite when the
  /// wall has no obstacles.
  double min_clearance = INFINITY;
  /// Smallest gap (m) between the tool disk and the wall boundary; negative when it leaves.
  double min_boundary_gap = INFINITY;
};

/// Checks every segment of the path exactly (closed-form distances, no sampling).
/// A single waypoint is checked as a point.
Validity checkValidity(const Wall& wall, const ToolParams& tool, const Path& path);

/// Path lengths in metres.
struct Lengths {
  double total = 0.0;
  double cover = 0.0;    ///< tool on
  double transit = 0.0;  ///< tool off
};
Lengths pathLengths(const Path& path);

}  // namespace coverbench
