// The importer: picks a reader per source, reads the formats that need no GDAL (polygon text,
// YAML hull/holes, map_server YAML), places and cleans the polygons, and makes walls of them.
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/wall_import.hpp"
#include "gdal_io.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;
using import_detail::RawPolygon;
using import_detail::RawSet;

/// Imported coordinates are rounded to 0.1 mm: a projection's last bits differ between PROJ
/// versions, and the walls must be the same bytes on every machine. (Dividing by the count per
/// metre gives the double nearest the decimal, which prints as that decimal.)
constexpr double kPerMetre = 1e4;

double roundToGrid(double v) { return std::round(v * kPerMetre) / kPerMetre; }

std::string stemOf(const std::string& path) {
  fs::path p(path);
  while (p.has_filename() == false && p.has_parent_path() && p != p.parent_path()) p = p.parent_path();
  return p.stem().string();
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// --- the formats without GDAL -----------------------------------------------------------------

/// `outer_polygon` (or outer_polygon.txt) in a folder: the polygon-text layout.
std::string polygonTextFile(const fs::path& folder, const std::string& name) {
  for (const std::string& candidate : {name, name + ".txt"})
    if (fs::is_regular_file(folder / candidate)) return (folder / candidate).string();
  return "";
}

/// Rings of `x y` lines, separated by blank lines.
std::vector<Ring> readPointRings(const std::string& path) {
  std::istringstream in(readFile(path));
  std::vector<Ring> rings(1);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) {
      if (!rings.back().empty()) rings.emplace_back();
      continue;
    }
    if (line[line.find_first_not_of(" \t")] == '#') continue;
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t') c = ' ';
    std::istringstream fields(line);
    double x = 0, y = 0;
    std::string extra;
    if (!(fields >> x >> y)) throw InputError(path, "line " + std::to_string(number), "must be two numbers, x y");
    if (fields >> extra) throw InputError(path, "line " + std::to_string(number), "has more than two numbers");
    if (!std::isfinite(x) || !std::isfinite(y)) throw InputError(path, "line " + std::to_string(number), "must be finite");
    rings.back().push_back({x, y});
  }
  if (rings.back().empty()) rings.pop_back();
  return rings;
}

RawSet readPolygonTextFolder(const fs::path& folder) {
  const std::string outer_path = polygonTextFile(folder, "outer_polygon");
  if (outer_path.empty()) throw InputError(folder.string(), "outer_polygon", "missing (the polygon-text layout needs it)");
  std::vector<Ring> outer = readPointRings(outer_path);
  if (outer.size() != 1) throw InputError(outer_path, "(rings)", "must hold one ring, found " + std::to_string(outer.size()));
  RawPolygon raw;
  raw.outer = std::move(outer.front());
  const std::string holes_path = polygonTextFile(folder, "holes");
  if (!holes_path.empty()) raw.holes = readPointRings(holes_path);
  raw.name = stemOf(folder.string());
  raw.feature = "outer_polygon";
  return {{std::move(raw)}, ""};
}

/// Reads YAML with the file named in its errors.
YAML::Node loadYaml(const std::string& path) {
  try {
    return YAML::Load(readFile(path));
  } catch (const YAML::Exception& e) {
    throw InputError(path, "line " + std::to_string(e.mark.line + 1), e.msg);
  }
}

double yamlNumber(const YAML::Node& node, const std::string& path, const std::string& field) {
  if (!node || !node.IsScalar()) throw InputError(path, field, node ? "must be a number" : "missing");
  try {
    const double v = node.as<double>();
    if (!std::isfinite(v)) throw InputError(path, field, "must be finite");
    return v;
  } catch (const YAML::Exception&) {
    throw InputError(path, field, "must be a number, got '" + node.Scalar() + "'");
  }
}

Ring yamlRing(const YAML::Node& node, const std::string& path, const std::string& field) {
  if (!node.IsSequence()) throw InputError(path, field, "must be a list of {x, y} points");
  Ring ring;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string f = field + "[" + std::to_string(i) + "]";
    if (!node[i].IsMap()) throw InputError(path, f, "must be a point {x: X, y: Y}");
    ring.push_back({yamlNumber(node[i]["x"], path, f + ".x"), yamlNumber(node[i]["y"], path, f + ".y")});
  }
  return ring;
}

RawSet readHullYaml(const std::string& path, const YAML::Node& doc) {
  for (const auto& kv : doc) {
    const std::string key = kv.first.as<std::string>();
    if (key != "hull" && key != "holes" && key != "name") throw InputError(path, key, "unknown key (expected hull, holes, name)");
  }
  RawPolygon raw;
  raw.outer = yamlRing(doc["hull"], path, "hull");
  if (doc["holes"]) {
    if (!doc["holes"].IsSequence()) throw InputError(path, "holes", "must be a list of rings");
    for (std::size_t i = 0; i < doc["holes"].size(); ++i)
      raw.holes.push_back(yamlRing(doc["holes"][i], path, "holes[" + std::to_string(i) + "]"));
  }
  raw.name = doc["name"] ? doc["name"].as<std::string>() : stemOf(path);
  raw.feature = "hull";
  return {{std::move(raw)}, ""};
}

/// A map_server map: its image's free cells (by the thresholds and `negate`) as polygons, placed
/// by the map's origin (x, y, yaw).
struct MapPlacement {
  double x = 0, y = 0, yaw = 0;
};

RawSet readOccupancyMap(const std::string& path, const YAML::Node& doc, const ImportOptions& options,
                        MapPlacement& placement, std::vector<ImportedSource>& extra_sources) {
  static const std::set<std::string> known = {"image", "resolution", "origin", "occupied_thresh", "free_thresh",
                                               "negate", "mode"};
  for (const auto& kv : doc)
    if (!known.count(kv.first.as<std::string>())) throw InputError(path, kv.first.as<std::string>(), "unknown key of a map_server map");
  if (!doc["image"] || !doc["image"].IsScalar()) throw InputError(path, "image", "missing (the map's PGM or PNG file)");
  const double resolution = yamlNumber(doc["resolution"], path, "resolution");
  if (resolution <= 0) throw InputError(path, "resolution", "must be positive (metres per pixel)");
  const YAML::Node origin = doc["origin"];
  if (!origin || !origin.IsSequence() || origin.size() != 3)
    throw InputError(path, "origin", origin ? "must be [x, y, yaw]" : "missing ([x, y, yaw] of the lower-left pixel)");
  placement = {yamlNumber(origin[0], path, "origin[0]"), yamlNumber(origin[1], path, "origin[1]"),
               yamlNumber(origin[2], path, "origin[2]")};
  const double occupied = doc["occupied_thresh"] ? yamlNumber(doc["occupied_thresh"], path, "occupied_thresh") : 0.65;
  const double free = doc["free_thresh"] ? yamlNumber(doc["free_thresh"], path, "free_thresh") : 0.196;
  if (occupied < 0 || occupied > 1) throw InputError(path, "occupied_thresh", "must be between 0 and 1, got " + shortNumber(occupied));
  if (free < 0 || free > 1) throw InputError(path, "free_thresh", "must be between 0 and 1, got " + shortNumber(free));
  if (free > occupied) throw InputError(path, "free_thresh", "must not exceed occupied_thresh (" + shortNumber(occupied) + ")");
  bool negate = false;
  if (doc["negate"]) {
    const std::string n = doc["negate"].Scalar();
    if (n != "0" && n != "1" && n != "true" && n != "false") throw InputError(path, "negate", "must be 0 or 1, got '" + n + "'");
    negate = n == "1" || n == "true";
  }
  const std::string mode = doc["mode"] ? doc["mode"].Scalar() : "trinary";
  if (mode != "trinary" && mode != "scale" && mode != "raw")
    throw InputError(path, "mode", "must be trinary, scale or raw, got '" + mode + "'");

  const fs::path image_path = fs::path(path).parent_path() / doc["image"].Scalar();
  const import_detail::GreyImage img = import_detail::readGreyImage(image_path.string(), path, "image");
  extra_sources.push_back({image_path.string(), sha256Hex(readFile(image_path.string()))});
  // map_server's rule: p = (255 - v) / 255 (v / 255 when negated) is the occupancy; free below
  // free_thresh. In raw mode the value is the occupancy in percent: free is 0.
  std::vector<std::uint8_t> mask(img.values.size());
  std::size_t free_cells = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const double v = img.values[i];
    const bool is_free = mode == "raw" ? img.values[i] == 0 : (negate ? v / 255.0 : (255.0 - v) / 255.0) < free;
    mask[i] = is_free ? 1 : 0;
    free_cells += is_free;
  }
  if (free_cells == 0) throw InputError(path, "image", "has no free cell (by free_thresh " + shortNumber(free) + ")");
  const double tolerance = options.simplify >= 0 ? options.simplify : resolution / 2;
  std::vector<RawPolygon> components =
      import_detail::polygonizeMask(mask, img.width, img.height, resolution, tolerance, path);
  if (components.empty()) throw InputError(path, "image", "has no free area left after simplification");
  if (!options.all_components) components.resize(1);
  const std::string stem = stemOf(path);
  for (std::size_t i = 0; i < components.size(); ++i) {
    components[i].feature = "component " + std::to_string(i + 1) + " of " + std::to_string(components.size());
    components[i].name = components.size() > 1 ? stem + "_" + std::to_string(i + 1) : stem;
  }
  return {std::move(components), ""};
}

// --- formats by name --------------------------------------------------------------------------

std::string formatOf(const fs::path& p) {
  if (fs::is_directory(p)) return polygonTextFile(p, "outer_polygon").empty() ? "folder" : "polygon-text";
  static const std::map<std::string, std::string> by_extension = {
      {".geojson", "geojson"}, {".json", "geojson"}, {".geojsonl", "geojson"}, {".gml", "gml"},  {".kml", "kml"},
      {".kmz", "kml"},         {".shp", "shapefile"}, {".gpkg", "gpkg"},       {".dxf", "dxf"},  {".wkt", "wkt"},
      {".yaml", "yaml"},       {".yml", "yaml"}};
  const auto it = by_extension.find(lower(p.extension().string()));
  return it == by_extension.end() ? "" : it->second;
}

/// The files a source reads besides itself, for the manifest's hashes (a Shapefile's parts).
std::vector<std::string> companionFiles(const fs::path& p, const std::string& format) {
  std::vector<std::string> out;
  if (format == "shapefile")
    for (const char* ext : {".shx", ".dbf", ".prj", ".cpg"}) {
      fs::path c = p;
      c.replace_extension(ext);
      if (fs::is_regular_file(c)) out.push_back(c.string());
    }
  return out;
}

/// Applies the placement (a map's origin, then the user's transform) to every ring.
void place(RawSet& set, const Eigen::Affine2d& transform) {
  if (transform.matrix().isIdentity()) return;
  for (RawPolygon& poly : set.polygons) {
    auto apply = [&](Ring& ring) {
      for (Point& p : ring) {
        const Eigen::Vector2d q = transform * Eigen::Vector2d(p.x, p.y);
        p = {q.x(), q.y()};
      }
    };
    apply(poly.outer);
    for (Ring& h : poly.holes) apply(h);
  }
}

Eigen::Affine2d userTransform(const std::vector<TransformStep>& steps) {
  Eigen::Affine2d t = Eigen::Affine2d::Identity();
  for (const TransformStep& s : steps) {
    switch (s.kind) {
      case TransformStep::Kind::Translate: t = Eigen::Translation2d(s.x, s.y) * t; break;
      case TransformStep::Kind::Rotate: t = Eigen::Rotation2Dd(s.x * M_PI / 180.0) * t; break;
      case TransformStep::Kind::Scale: t = Eigen::Scaling(s.x, s.y) * t; break;
    }
  }
  return t;
}

/// A ring as the wall model keeps it: rounded, repeated and closing vertices dropped, checked.
Ring cleanRing(const Ring& in, const std::string& source, const std::string& field) {
  Ring ring;
  for (const Point& p : in) {
    const Point q{roundToGrid(p.x), roundToGrid(p.y)};
    if (ring.empty() || !(ring.back() == q)) ring.push_back(q);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) throw InputError(source, field, "has fewer than 3 distinct points");
  if (!ringIsSimple(ring)) throw InputError(source, field, "is self-intersecting or degenerate");
  if (signedArea(ring) < 0) std::reverse(ring.begin(), ring.end());
  return ring;
}

ImportedWall wallOf(const RawPolygon& raw, const std::string& fallback_name, const std::string& crs,
                    const std::string& source, const ImportOptions& options) {
  ImportedWall out;
  out.source = source;
  out.feature = raw.feature;
  out.crs = crs;
  Wall& wall = out.wall;
  wall.name = raw.name.empty() ? fallback_name : raw.name;
  wall.boundary = cleanRing(raw.outer, source, raw.feature + " (outer ring)");
  for (std::size_t i = 0; i < raw.holes.size(); ++i) {
    const std::string field = raw.feature + " (hole " + std::to_string(i + 1) + ")";
    const double hole_area = std::fabs(signedArea(raw.holes[i]));
    if (hole_area < options.min_hole_area) {
      ++out.dropped_holes;
      out.dropped_hole_area += hole_area;
      continue;
    }
    Obstacle o;
    o.type = ObstacleType::Polygon;
    o.polygon = cleanRing(raw.holes[i], source, field);
    o.label = "hole";
    wall.obstacles.push_back(std::move(o));
  }
  Box box = boundingBox(wall.boundary);
  const bool far = std::max({std::fabs(box.min_x), std::fabs(box.max_x), std::fabs(box.min_y), std::fabs(box.max_y)}) > kMaxExtent;
  if (options.origin == "corner" || (options.origin == "auto" && far)) {
    // Whole metres, so the decimals of the coordinates stay as they were.
    out.origin_x = std::floor(box.min_x);
    out.origin_y = std::floor(box.min_y);
    auto shift = [&](Ring& ring) {
      for (Point& p : ring) p = {roundToGrid(p.x - out.origin_x), roundToGrid(p.y - out.origin_y)};
    };
    shift(wall.boundary);
    for (Obstacle& o : wall.obstacles) shift(o.polygon);
    box = boundingBox(wall.boundary);
  }
  if (box.width() > kMaxExtent || box.height() > kMaxExtent)
    throw InputError(source, raw.feature, "is over 10 km across (" + shortNumber(box.width()) + " x " + shortNumber(box.height()) +
                                              " m): is it in metres? (--transform scale=..., --crs)");
  if (std::max({std::fabs(box.min_x), std::fabs(box.max_x), std::fabs(box.min_y), std::fabs(box.max_y)}) > kMaxExtent)
    throw InputError(source, raw.feature, "lies beyond 10 km of the origin: import with --origin corner");
  validateWall(wall, source + ": " + raw.feature);
  return out;
}

/// Imports one file or folder into `result`.
void importSource(const std::string& source, const std::string& forced_format, const ImportOptions& options,
                  ImportResult& result, bool top_level) {
  const fs::path p(source);
  if (!fs::exists(p)) throw InputError(source, "(source)", "does not exist");
  std::string format = forced_format == "auto" ? formatOf(p) : forced_format;
  if (fs::is_directory(p) && format != "polygon-text") {
    if (!top_level && format == "folder") return;  // one level deep: a folder's folders are polygon text or nothing
    // A folder: every file of a known format in it, and its polygon-text folders, in name order.
    std::vector<fs::path> entries;
    for (const auto& e : fs::directory_iterator(p)) entries.push_back(e.path());
    std::sort(entries.begin(), entries.end());
    const std::size_t before = result.walls.size();
    for (const fs::path& e : entries) {
      const std::string f = formatOf(e);
      if (f.empty() || f == "folder") continue;
      const bool matches = forced_format == "auto" || f == forced_format ||
                           (f == "yaml" && (forced_format == "map" || forced_format == "yaml-polygon"));
      if (!matches) continue;
      importSource(e.string(), forced_format == "auto" ? "auto" : forced_format, options, result, false);
    }
    if (result.walls.size() == before)
      throw InputError(source, "(folder)", "holds nothing to import (formats: " +
                                               [] { std::string s; for (const std::string& f : importFormats()) s += (s.empty() ? "" : ", ") + f; return s; }() + ")");
    return;
  }
  if (format.empty())
    throw InputError(source, "--format", "cannot tell the format from the name '" + p.filename().string() + "': give --format");
  if (!fs::is_directory(p)) result.sources.push_back({source, sha256Hex(readFile(source))});

  RawSet set;
  MapPlacement placement;
  bool is_map = false;
  if (format == "polygon-text") {
    if (!fs::is_directory(p)) throw InputError(source, "--format", "polygon-text is a folder holding outer_polygon (and holes)");
    set = readPolygonTextFolder(p);
    for (const char* name : {"outer_polygon", "holes"}) {
      const std::string f = polygonTextFile(p, name);
      if (!f.empty()) result.sources.push_back({f, sha256Hex(readFile(f))});
    }
  } else if (format == "yaml" || format == "yaml-polygon" || format == "map") {
    const YAML::Node doc = loadYaml(source);
    if (!doc.IsMap()) throw InputError(source, "(document)", "must be a YAML mapping (hull/holes, or a map_server map)");
    is_map = format == "map" || (format == "yaml" && doc["image"]);
    if (is_map) set = readOccupancyMap(source, doc, options, placement, result.sources);
    else if (format == "yaml-polygon" || doc["hull"]) set = readHullYaml(source, doc);
    else throw InputError(source, "(document)", "is neither a hull/holes polygon (no 'hull') nor a map_server map (no 'image')");
  } else if (format == "wkt") {
    set = import_detail::readWktText(readFile(source), source, options);
  } else if (format == "dxf") {
    set = import_detail::readDxfFile(source, options);
  } else if (format == "geojson" || format == "gml" || format == "kml" || format == "shapefile" || format == "gpkg") {
    set = import_detail::readVectorFile(source, format, options);
    for (const std::string& c : companionFiles(p, format)) result.sources.push_back({c, sha256Hex(readFile(c))});
  } else {
    throw InputError(source, "--format", "unknown format '" + format + "'");
  }

  Eigen::Affine2d placement_transform = userTransform(options.transform);
  if (is_map) placement_transform = placement_transform * Eigen::Translation2d(placement.x, placement.y) * Eigen::Rotation2Dd(placement.yaw);
  place(set, placement_transform);
  const std::string stem = stemOf(source);
  for (std::size_t i = 0; i < set.polygons.size(); ++i) {
    const std::string fallback = set.polygons.size() > 1 ? stem + "_" + std::to_string(i + 1) : stem;
    result.walls.push_back(wallOf(set.polygons[i], fallback, set.crs, source, options));
  }
}

}  // namespace

const std::vector<std::string>& importFormats() {
  static const std::vector<std::string> formats = {"auto", "geojson", "gml",         "kml",          "shapefile", "gpkg",
                                                   "dxf",  "wkt",     "polygon-text", "yaml-polygon", "map"};
  return formats;
}

std::vector<TransformStep> parseTransform(const std::string& text, const std::string& source, const std::string& field) {
  std::vector<TransformStep> steps;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    const std::size_t eq = word.find('=');
    const std::string op = word.substr(0, eq);
    std::vector<double> values;
    if (eq != std::string::npos) {
      std::string rest = word.substr(eq + 1);
      std::istringstream nums(rest);
      std::string item;
      while (std::getline(nums, item, ',')) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || *end || !std::isfinite(v)) throw InputError(source, field, "'" + word + "': '" + item + "' is not a number");
        values.push_back(v);
      }
    }
    TransformStep s;
    if (op == "translate" && values.size() == 2) {
      s = {TransformStep::Kind::Translate, values[0], values[1]};
    } else if (op == "rotate" && values.size() == 1) {
      s = {TransformStep::Kind::Rotate, values[0], 0.0};
    } else if (op == "scale" && (values.size() == 1 || values.size() == 2)) {
      s = {TransformStep::Kind::Scale, values[0], values.size() == 2 ? values[1] : values[0]};
      if (s.x == 0 || s.y == 0) throw InputError(source, field, "'" + word + "': a scale of 0 flattens the wall");
    } else {
      throw InputError(source, field, "'" + word + "' is not translate=X,Y, rotate=DEGREES or scale=S (or scale=SX,SY)");
    }
    steps.push_back(s);
  }
  return steps;
}

ImportResult importWalls(const std::vector<std::string>& sources, const ImportOptions& options) {
  const auto& formats = importFormats();
  if (std::find(formats.begin(), formats.end(), options.format) == formats.end())
    throw InputError("--format", "(value)", "unknown format '" + options.format + "'");
  if (options.origin != "auto" && options.origin != "keep" && options.origin != "corner")
    throw InputError("--origin", "(value)", "must be auto, keep or corner, got '" + options.origin + "'");
  if (!(options.min_hole_area >= 0)) throw InputError("--min-hole-area", "(value)", "must be 0 or more");
  if (sources.empty()) throw InputError("(sources)", "(value)", "name at least one file or folder to import");
  ImportResult result;
  for (const std::string& s : sources) importSource(s, options.format, options, result, true);
  return result;
}

std::string importRecordJson(const ImportResult& result, const ImportOptions& options) {
  using nlohmann::json;
  auto num = [](double v) { return json(v).dump(); };
  std::string transform;
  for (const TransformStep& s : options.transform) {
    const char* op = s.kind == TransformStep::Kind::Translate ? "translate" : s.kind == TransformStep::Kind::Rotate ? "rotate" : "scale";
    transform += std::string(transform.empty() ? "" : " ") + op + "=" + num(s.x) +
                 (s.kind == TransformStep::Kind::Rotate ? "" : "," + num(s.y));
  }
  std::string layers;
  for (const std::string& l : options.dxf_obstacle_layers) layers += (layers.empty() ? "" : ", ") + json(l).dump();
  std::string out = "{\n    \"options\": {\"format\": " + json(options.format).dump() + ", \"crs\": " + json(options.crs).dump() +
                    ", \"source_crs\": " + json(options.source_crs).dump() + ", \"name_field\": " + json(options.name_field).dump() +
                    ", \"split_multipolygons\": " + (options.split_multipolygons ? "true" : "false") +
                    ", \"boundary_layer\": " + json(options.dxf_boundary_layer).dump() + ", \"obstacle_layers\": [" + layers +
                    "], \"all_components\": " + (options.all_components ? "true" : "false") +
                    ", \"min_hole_area\": " + num(options.min_hole_area) + ", \"simplify\": " + num(options.simplify) +
                    ", \"transform\": " + json(transform).dump() + ", \"origin\": " + json(options.origin).dump() +
                    "},\n    \"sources\": [";
  for (std::size_t i = 0; i < result.sources.size(); ++i)
    out += std::string(i ? ",\n      " : "\n      ") + "{\"file\": " + json(result.sources[i].path).dump() + ", \"sha256\": \"" +
           result.sources[i].sha256 + "\"}";
  out += "\n    ],\n    \"walls\": [";
  for (std::size_t i = 0; i < result.walls.size(); ++i) {
    const ImportedWall& w = result.walls[i];
    out += std::string(i ? ",\n      " : "\n      ") + "{\"name\": " + json(w.wall.name).dump() + ", \"source\": " +
           json(w.source).dump() + ", \"feature\": " + json(w.feature).dump() + ", \"crs\": " + json(w.crs).dump() +
           ", \"origin\": [" + num(w.origin_x) + ", " + num(w.origin_y) + "], \"dropped_holes\": " +
           std::to_string(w.dropped_holes) + ", \"dropped_hole_area\": " + num(w.dropped_hole_area) + "}";
  }
  return out + "\n    ]\n  }";
}

}  // namespace coverbench
