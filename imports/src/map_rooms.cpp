// Rooms from a segmentation image (docs/datasets.md, "Rooms"): each label's free pixels, as the
// map's thresholds read them, vectorised like the map's free space (the plug-in's polygonizer),
// the largest part of each room a wall; everything else counted in the RoomsReport.
#include "map_rooms.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"

namespace coverbench {

std::size_t RoomsReport::keptPixels() const {
  std::size_t n = 0;
  for (const RoomReport& r : rooms) n += r.kept_pixels;
  return n;
}

std::size_t RoomsReport::droppedPixels() const {
  std::size_t n = unlabelled_free_pixels;
  for (const RoomReport& r : rooms) n += r.free_pixels - r.kept_pixels;
  return n;
}

std::size_t RoomsReport::notFreePixels() const {
  std::size_t n = 0;
  for (const RoomReport& r : rooms) n += r.not_free_pixels;
  return n;
}

std::string describeRooms(const RoomsReport& report) {
  auto pixels = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " pixel" : " pixels"); };
  auto area = [&](std::size_t n) { return shortNumber(std::round(report.area(n) * 1e8) / 1e8) + " m^2"; };
  std::size_t walls = 0, room_dropped = 0;
  for (const RoomReport& r : report.rooms) walls += !r.wall.empty(), room_dropped += r.free_pixels - r.kept_pixels;
  std::string out = "rooms of " + report.map + " by " + report.segmentation + ": " + std::to_string(walls) + " of " +
                    std::to_string(report.rooms.size()) + " labels are walls; " + std::to_string(report.keptPixels()) +
                    " of the map's " + pixels(report.free_pixels) + " free kept (" + area(report.keptPixels()) + " of " +
                    area(report.free_pixels) + "), " + std::to_string(report.droppedPixels()) + " dropped (" +
                    area(report.droppedPixels()) + "): " + std::to_string(report.unlabelled_free_pixels) + " unlabelled, " +
                    std::to_string(room_dropped) + " of rooms; " + pixels(report.notFreePixels()) +
                    " labelled but not free in the map\n";
  for (const RoomReport& r : report.rooms) {
    out += "  room " + std::to_string(r.label) + ": ";
    if (r.wall.empty()) {
      out += "dropped (" + r.dropped + "): " + pixels(r.free_pixels) + " free (" + area(r.free_pixels) + ")";
    } else {
      out += r.wall + ", " + std::to_string(r.kept_pixels) + " of " + pixels(r.free_pixels) + " free kept (" +
             area(r.kept_pixels) + ")";
      if (r.parts > 1)
        out += ", " + std::to_string(r.parts - 1) + " of " + std::to_string(r.parts) + " parts dropped (" +
               pixels(r.free_pixels - r.kept_pixels) + ", " + area(r.free_pixels - r.kept_pixels) + ")";
    }
    if (r.not_free_pixels) out += "; " + pixels(r.not_free_pixels) + " labelled but not free";
    out += "\n";
  }
  return out;
}

namespace import_detail {

RawSet readRooms(const std::string& map_path, const std::string& image_path, const std::string& stem, FreeMask mask,
                 double resolution, double tolerance, const ImportOptions& options, std::vector<ImportedSource>& extra_sources,
                 RoomsReport& report) {
  const std::string& segmentation = options.rooms;
  requireUtf8Path(segmentation, map_path, "--rooms");
  // As the map's image: a regular file (a link to one is followed; a FIFO is never opened).
  if (!std::filesystem::is_regular_file(segmentation))
    throw InputError(map_path, "--rooms", "'" + segmentation + "' is not a file");
  LabelImage image = gdal().read_labels(segmentation, map_path, "--rooms", mask.width, mask.height, image_path);
  extra_sources.push_back({segmentation, sha256Hex(readFile(segmentation))});

  // Each label's free and not-free pixels; then the labels' own image keeps only free pixels.
  std::vector<std::size_t> free_count(65536, 0), other_count(65536, 0);
  std::size_t labels = 0;
  for (std::size_t i = 0; i < image.labels.size(); ++i) {
    const std::uint16_t label = image.labels[i];
    if (label == 0) continue;
    if (free_count[label] == 0 && other_count[label] == 0) ++labels;
    ++(mask.free[i] ? free_count : other_count)[label];
    if (!mask.free[i]) image.labels[i] = 0;
  }
  if (labels == 0) throw InputError(map_path, "--rooms", "'" + segmentation + "' labels no room (every pixel is 0)");
  if (labels > kMaxRooms)
    throw InputError(map_path, "--rooms", "'" + segmentation + "' holds " + std::to_string(labels) +
                                              " labels, over the limit of " + std::to_string(kMaxRooms) + " rooms");
  mask.free = {};  // its memory, before the polygons take theirs
  Components found = gdal().polygonize_labels(image.labels, image.width, image.height, resolution, tolerance, map_path);

  report.map = map_path;
  report.segmentation = segmentation;
  report.resolution = resolution;
  report.free_pixels = mask.free_cells;
  report.unlabelled_free_pixels = mask.free_cells;
  // Largest first: a label's first polygon is its wall's part.
  std::vector<long> kept_index(65536, -1);
  std::vector<std::size_t> parts(65536, 0);
  for (std::size_t i = 0; i < found.polygons.size(); ++i) {
    const auto label = static_cast<std::size_t>(found.values[i]);
    ++parts[label];
    if (kept_index[label] < 0) kept_index[label] = static_cast<long>(i);
  }
  for (int value : found.lost_values) ++parts[static_cast<std::size_t>(value)];
  RawSet set;
  const double pixel_area = resolution * resolution;
  for (std::size_t label = 1; label < free_count.size(); ++label) {
    if (free_count[label] == 0 && other_count[label] == 0) continue;
    RoomReport room;
    room.label = static_cast<int>(label);
    room.free_pixels = free_count[label];
    room.not_free_pixels = other_count[label];
    room.parts = parts[label];
    report.unlabelled_free_pixels -= room.free_pixels;
    const long k = kept_index[label];
    // The part's area is whole pixels (before simplification): its count, exactly.
    const std::size_t kept =
        k < 0 ? 0 : static_cast<std::size_t>(std::llround(found.pixel_areas[static_cast<std::size_t>(k)] / pixel_area));
    if (room.free_pixels == 0) room.dropped = "no free pixel";
    else if (k < 0) room.dropped = "simplified away";
    else if (static_cast<double>(kept) * pixel_area < options.min_room_area) room.dropped = "under --min-room-area";
    if (room.dropped.empty()) {
      room.kept_pixels = kept;
      room.wall = stem + "-room-" + std::to_string(label);
      RawPolygon& polygon = found.polygons[static_cast<std::size_t>(k)];
      polygon.name = room.wall;
      polygon.feature = "room " + std::to_string(label);
      set.polygons.push_back(std::move(polygon));
    }
    report.rooms.push_back(std::move(room));
  }
  if (set.polygons.empty())
    throw InputError(map_path, "--rooms", "no room of '" + segmentation + "' is left: each of its " + std::to_string(labels) +
                                              " labels has no free pixel, was simplified away or is under --min-room-area");
  return set;
}

std::string roomsRecordJson(const RoomsReport& report) {
  using nlohmann::json;
  // Areas as the decimals whole pixels make (as a map's dropped components).
  auto area = [&](std::size_t pixels) { return json(std::round(report.area(pixels) * 1e8) / 1e8).dump(); };
  std::string out = "{\"map\": " + json(report.map).dump() + ", \"segmentation\": " + json(report.segmentation).dump() +
                    ", \"resolution\": " + json(report.resolution).dump() + ", \"free_pixels\": " +
                    std::to_string(report.free_pixels) + ", \"kept_pixels\": " + std::to_string(report.keptPixels()) +
                    ", \"dropped_pixels\": " + std::to_string(report.droppedPixels()) + ", \"unlabelled_free_pixels\": " +
                    std::to_string(report.unlabelled_free_pixels) + ", \"labelled_not_free_pixels\": " +
                    std::to_string(report.notFreePixels()) + ", \"free_area\": " + area(report.free_pixels) +
                    ", \"kept_area\": " + area(report.keptPixels()) + ", \"dropped_area\": " + area(report.droppedPixels()) +
                    ",\n      \"by_label\": [";
  for (std::size_t i = 0; i < report.rooms.size(); ++i) {
    const RoomReport& r = report.rooms[i];
    out += std::string(i ? ",\n        " : "\n        ") + "{\"label\": " + std::to_string(r.label) +
           ", \"wall\": " + json(r.wall).dump() + ", \"dropped\": " + json(r.dropped).dump() +
           ", \"free_pixels\": " + std::to_string(r.free_pixels) + ", \"parts\": " + std::to_string(r.parts) +
           ", \"kept_pixels\": " + std::to_string(r.kept_pixels) + ", \"dropped_pixels\": " +
           std::to_string(r.free_pixels - r.kept_pixels) + ", \"not_free_pixels\": " + std::to_string(r.not_free_pixels) +
           ", \"kept_area\": " + area(r.kept_pixels) + ", \"dropped_area\": " + area(r.free_pixels - r.kept_pixels) + "}";
  }
  return out + "\n      ]}";
}

}  // namespace import_detail
}  // namespace coverbench
