// Dataset folders: wall files plus manifest.json (family, seed, and each file's SHA-256).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "coverbench/datasets.hpp"
#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr const char* kManifest = "manifest.json";
constexpr const char* kFormat = "coverbench-dataset/1";

std::string manifestText(const Dataset& d) {
  // One wall per line, fixed key order: the same dataset gives the same bytes.
  std::string out = "{\n  \"format\": \"" + std::string(kFormat) + "\",\n  \"family\": " + json(d.family).dump() +
                    ",\n  \"seed\": " + std::to_string(d.seed) + ",\n  \"count\": " + std::to_string(d.entries.size()) +
                    ",\n  \"walls\": [";
  for (std::size_t i = 0; i < d.entries.size(); ++i) {
    const DatasetEntry& e = d.entries[i];
    out += (i ? ",\n    " : "\n    ") + std::string("{\"file\": ") + json(e.file).dump() + ", \"name\": " + json(e.name).dump() +
           ", \"sha256\": \"" + e.sha256 + "\"}";
  }
  out += d.entries.empty() ? "]" : "\n  ]";
  if (!d.import_record.empty()) out += ",\n  \"import\": " + d.import_record;
  return out + "\n}\n";
}

}  // namespace

Dataset writeDataset(const std::string& dir, const std::string& family, std::uint64_t seed, const std::vector<Wall>& walls,
                     const std::string& import_record) {
  Dataset d;
  d.family = family;
  d.seed = seed;
  d.import_record = import_record;
  // "manifest" first: the manifest's name is taken, so a wall named manifest is manifest-2.json
  // (it was written twice, and refused).
  std::vector<std::string> texts, names{"manifest"};
  for (const Wall& w : walls) names.push_back(w.name);
  std::vector<std::string> files = uniqueFileNames(names);  // path-safe, one file per wall
  files.erase(files.begin());
  for (std::size_t i = 0; i < walls.size(); ++i) {
    texts.push_back(wallToJson(walls[i]));
    d.entries.push_back({files[i] + ".json", walls[i].name, family, sha256Hex(texts.back())});
  }
  d.walls = walls;
  const std::string manifest = manifestText(d);
  const fs::path folder(dir);
  const fs::path manifest_path = folder / kManifest;
  if (fs::exists(folder)) {
    if (!fs::is_directory(folder)) throw InputError(dir, "--out", "exists and is not a folder");
    if (fs::exists(manifest_path)) {
      if (readFile(manifest_path.string()) == manifest) return d;  // already there, byte for byte
      throw InputError(dir, "--out", "already holds a different dataset (manifest.json differs); choose another folder");
    }
    if (!fs::is_empty(folder)) throw InputError(dir, "--out", "is not empty and has no manifest.json; choose an empty folder");
  }
  OutputFiles out;  // all walls and the manifest, or nothing
  out.folder(dir);
  for (std::size_t i = 0; i < walls.size(); ++i) out.add((folder / d.entries[i].file).string(), texts[i]);
  out.add(manifest_path.string(), manifest);  // its presence marks a complete dataset
  out.commit();
  return d;
}

Dataset readDataset(const std::string& dir) {
  const fs::path folder(dir);
  if (!fs::is_directory(folder)) throw InputError(dir, "(folder)", "is not a folder");
  Dataset d;
  const fs::path manifest_path = folder / kManifest;
  if (fs::exists(manifest_path)) {
    const std::string source = manifest_path.string();
    const json doc = parseJsonStrict(readFile(source), source);
    if (!doc.is_object() || doc.value("format", "") != kFormat)
      throw InputError(source, "format", std::string("must be \"") + kFormat + "\"");
    if (!doc.contains("walls") || !doc["walls"].is_array()) throw InputError(source, "walls", "must be an array");
    if (doc.contains("family") && !doc["family"].is_string()) throw InputError(source, "family", "must be a string");
    if (doc.contains("seed") && !doc["seed"].is_number_unsigned())
      throw InputError(source, "seed", "must be a whole number, 0 or more");
    d.family = doc.value("family", "");
    d.seed = doc.value("seed", std::uint64_t{0});
    if (doc.contains("import")) {
      if (!doc["import"].is_object()) throw InputError(source, "import", "must be an object");
      d.import_record = doc["import"].dump();
    }
    for (std::size_t i = 0; i < doc["walls"].size(); ++i) {
      const json& w = doc["walls"][i];
      const std::string field = "walls[" + std::to_string(i) + "]";
      if (!w.is_object() || !w.contains("file") || !w["file"].is_string() || !w.contains("sha256") || !w["sha256"].is_string())
        throw InputError(source, field, "must have \"file\" and \"sha256\" strings");
      DatasetEntry e{w["file"].get<std::string>(), w.value("name", ""), d.family, w["sha256"].get<std::string>()};
      if (e.file.empty() || e.file.find('/') != std::string::npos || e.file == "." || e.file == "..")
        throw InputError(source, field + ".file", "must be a file name in the dataset's folder, got '" + shownBytes(e.file) + "'");
      const std::string path = (folder / e.file).string();
      const std::string text = readFile(path);
      if (sha256Hex(text) != e.sha256)
        throw InputError(source, field + ".sha256", "does not match " + e.file + " (the file changed after generation)");
      d.walls.push_back(parseWallJson(text, path));
      d.entries.push_back(std::move(e));
    }
    return d;
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(dir, "(folder)", "holds no .json wall files");
  d.family = "file";
  for (const fs::path& f : files) {
    const std::string text = readFile(f.string());
    d.walls.push_back(parseWallJson(text, f.string()));
    d.entries.push_back({f.filename().string(), d.walls.back().name, "file", sha256Hex(text)});
  }
  return d;
}

std::string describeDataset(const Dataset& d) {
  std::map<std::string, int> labels;
  std::size_t rects = 0, polygons = 0, circles = 0, rect_boundary = 0;
  std::vector<double> widths, heights, counts;
  for (const Wall& w : d.walls) {
    const Box b = boundingBox(w.boundary);
    widths.push_back(b.width());
    heights.push_back(b.height());
    counts.push_back(static_cast<double>(w.obstacles.size()));
    rect_boundary += w.boundary.size() == 4;
    for (const Obstacle& o : w.obstacles) {
      if (o.type == ObstacleType::Circle) {
        ++circles;
      } else {
        const Box ob = boundingBox(o.polygon);
        bool axis_rect = o.polygon.size() == 4;
        for (const Point& p : o.polygon)
          axis_rect = axis_rect && (p.x == ob.min_x || p.x == ob.max_x) && (p.y == ob.min_y || p.y == ob.max_y);
        ++(axis_rect ? rects : polygons);
      }
      ++labels[o.label.empty() ? "(no label)" : o.label];
    }
  }
  auto range = [](std::vector<double> v, const char* unit) {
    if (v.empty()) return std::string("-");
    std::sort(v.begin(), v.end());
    char buf[128];
    std::snprintf(buf, sizeof buf, "%g to %g%s (median %g)", v.front(), v.back(), unit, v[v.size() / 2]);
    return std::string(buf);
  };
  std::string out = "family: " + d.family + (d.family == "file" ? "" : ", seed " + std::to_string(d.seed)) + "\n";
  out += "walls: " + std::to_string(d.walls.size()) + " (" + std::to_string(rect_boundary) + " with 4-corner boundaries)\n";
  out += "width: " + range(widths, " m") + "\n";
  out += "height: " + range(heights, " m") + "\n";
  out += "obstacles per wall: " + range(counts, "") + "\n";
  out += "obstacle kinds: " + std::to_string(rects) + " axis-aligned rectangles, " + std::to_string(polygons) +
         " other polygons, " + std::to_string(circles) + " circles\n";
  out += "labels:";
  for (const auto& [label, n] : labels) out += " " + label + " " + std::to_string(n) + ";";
  out += "\n";
  return out;
}

}  // namespace coverbench
