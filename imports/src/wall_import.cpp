// The importer: picks a reader per source, reads the formats that need no GDAL (polygon text,
// YAML hull/holes, map_server YAML), places and cleans the polygons, and makes walls of them.
// What needs GDAL is in the plug-in libcoverbench_gdal.so (gdal_plugin.hpp), opened on first use.
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/wall_import.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/plugin.hpp"
#include "gdal_plugin.hpp"
#include "map_rooms.hpp"

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

void hostInputError(const std::string& source, const std::string& field, const std::string& problem) {
  throw InputError(source, field, problem);
}
bool hostPointInRing(Point p, const Ring& ring) { return pointInRing(p, ring); }
std::string hostShortNumber(double v) { return shortNumber(v); }

}  // namespace

void import_detail::requireUtf8Path(const std::string& path, const std::string& source, const std::string& field) {
  // As an error shows a path: valid UTF-8 on one line (each control character a '?').
  auto shown = [](const std::string& text) {
    std::string out = toValidUtf8(text);
    for (char& c : out)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return out;
  };
  const std::string named = path == source ? "" : "'" + shown(path) + "' ";
  if (!isValidUtf8(path))
    throw InputError(shown(source), field, named + "is not a valid UTF-8 path (the manifest records each file's path as text): rename it");
  for (unsigned char c : path)
    if (c < 0x20 || c == 0x7f)
      throw InputError(shown(source), field, named + "holds a control character (a line break, a tab): rename it");
}

/// The GDAL plug-in (gdal_plugin.hpp), opened by the first import: no other command loads GDAL.
const import_detail::GdalApi& import_detail::gdal() {
  static const import_detail::GdalHost host{&hostInputError, &hostPointInRing, &hostShortNumber};
  static const PluginSpec spec{"GDAL", "this format cannot be imported", "libcoverbench_gdal.so", "COVERBENCH_GDAL_PLUGIN",
                               COVERBENCH_GDAL_PLUGIN_PATH, import_detail::kGdalPluginEntry, import_detail::kGdalPluginAbi};
  static const auto* api = static_cast<const import_detail::GdalApi*>(openPlugin(spec, &host));
  return *api;
}

namespace {

using import_detail::gdal;

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

/// A text file's bytes; a NUL byte (a binary file, or one cut short by it) is refused.
std::string readText(const std::string& path) {
  std::string text = readFile(path);
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw InputError(path, "(text)", "contains a NUL byte at offset " + std::to_string(nul) + " (not a text file)");
  return text;
}

/// Rings of `x y` lines, separated by blank lines.
std::vector<Ring> readPointRings(const std::string& path) {
  std::istringstream in(readText(path));
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

RawSet readPolygonTextFolder(const fs::path& folder, const ImportOptions& options) {
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
  RawSet set{{std::move(raw)}, ""};
  gdal().place_bare_set(set, outer_path, options);
  return set;
}

/// Reads YAML with the file named in its errors.
YAML::Node loadYaml(const std::string& path) {
  try {
    return YAML::Load(readText(path));
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

/// A mapping's key as text; a key that is a list or a mapping is refused (yaml-cpp would throw).
std::string keyOf(const YAML::Node& key, const std::string& path) {
  if (!key.IsScalar())
    throw InputError(path, "line " + std::to_string(key.Mark().line + 1), std::string("a key must be a plain name, got a ") +
                                                                            (key.IsSequence() ? "list" : key.IsMap() ? "mapping" : "null"));
  return key.Scalar();
}

RawSet readHullYaml(const std::string& path, const YAML::Node& doc, const ImportOptions& options) {
  for (const auto& kv : doc) {
    const std::string key = keyOf(kv.first, path);
    if (key != "hull" && key != "holes" && key != "name") throw InputError(path, key, "unknown key (expected hull, holes, name)");
  }
  RawPolygon raw;
  raw.outer = yamlRing(doc["hull"], path, "hull");
  if (doc["holes"]) {
    if (!doc["holes"].IsSequence()) throw InputError(path, "holes", "must be a list of rings");
    for (std::size_t i = 0; i < doc["holes"].size(); ++i)
      raw.holes.push_back(yamlRing(doc["holes"][i], path, "holes[" + std::to_string(i) + "]"));
  }
  if (doc["name"] && !doc["name"].IsScalar()) throw InputError(path, "name", "must be text");
  raw.name = doc["name"] ? doc["name"].Scalar() : stemOf(path);
  raw.feature = "hull";
  RawSet set{{std::move(raw)}, ""};
  gdal().place_bare_set(set, path, options);
  return set;
}

/// A map_server map: its image's free cells (by the thresholds and `negate`) as polygons, placed
/// by the map's origin (x, y, yaw).
struct MapPlacement {
  double x = 0, y = 0, yaw = 0;
};

/// What a map import left out: free components other than the kept ones.
struct MapDrops {
  std::size_t components = 0;
  double area = 0.0;
};

RawSet readOccupancyMap(const std::string& path, const YAML::Node& doc, const ImportOptions& options,
                        MapPlacement& placement, std::vector<ImportedSource>& extra_sources, MapDrops& drops,
                        std::vector<RoomsReport>& rooms) {
  static const std::set<std::string> known = {"image", "resolution", "origin", "occupied_thresh", "free_thresh",
                                               "negate", "mode"};
  for (const auto& kv : doc)
    if (!known.count(keyOf(kv.first, path))) throw InputError(path, kv.first.Scalar(), "unknown key of a map_server map");
  if (!doc["image"] || !doc["image"].IsScalar()) throw InputError(path, "image", "missing (the map's PGM or PNG file)");
  const double resolution = yamlNumber(doc["resolution"], path, "resolution");
  if (!(resolution >= kMinMapResolution && resolution <= kMaxMapResolution))
    throw InputError(path, "resolution", "must be between 0.001 and 100 metres per pixel, got " + shortNumber(resolution));
  const YAML::Node origin = doc["origin"];
  if (!origin || !origin.IsSequence() || origin.size() != 3)
    throw InputError(path, "origin", origin ? "must be [x, y, yaw]" : "missing ([x, y, yaw] of the lower-left pixel)");
  placement = {yamlNumber(origin[0], path, "origin[0]"), yamlNumber(origin[1], path, "origin[1]"),
               yamlNumber(origin[2], path, "origin[2]")};
  for (int k = 0; k < 2; ++k)
    if (std::fabs(k == 0 ? placement.x : placement.y) > kMaxImportCoordinate)
      throw InputError(path, "origin[" + std::to_string(k) + "]", "must be within 1e8 metres, got " + shortNumber(k == 0 ? placement.x : placement.y));
  import_detail::MapRule rule;
  rule.occupied_thresh = doc["occupied_thresh"] ? yamlNumber(doc["occupied_thresh"], path, "occupied_thresh") : 0.65;
  rule.free_thresh = doc["free_thresh"] ? yamlNumber(doc["free_thresh"], path, "free_thresh") : 0.196;
  const double occupied = rule.occupied_thresh, free = rule.free_thresh;
  if (occupied < 0 || occupied > 1) throw InputError(path, "occupied_thresh", "must be between 0 and 1, got " + shortNumber(occupied));
  if (free < 0 || free > 1) throw InputError(path, "free_thresh", "must be between 0 and 1, got " + shortNumber(free));
  if (free > occupied) throw InputError(path, "free_thresh", "must not exceed occupied_thresh (" + shortNumber(occupied) + ")");
  if (doc["negate"]) {
    const std::string n = doc["negate"].IsScalar() ? doc["negate"].Scalar() : "(not a value)";
    if (n != "0" && n != "1" && n != "true" && n != "false") throw InputError(path, "negate", "must be 0 or 1, got '" + n + "'");
    rule.negate = n == "1" || n == "true";
  }
  const std::string mode = doc["mode"] ? (doc["mode"].IsScalar() ? doc["mode"].Scalar() : "(not a value)") : "trinary";
  if (mode != "trinary" && mode != "scale" && mode != "raw")
    throw InputError(path, "mode", "must be trinary, scale or raw, got '" + mode + "'");
  rule.mode = mode == "raw" ? import_detail::MapRule::Mode::Raw
              : mode == "scale" ? import_detail::MapRule::Mode::Scale
                                : import_detail::MapRule::Mode::Trinary;
  if (options.simplify > kMaxExtent)
    throw InputError("--simplify", "(value)", "must be at most 10000 metres, got " + shortNumber(options.simplify));

  const fs::path image_path = fs::path(path).parent_path() / doc["image"].Scalar();
  import_detail::requireUtf8Path(image_path.string(), path, "image");
  if (!fs::is_regular_file(image_path)) throw InputError(path, "image", "'" + image_path.string() + "' is not a file");
  import_detail::FreeMask mask = gdal().read_free_cells(image_path.string(), path, "image", rule, resolution);
  extra_sources.push_back({image_path.string(), sha256Hex(readFile(image_path.string()))});
  if (mask.free_cells == 0) throw InputError(path, "image", "has no free cell (by free_thresh " + shortNumber(free) + ")");
  const double tolerance = options.simplify >= 0 ? options.simplify : resolution / 2;
  if (!options.rooms.empty()) {
    rooms.emplace_back();
    return import_detail::readRooms(path, image_path.string(), stemOf(path), std::move(mask), resolution, tolerance, options,
                                    extra_sources, rooms.back());
  }
  import_detail::Components found = gdal().polygonize_mask(mask.free, mask.width, mask.height, resolution, tolerance, path);
  if (found.polygons.empty()) throw InputError(path, "image", "has no free area left after simplification");
  std::vector<RawPolygon>& components = found.polygons;
  const std::size_t total = components.size() + found.lost;
  drops.components = found.lost;
  drops.area = found.lost_area;
  if (!options.all_components) {
    for (std::size_t i = 1; i < components.size(); ++i) {
      ++drops.components;
      drops.area += found.pixel_areas[i];
    }
    components.resize(1);
  }
  drops.area = std::round(drops.area * 1e8) / 1e8;  // whole pixels' area, as the decimal it is
  const std::string stem = stemOf(path);
  for (std::size_t i = 0; i < components.size(); ++i) {
    components[i].feature = "component " + std::to_string(i + 1) + " of " + std::to_string(total);
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

/// An image a map_server map names: on its own it has no scale or placement.
bool isImageFile(const fs::path& p) {
  static const std::set<std::string> images = {".png", ".pgm", ".ppm", ".pnm", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".gif"};
  if (images.count(lower(p.extension().string()))) return true;
  std::ifstream in(p, std::ios::binary);
  std::string head(8, '\0');
  in.read(head.data(), 8);
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.rfind("\x89PNG", 0) == 0 || head.rfind("P5", 0) == 0 || head.rfind("P6", 0) == 0;
}

std::string bareImageMessage(const fs::path& p) {
  fs::path yaml = p;
  yaml.replace_extension(".yaml");
  return "is an image without its map_server YAML, which gives its scale and place: write " + yaml.filename().string() +
         " holding `image: " + p.filename().string() +
         "`, `resolution: METRES_PER_PIXEL` and `origin: [X, Y, YAW]` beside it and import that";
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
  ring.reserve(in.size());
  for (const Point& p : in) {
    // After projection and --transform: a scale of 1e300 must not reach the geometry.
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::fabs(p.x) > kMaxImportCoordinate || std::fabs(p.y) > kMaxImportCoordinate)
      throw InputError(source, field, "has a point (" + shortNumber(p.x) + ", " + shortNumber(p.y) +
                                          ") beyond 1e8 m once placed (--transform?)");
    const Point q{roundToGrid(p.x), roundToGrid(p.y)};
    if (ring.empty() || !(ring.back() == q)) ring.push_back(q);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) throw InputError(source, field, "has fewer than 3 distinct points");
  // The wall reader's own test (an O(n log n) sweep since ecf349f): an imported wall reads back.
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

/// The files of a folder to import, with its subfolders' (any depth), in name order: polygon-text
/// folders as themselves. Symbolic links to folders are not followed (no loops).
void collectFolder(const fs::path& folder, const std::string& forced_format, std::vector<std::pair<fs::path, std::string>>& out,
                   int depth) {
  if (depth > 32) throw InputError(folder.string(), "(folder)", "is nested over 32 folders deep");
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(folder)) entries.push_back(e.path());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& e : entries) {
    const std::string f = formatOf(e);
    if (f == "folder") {
      // A CoverBench dataset (an earlier import's output, say) is walls, not sources.
      if (!fs::is_symlink(e) && !fs::exists(e / "manifest.json")) collectFolder(e, forced_format, out, depth + 1);
      continue;
    }
    if (f.empty()) continue;
    const bool matches = forced_format == "auto" || f == forced_format ||
                         (f == "yaml" && (forced_format == "map" || forced_format == "yaml-polygon"));
    if (matches) out.emplace_back(e, forced_format == "auto" ? f : forced_format);
  }
}

std::string formatList() {
  std::string s;
  for (const std::string& f : importFormats()) s += (s.empty() ? "" : ", ") + f;
  return s;
}

void importFile(const std::string& source, const std::string& format, const ImportOptions& options, ImportResult& result);

/// Imports one file or folder into `result`.
void importSource(const std::string& source, const std::string& forced_format, const ImportOptions& options,
                  ImportResult& result) {
  const fs::path p(source);
  if (!fs::exists(p)) throw InputError(source, "(source)", "does not exist");
  if (fs::is_directory(p)) {
    // A polygon-text folder is one wall; any other folder: every file of a known format in it
    // and in its subfolders, and its polygon-text folders, in name order.
    if (formatOf(p) == "polygon-text" && (forced_format == "auto" || forced_format == "polygon-text")) {
      importFile(source, "polygon-text", options, result);
      return;
    }
    std::vector<std::pair<fs::path, std::string>> files;
    collectFolder(p, forced_format, files, 0);
    if (files.empty())
      throw InputError(source, "(folder)", forced_format == "auto"
                                               ? "holds nothing to import (formats: " + formatList() + ")"
                                               : "holds nothing of --format " + forced_format);
    for (const auto& [file, format] : files) importFile(file.string(), format, options, result);
    return;
  }
  const std::string format = forced_format == "auto" ? formatOf(p) : forced_format;
  if (format.empty()) {
    if (isImageFile(p)) throw InputError(source, "(file)", bareImageMessage(p));
    throw InputError(source, "--format", "cannot tell the format from the name '" + p.filename().string() +
                                             "': give --format (" + formatList() + ")");
  }
  importFile(source, format, options, result);
}

void importFile(const std::string& source, const std::string& format, const ImportOptions& options, ImportResult& result) {
  import_detail::requireUtf8Path(source, source, "(path)");
  const fs::path p(source);
  if (format == "polygon-text") {
    if (!fs::is_directory(p)) throw InputError(source, "--format", "polygon-text is a folder holding outer_polygon (and holes)");
  } else if (fs::is_directory(p)) {
    throw InputError(source, "--format", "is a folder: " + format + " is a file");
  }
  if (format != "polygon-text" && format != "yaml" && format != "yaml-polygon" && format != "map" && format != "wkt" &&
      format != "dxf" && format != "geojson" && format != "gml" && format != "kml" && format != "shapefile" && format != "gpkg")
    throw InputError(source, "--format", "unknown format '" + format + "'");
  if (!options.rooms.empty() && format != "map" && format != "yaml")
    throw InputError(source, "--rooms", "needs a map_server map (a YAML naming its image), not " + format);
  if ((format == "map" || format == "yaml" || format == "yaml-polygon" || format == "wkt") && isImageFile(p))
    throw InputError(source, "--format", format == "map" ? bareImageMessage(p) : "is an image, not " + format + " text");
  // Read once: hashed here, parsed from the same bytes (WKT); 20 MB twice was a tenth of the time.
  const std::string bytes = fs::is_directory(p) ? std::string() : readFile(source);
  if (!fs::is_directory(p)) result.sources.push_back({source, sha256Hex(bytes)});

  RawSet set;
  MapPlacement placement;
  MapDrops drops;
  bool is_map = false;
  if (format == "polygon-text") {
    set = readPolygonTextFolder(p, options);
    for (const char* name : {"outer_polygon", "holes"}) {
      const std::string f = polygonTextFile(p, name);
      if (!f.empty()) result.sources.push_back({f, sha256Hex(readFile(f))});
    }
  } else if (format == "yaml" || format == "yaml-polygon" || format == "map") {
    try {
      const YAML::Node doc = loadYaml(source);
      if (!doc.IsMap()) throw InputError(source, "(document)", "must be a YAML mapping (hull/holes, or a map_server map)");
      is_map = format == "map" || (format == "yaml" && doc["image"]);
      if (is_map) set = readOccupancyMap(source, doc, options, placement, result.sources, drops, result.rooms);
      else if (!options.rooms.empty()) throw InputError(source, "--rooms", "needs a map_server map (a YAML naming its image)");
      else if (format == "yaml-polygon" || doc["hull"]) set = readHullYaml(source, doc, options);
      else throw InputError(source, "(document)", "is neither a hull/holes polygon (no 'hull') nor a map_server map (no 'image')");
    } catch (const YAML::Exception& e) {  // a value of the wrong kind anywhere: one line, not an internal error
      throw InputError(source, "line " + std::to_string(e.mark.line + 1), e.msg);
    }
  } else if (format == "wkt") {
    set = gdal().read_wkt_text(bytes, source, options);
  } else if (format == "dxf") {
    set = gdal().read_dxf_file(source, options);
  } else {
    set = gdal().read_vector_file(source, format, options);
    for (const std::string& c : companionFiles(p, format)) result.sources.push_back({c, sha256Hex(readFile(c))});
  }

  Eigen::Affine2d placement_transform = userTransform(options.transform);
  if (is_map) placement_transform = placement_transform * Eigen::Translation2d(placement.x, placement.y) * Eigen::Rotation2Dd(placement.yaw);
  place(set, placement_transform);
  const std::string stem = stemOf(source);
  std::vector<int> room_labels;  // of the walls, in order: the kept rooms'
  if (is_map && !options.rooms.empty())
    for (const RoomReport& room : result.rooms.back().rooms)
      if (!room.wall.empty()) room_labels.push_back(room.label);
  for (std::size_t i = 0; i < set.polygons.size(); ++i) {
    const std::string fallback = set.polygons.size() > 1 ? stem + "_" + std::to_string(i + 1) : stem;
    result.walls.push_back(wallOf(set.polygons[i], fallback, set.crs, source, options));
    if (is_map) {
      result.walls.back().from_map = true;
      if (!room_labels.empty()) {  // a room's wall: what it dropped is in result.rooms
        result.walls.back().room = room_labels[i];
      } else if (i == 0) {  // a map's drops are recorded once, on its first wall
        result.walls.back().dropped_components = drops.components;
        result.walls.back().dropped_component_area = drops.area;
      }
    }
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
  if (!(options.min_room_area >= 0)) throw InputError("--min-room-area", "(value)", "must be 0 or more");
  if (options.rooms.empty() && options.min_room_area > 0) throw InputError("--min-room-area", "(value)", "applies to --rooms only");
  if (!options.rooms.empty()) {
    if (sources.size() != 1 || fs::is_directory(sources[0]))
      throw InputError("--rooms", "(value)", "labels the rooms of one map: give its YAML as the only source");
    if (options.all_components)
      throw InputError("--rooms", "(value)", "keeps each room's largest part: --all-components does not apply");
  }
  ImportResult result;
  for (const std::string& s : sources) importSource(s, options.format, options, result);
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
                    (options.rooms.empty() ? std::string()
                                           : ", \"rooms\": " + json(options.rooms).dump() + ", \"min_room_area\": " + num(options.min_room_area)) +
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
           std::to_string(w.dropped_holes) + ", \"dropped_hole_area\": " + num(w.dropped_hole_area) +
           (w.room ? ", \"room\": " + std::to_string(w.room)
            : w.from_map ? ", \"dropped_components\": " + std::to_string(w.dropped_components) +
                               ", \"dropped_component_area\": " + num(w.dropped_component_area)
                         : std::string()) +
           "}";
  }
  out += "\n    ]";
  for (const RoomsReport& rooms : result.rooms) out += ",\n    \"rooms\": " + import_detail::roomsRecordJson(rooms);
  return out + "\n  }";
}

}  // namespace coverbench
