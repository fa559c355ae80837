#pragma once
/// The bounds CoverBench puts on its inputs, in one place, with why. Inputs beyond them are
/// refused with a one-line InputError before any work, instead of running out of memory, time
/// or numeric range (docs/file_formats.md lists them for users).
#include <cstddef>
#include <string>

#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// Tool width s: a tool under 1 mm is no painting, plastering or mowing tool, and the exact
/// area grid (1 um) could not resolve its swath; 10 m bounds a wall-sized tool.
inline constexpr double kMinToolWidth = 0.001;
inline constexpr double kMaxToolWidth = 10.0;
/// Clearance c, metres.
inline constexpr double kMaxClearance = 10.0;
/// Tool-sized cells in a wall's bounding box (area / s^2): grid planners allocate per cell and
/// make about a waypoint per cell. Measured here: spanning-tree on 10^7 cells took 9 s and 1.2 GB
/// (a 10^7-waypoint path, beyond the scoring limit); on 10^8 cells, 84 s and 9.9 GB. So 10^7.
/// The limit of the grid planners (spanning-tree, adaptive-resolution): they end with
/// `invalid_input` and gridCellsProblem's reason past it; the other planners need no grid.
inline constexpr double kMaxGridCells = 1e7;
/// Tool-sized cells of any problem (every planner): 10^9 is a 3 km field at a 10 cm tool, or a
/// 200 m one at 6 mm. Past it no path could be scored (a row per tool width, millions of rows).
inline constexpr double kMaxToolCells = 1e9;
/// A planner's time budget, seconds (one day).
inline constexpr double kMaxTimeLimitSeconds = 86400.0;
/// Experiments with more runs than this need an explicit confirmation (`--yes` or
/// `allow_large: true`): they take hours to days.
inline constexpr std::size_t kLargeExperimentRuns = 100000;

/// Tool width s in [kMinToolWidth, kMaxToolWidth] m (a rectangle's depth too; no other shape has one) and
/// clearance in [0, kMaxClearance] m, finite.
/// Throws InputError naming `source` and the field.
void validateTool(const ToolParams& tool, const std::string& source);

/// validateTool, and the wall's bounding box holds at most kMaxToolCells tool-sized cells.
/// `source` names where the tool came from, `wall_source` the wall.
void validateToolForWall(const ToolParams& tool, const Wall& wall, const std::string& source);
/// Why a grid planner refuses the problem (its bounding box holds more than kMaxGridCells
/// tool-sized cells), or "" when it fits.
std::string gridCellsProblem(const ToolParams& tool, const Wall& wall);

/// A gantry's lift and lower times, seconds: an hour bounds any tool change.
inline constexpr double kMaxLiftTime = 3600.0;
/// A car's smallest turn radius, metres: below it the car's smoothing works at the scale of its
/// own rounding (at 1e-8 m every planner's smoothed path failed its own heading check, at 1 mm
/// spiral's on a random wall did; from 2 mm on all passed) and the car turns all but on the spot:
/// the holonomic vehicle is that car. 1 cm keeps a factor of five from the last failure.
inline constexpr double kMinTurnRadius = 0.01;
/// A car's largest turn radius, metres: a harvester turns on about 15 m; arcs are checked as
/// chords of 1e-7 m, and a half circle of 100 m needs 35 000 of them (metrics' kMaxArcChords).
inline constexpr double kMaxTurnRadius = 100.0;
/// lift_s and lower_s in [0, kMaxLiftTime] s, finite; a car's turn radius in
/// [kMinTurnRadius, kMaxTurnRadius] m. Throws InputError(source, `field`.lift_s, ...).
void validateVehicle(const VehicleModel& vehicle, const std::string& source, const std::string& field);

/// A sampling transit planner's iterations per query: 10^7 took minutes per query here.
inline constexpr long long kMaxTransitIterations = 10000000;

/// A time limit in (0, kMaxTimeLimitSeconds] s. Throws InputError(source, field, ...).
void validateTimeLimit(double seconds, const std::string& source, const std::string& field);

}  // namespace coverbench
