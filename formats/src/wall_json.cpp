// Wall files: JSON parsing with one-line errors (each wall checked by validateWall), and serialisation.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "coverbench/files.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench {

namespace {

using nlohmann::json;


/// Reads JSON values with the file name and field path at hand for errors.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(source_, field, problem);
  }

  void onlyKeys(const json& obj, const std::string& where, const std::set<std::string>& allowed) const {
    for (auto it = obj.begin(); it != obj.end(); ++it)
      if (!allowed.count(it.key()))
        fail(where.empty() ? it.key() : where + "." + it.key(), "unknown key");
  }

  double number(const json& obj, const std::string& key, const std::string& field) const {
    if (!obj.contains(key)) fail(field, "missing");
    return numberValue(obj.at(key), field);
  }

  double numberValue(const json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "must be a number, got " + std::string(v.type_name()));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(field, "must be finite");
    if (std::fabs(d) > kMaxExtent) fail(field, "absurd value " + shortNumber(d) + " (beyond 10 km)");
    return d;
  }

  double positiveSize(const json& obj, const std::string& key, const std::string& field) const {
    const double d = number(obj, key, field);
    if (d <= 0.0) fail(field, "must be positive, got " + shortNumber(d));
    return d;
  }

  Ring points(const json& v, const std::string& field) const {
    if (!v.is_array()) fail(field, "must be an array of [x, y] points");
    Ring ring;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string f = field + "[" + std::to_string(i) + "]";
      const json& p = v[i];
      if (!p.is_array() || p.size() != 2) fail(f, "must be an [x, y] pair");
      Point pt{numberValue(p[0], f + "[0]"), numberValue(p[1], f + "[1]")};
      if (!ring.empty() && ring.back() == pt) continue;  // repeated vertex: harmless, dropped
      ring.push_back(pt);
    }
    if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();  // explicitly closed
    if (ring.size() < 3) fail(field, "needs at least 3 distinct points, got " + std::to_string(ring.size()));
    if (!ringIsSimple(ring)) fail(field, "polygon is self-intersecting or degenerate");
    if (signedArea(ring) < 0) std::reverse(ring.begin(), ring.end());
    return ring;
  }

  void checkExtent(const Ring& ring, const std::string& field) const {
    const Box b = boundingBox(ring);
    if (b.width() > kMaxExtent || b.height() > kMaxExtent) fail(field, "absurd size (over 10 km)");
  }

 private:
  std::string source_;
};

Obstacle parseObstacle(const Reader& r, const json& v, const std::string& field) {
  if (!v.is_object()) r.fail(field, "must be an object");
  if (!v.contains("type")) r.fail(field + ".type", "missing");
  if (!v["type"].is_string()) r.fail(field + ".type", "must be a string");
  const std::string type = v["type"].get<std::string>();
  Obstacle o;
  if (v.contains("label")) {
    if (!v["label"].is_string()) r.fail(field + ".label", "must be a string");
    o.label = v["label"].get<std::string>();
  }
  if (type == "rect") {
    r.onlyKeys(v, field, {"type", "label", "x", "y", "width", "height"});
    const double x = r.number(v, "x", field + ".x"), y = r.number(v, "y", field + ".y");
    const double w = r.positiveSize(v, "width", field + ".width");
    const double h = r.positiveSize(v, "height", field + ".height");
    o.type = ObstacleType::Rect;
    o.polygon = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
    // As thin as rounding (a height of 1e-15 m): its corners make a polygon the same check as a
    // polygon obstacle's refuses, so its own JSON would not read back.
    if (!ringIsSimple(o.polygon)) r.fail(field, "rectangle is degenerate (its width or height is lost to rounding)");
  } else if (type == "polygon") {
    r.onlyKeys(v, field, {"type", "label", "points"});
    if (!v.contains("points")) r.fail(field + ".points", "missing");
    o.type = ObstacleType::Polygon;
    o.polygon = r.points(v["points"], field + ".points");
    r.checkExtent(o.polygon, field + ".points");
  } else if (type == "circle") {
    r.onlyKeys(v, field, {"type", "label", "x", "y", "radius"});
    o.type = ObstacleType::Circle;
    o.center = {r.number(v, "x", field + ".x"), r.number(v, "y", field + ".y")};
    o.radius = r.positiveSize(v, "radius", field + ".radius");
    if (2 * o.radius > kMaxExtent) r.fail(field + ".radius", "absurd size (over 10 km)");
  } else {
    r.fail(field + ".type", "unknown obstacle type '" + shownBytes(type) + "' (expected rect, polygon or circle)");
  }
  return o;
}

}  // namespace

Wall parseWallJson(const std::string& text, const std::string& source) {
  Reader r(source);
  const json doc = parseJsonStrict(text, source);
  if (!doc.is_object()) r.fail("(document)", "must be a JSON object");
  r.onlyKeys(doc, "", {"name", "width", "height", "boundary", "obstacles", "description", "metadata", "start", "end"});

  Wall wall;
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) r.fail("name", "must be a string");
    wall.name = doc["name"].get<std::string>();
  }
  const bool has_size = doc.contains("width") || doc.contains("height");
  if (doc.contains("boundary")) {
    if (has_size) r.fail("boundary", "give either width/height or boundary, not both");
    wall.boundary = r.points(doc["boundary"], "boundary");
    r.checkExtent(wall.boundary, "boundary");
  } else {
    if (!has_size) r.fail("width", "missing (give width and height, or boundary)");
    const double w = r.positiveSize(doc, "width", "width");
    const double h = r.positiveSize(doc, "height", "height");
    wall.boundary = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  }
  if (doc.contains("obstacles")) {
    const json& obs = doc["obstacles"];
    if (!obs.is_array()) r.fail("obstacles", "must be an array");
    for (std::size_t i = 0; i < obs.size(); ++i)
      wall.obstacles.push_back(parseObstacle(r, obs[i], "obstacles[" + std::to_string(i) + "]"));
  }
  auto point = [&](const char* key) -> std::optional<Point> {
    if (!doc.contains(key)) return std::nullopt;
    const json& p = doc[key];
    if (!p.is_array() || p.size() != 2) r.fail(key, "must be an [x, y] point");
    return Point{r.numberValue(p[0], std::string(key) + "[0]"), r.numberValue(p[1], std::string(key) + "[1]")};
  };
  wall.start = point("start");
  if (doc.contains("end") && doc["end"].is_string()) {
    if (doc["end"].get<std::string>() != "start") r.fail("end", "must be an [x, y] point or \"start\"");
    if (!wall.start) r.fail("end", "is \"start\", but the wall has no start");
    wall.end = wall.start;
  } else {
    wall.end = point("end");
  }
  validateWall(wall, source);
  return wall;
}

Wall loadWallFile(const std::string& path) {
  Wall wall = parseWallJson(readFile(path), path);
  if (wall.name.empty()) {
    std::string stem = path.substr(path.find_last_of('/') + 1);
    wall.name = stem.substr(0, stem.rfind('.'));
    if (!isValidUtf8(wall.name))
      throw InputError(path, "name", "missing, and the file name is not valid UTF-8: give the wall a \"name\"");
  }
  return wall;
}

namespace {

std::string jsonNumber(double v) { return json(v).dump(); }

std::string pointsToJson(const Ring& ring) {
  std::string out = "[";
  for (std::size_t i = 0; i < ring.size(); ++i)
    out += (i ? ", [" : "[") + jsonNumber(ring[i].x) + ", " + jsonNumber(ring[i].y) + "]";
  return out + "]";
}

std::string obstacleToJson(const Obstacle& o) {
  std::string out;
  if (o.type == ObstacleType::Circle)
    out = "{\"type\": \"circle\", \"x\": " + jsonNumber(o.center.x) + ", \"y\": " + jsonNumber(o.center.y) +
          ", \"radius\": " + jsonNumber(o.radius);
  else
    out = "{\"type\": \"polygon\", \"points\": " + pointsToJson(o.polygon);
  if (!o.label.empty()) out += ", \"label\": " + json(o.label).dump();
  return out + "}";
}

}  // namespace

std::string wallToJson(const Wall& wall) {
  // One obstacle per line; numbers in their shortest round-trip form, so equal walls give equal
  // bytes on every machine. Rects are written as their polygons: exact, no arithmetic on corners.
  std::string out = "{\n  \"name\": " + json(wall.name).dump() + ",\n  \"boundary\": " + pointsToJson(wall.boundary) +
                    ",\n  \"obstacles\": [";
  for (std::size_t i = 0; i < wall.obstacles.size(); ++i) out += (i ? ",\n    " : "\n    ") + obstacleToJson(wall.obstacles[i]);
  out += wall.obstacles.empty() ? "]" : "\n  ]";
  // Only when given, so walls without them keep their bytes (and their hashes).
  if (wall.start) out += ",\n  \"start\": [" + jsonNumber(wall.start->x) + ", " + jsonNumber(wall.start->y) + "]";
  if (wall.end) out += ",\n  \"end\": [" + jsonNumber(wall.end->x) + ", " + jsonNumber(wall.end->y) + "]";
  return out + "\n}\n";
}

std::string obstaclesToJson(const std::vector<Obstacle>& obstacles) {
  std::string out = "[";
  for (std::size_t i = 0; i < obstacles.size(); ++i) out += (i ? ", " : "") + obstacleToJson(obstacles[i]);
  return out + "]";
}

std::vector<Obstacle> parseObstaclesJson(const std::string& text, const std::string& source) {
  Reader r(source);
  const json doc = parseJsonStrict(text, source);
  if (!doc.is_array()) r.fail("obstacles", "must be an array");
  std::vector<Obstacle> out;
  for (std::size_t i = 0; i < doc.size(); ++i) out.push_back(parseObstacle(r, doc[i], "obstacles[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace coverbench
