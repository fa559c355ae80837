#pragma once
/// The wall model: a boundary polygon and obstacles (windows, doors, sockets, pipes), and the check
/// of a wall's geometric sense (bad input is an InputError, base/input_error.hpp). Wall files are read in formats/
/// (coverbench/wall_file.hpp).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/input_error.hpp"

namespace coverbench {

enum class ObstacleType { Rect, Polygon, Circle };

/// One obstacle. Rects and polygons are stored as a counter-clockwise `polygon`; circles keep
/// their exact `center` and `radius` (and have an empty polygon).
struct Obstacle {
  ObstacleType type = ObstacleType::Rect;
  Ring polygon;
  Point center;
  double radius = 0.0;
  std::string label;
};

/// A wall: units are metres, origin at the lower-left corner. `boundary` is counter-clockwise.
struct Wall {
  std::string name;
  Ring boundary;
  std::vector<Obstacle> obstacles;
  /// Where every path must begin and end (a dock, a charger, a field's gate), when given: planners
  /// reach the start and leave for the end with the tool off. Each must lie inside the boundary
  /// (or on it). One outside F is joined to F by a depot leg (path.hpp: depot legs), and must then
  /// lie off every obstacle.
  std::optional<Point> start, end;
};

/// The largest coordinate extent accepted for walls and obstacles (10 km).
inline constexpr double kMaxExtent = 10000.0;

/// Checks a parsed wall for geometric sense (simple polygons, obstacles inside, something left
/// to cover). Called by the parser; exposed for generators and tests.
void validateWall(const Wall& wall, const std::string& source);

}  // namespace coverbench
