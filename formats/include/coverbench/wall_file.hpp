#pragma once
/// Wall files (docs/file_formats.md): the JSON parser with its one-line errors, and serialisation.

#include <string>
#include <vector>

#include "coverbench/wall.hpp"

namespace coverbench {

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

}  // namespace coverbench
