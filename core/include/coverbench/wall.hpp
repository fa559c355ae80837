#pragma once
/// The wall model: a boundary polygon and obstacles (windows, doors, sockets, pipes), and the
/// wall-file parser with its one-line errors.

#include <stdexcept>
#include <string>
#include <vector>

#include "coverbench/geometry.hpp"

namespace coverbench {

/// Bad input from a user: carries the file (or flag), the field and the problem, and formats them
/// as one line: `FILE: FIELD: PROBLEM`.
class InputError : public std::runtime_error {
 public:
  InputError(std::string source, std::string field, std::string problem);
  const std::string& source() const { return source_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string source_, field_, problem_;
};

/// A number as messages show it: six significant digits, or as many more as read back as it
/// ("0.1", "1e-09", "3600.0000001").
std::string shortNumber(double v);

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
};

/// The largest coordinate extent accepted for walls and obstacles (10 km).
inline constexpr double kMaxExtent = 10000.0;

/// Parses a wall from JSON text. `source` names the file in error messages.
/// Throws InputError for every malformed or meaningless input (see docs/file_formats.md).
Wall parseWallJson(const std::string& text, const std::string& source);
/// Reads and parses a wall file.
Wall loadWallFile(const std::string& path);
/// Serialises a wall to JSON text (boundary always written as a polygon).
std::string wallToJson(const Wall& wall);
/// Obstacles as a wall file's "obstacles" array, on one line (rects as polygons, as wallToJson).
std::string obstaclesToJson(const std::vector<Obstacle>& obstacles);
/// Parses such an array (every obstacle checked as the wall parser checks it; not against a wall).
std::vector<Obstacle> parseObstaclesJson(const std::string& text, const std::string& source);

/// Checks a parsed wall for geometric sense (simple polygons, obstacles inside, something left
/// to cover). Called by the parser; exposed for generators and tests.
void validateWall(const Wall& wall, const std::string& source);

}  // namespace coverbench
