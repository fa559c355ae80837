#pragma once
/// Walls from the maps and polygons the field already has (docs/datasets.md): vector geodata and
/// CAD through GDAL/OGR (GeoJSON, GML, KML, Shapefile, GeoPackage, DXF, WKT), the plain
/// polygon-text folders, YAML hull/holes, and map_server occupancy grids (YAML + PGM/PNG).
/// Every imported wall passes validateWall; bad input throws InputError (`FILE: FIELD: PROBLEM`)
/// before anything is written.

#include <cstddef>
#include <string>
#include <vector>

#include "coverbench/wall.hpp"

namespace coverbench {

/// Limits on what an import reads, refused up front with one line (docs/datasets.md): a map
/// image's pixels (a 30000 x 30000 PGM of 1 KB asked for 3.5 GB), a map's metres per pixel, and
/// any coordinate's magnitude in the file's units (1e155 hung GEOS).
inline constexpr double kMaxMapPixels = 1e8;
inline constexpr double kMinMapResolution = 1e-3;
inline constexpr double kMaxMapResolution = 100.0;
inline constexpr double kMaxImportCoordinate = 1e8;
/// At most this many room labels in a segmentation image (`--rooms`): each is a wall.
inline constexpr std::size_t kMaxRooms = 1000;

/// The formats `--format` names; "auto" picks one by the file's extension (or a folder's files).
const std::vector<std::string>& importFormats();

/// One step of a placement transform, applied in the order given (`--transform`).
struct TransformStep {
  enum class Kind { Translate, Rotate, Scale } kind = Kind::Translate;
  double x = 0.0, y = 0.0;  ///< translate: offset; scale: factors (x, y); rotate: x is degrees
};

struct ImportOptions {
  std::string format = "auto";
  /// Target CRS of geographic input ("EPSG:32632", any string PROJ reads); empty: the local UTM
  /// zone of each file's centre.
  std::string crs;
  /// CRS of input that names none (a Shapefile without .prj, DXF, WKT, polygon text, YAML hull):
  /// empty means metres, but coordinates that look like degrees are refused; "metres" says they
  /// are metres.
  std::string source_crs;
  /// The attribute that names each wall (vector formats); empty: "name" when present, else the
  /// file's stem and the feature's number.
  std::string name_field;
  bool split_multipolygons = true;  ///< false: a multipolygon with more than one part is refused
  /// DXF: the layer whose closed polylines are boundaries; obstacles come from `dxf_obstacle_layers`
  /// (empty: every other layer).
  std::string dxf_boundary_layer = "boundary";
  std::vector<std::string> dxf_obstacle_layers;
  /// Occupancy grids: every free component as its own wall (default: the largest only).
  bool all_components = false;
  /// Holes (obstacles) smaller than this many m^2 are dropped and counted (every format).
  double min_hole_area = 0.0;
  /// Occupancy grids: simplification tolerance in metres; negative: half a pixel.
  double simplify = -1.0;
  /// A map's segmentation image (`--rooms`): one wall per labelled room instead of the largest
  /// free component. Only with one map as the only source.
  std::string rooms;
  /// With `rooms`: a room whose wall would cover less than this many m^2 of free pixels is dropped.
  double min_room_area = 0.0;
  /// Placement of every imported wall, after projection and the map's own origin.
  std::vector<TransformStep> transform;
  /// Where the coordinates end up: "keep" them, move each wall's lower-left corner to the
  /// "corner" (0, 0), or "auto": the corner when a coordinate lies beyond 10 km (UTM metres do).
  std::string origin = "auto";
};

/// Parses `--transform` text: steps separated by spaces, each `translate=X,Y`, `rotate=DEG` or
/// `scale=S` / `scale=SX,SY`. Throws InputError(source, field, ...).
std::vector<TransformStep> parseTransform(const std::string& text, const std::string& source, const std::string& field);

struct ImportedWall {
  Wall wall;
  std::string source;        ///< the file it came from
  std::string feature;       ///< which feature or component ("feature 3", "component 1 of 2")
  double origin_x = 0.0, origin_y = 0.0;  ///< subtracted from every coordinate (origin "corner")
  std::string crs;           ///< the CRS of its coordinates before that shift ("" for local metres)
  std::size_t dropped_holes = 0;
  double dropped_hole_area = 0.0;
  /// A map's wall: the free components left out (all but the largest, without --all-components,
  /// and those simplification left empty) and their area before simplification.
  bool from_map = false;
  std::size_t dropped_components = 0;
  double dropped_component_area = 0.0;
  int room = 0;  ///< a room's wall (`--rooms`): its label; 0 otherwise
};

/// One label of a segmentation (`--rooms`), in the map's pixels (a pixel's area is the
/// resolution squared). Its free pixels are its wall's part (the largest 4-connected one) and
/// its other parts, dropped; a room dropped whole has no wall and keeps no pixel.
struct RoomReport {
  int label = 0;
  std::string wall;     ///< its wall's name; empty when the room was dropped
  std::string dropped;  ///< why the room has no wall ("no free pixel", "under --min-room-area", "simplified away")
  std::size_t free_pixels = 0;      ///< labelled and free in the map
  std::size_t parts = 0;            ///< 4-connected parts of those
  std::size_t kept_pixels = 0;      ///< those of its wall's part
  std::size_t not_free_pixels = 0;  ///< labelled but occupied or unknown in the map: never free, in no area
};

/// What a `--rooms` import kept and dropped. The identity: the kept pixels of every room are the
/// map's free pixels less the dropped ones (unlabelled free pixels, and each room's free pixels
/// outside its wall's part).
struct RoomsReport {
  std::string map, segmentation;
  double resolution = 0.0;  ///< metres per pixel
  std::size_t free_pixels = 0;             ///< the map's
  std::size_t unlabelled_free_pixels = 0;  ///< free pixels of label 0
  std::vector<RoomReport> rooms;           ///< by label
  std::size_t keptPixels() const;
  std::size_t droppedPixels() const;
  std::size_t notFreePixels() const;
  double area(std::size_t pixels) const { return static_cast<double>(pixels) * resolution * resolution; }
};

struct ImportedSource {
  std::string path;
  std::string sha256;  ///< of the file's bytes (a map: of the YAML; its image is listed too)
};

struct ImportResult {
  std::vector<ImportedWall> walls;
  std::vector<ImportedSource> sources;
  std::vector<RoomsReport> rooms;  ///< one with `--rooms`, else none
};

/// Imports every source (files or folders) in order; walls keep the order of their sources and
/// features. Throws InputError on the first problem: nothing is half imported.
ImportResult importWalls(const std::vector<std::string>& sources, const ImportOptions& options);

/// What a `--rooms` import kept and dropped, as the command prints it: the totals, then a line per
/// label.
std::string describeRooms(const RoomsReport& report);

/// The manifest's "import" object: the sources with their hashes, the options, and each wall's
/// source, feature, CRS and origin (one wall per line; same input, same bytes).
std::string importRecordJson(const ImportResult& result, const ImportOptions& options);

}  // namespace coverbench
