#pragma once
// What the importer asks of GDAL/OGR, in plain types: the only translation unit that includes
// GDAL's headers is gdal_io.cpp (a heavy dependency stays in one place).

#include <cstdint>
#include <string>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/wall_import.hpp"

namespace coverbench::import_detail {

/// A polygon with holes as read, in metres of its CRS (rings in any orientation, not closed).
struct RawPolygon {
  Ring outer;
  std::vector<Ring> holes;
  std::string name;     ///< from the naming attribute, or empty
  std::string feature;  ///< "feature 3", "feature 3 part 2", "entity 12", "component 1 of 4"
};

/// Polygons of one file, and what they are in.
struct RawSet {
  std::vector<RawPolygon> polygons;
  std::string crs;  ///< the CRS of the coordinates ("EPSG:32632"), empty for local metres
};

/// A vector file through OGR (GeoJSON, GML, KML, Shapefile, GeoPackage; `format` is one of those
/// names of importFormats()). Geographic coordinates are projected (ImportOptions::crs, else
/// the local UTM zone); every polygon is checked for validity.
RawSet readVectorFile(const std::string& path, const std::string& format, const ImportOptions& options);

/// A DXF drawing: closed polylines (and polygons, circles) on the boundary layer become outer
/// rings; those on the obstacle layers become holes of the boundary that holds them.
RawSet readDxfFile(const std::string& path, const ImportOptions& options);

/// WKT text (one or more POLYGON / MULTIPOLYGON, separated by white space).
RawSet readWktText(const std::string& text, const std::string& source, const ImportOptions& options);

/// Coordinates of input without a CRS (polygon text, YAML hull/holes): refused when they look
/// like degrees, projected when --source-crs names a CRS in degrees. Sets `set.crs`.
void placeBareSet(RawSet& set, const std::string& source, const ImportOptions& options);

/// map_server's rule for one pixel (docs/datasets.md): occupancy is 1 - shade (shade with
/// `negate`), shade the mean of the colour channels (never alpha) on 0..1.
struct MapRule {
  enum class Mode { Trinary, Scale, Raw } mode = Mode::Trinary;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  bool negate = false;
};

/// The free cells of a map image (PGM, PNG, 8 or 16 bits, grey, grey+alpha, RGB(A), palette),
/// row 0 at the top; free = 1. `resolution` is checked against the image's size (10 km at most).
struct FreeMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> free;  ///< width * height, row-major
  std::size_t free_cells = 0;
};
FreeMask readFreeCells(const std::string& path, const std::string& source, const std::string& field, const MapRule& rule,
                       double resolution);

/// The grey values of a segmentation image (`--rooms`), row 0 at the top: each room's pixels carry
/// its label, 0 is no room. Read within the map image's limits, and refused unless it is `width`
/// x `height` pixels (the map's image, `map_image`) and every pixel is grey (8 or 16 bits, or
/// colours whose channels agree).
struct LabelImage {
  int width = 0, height = 0;
  std::vector<std::uint16_t> labels;  ///< width * height, row-major
};
LabelImage readLabels(const std::string& path, const std::string& source, const std::string& field, int width, int height,
                      const std::string& map_image);

/// The polygons of the cells where `mask` is non-zero (4-connected components), in metres with
/// the image's lower-left corner at (0, 0) and `resolution` metres per pixel, each simplified
/// within `tolerance` (topology kept). Sorted by their pixels' area, largest first; components
/// that simplification leaves empty are counted in `lost`. polygonizeLabels does the same with
/// the 4-connected runs of each non-zero label, and says which label each polygon has.
struct Components {
  std::vector<RawPolygon> polygons;
  std::vector<double> pixel_areas;  ///< each polygon's area before simplification (pixels * r^2)
  std::vector<int> values;          ///< each polygon's cell value (a mask's: 1)
  std::size_t lost = 0;
  double lost_area = 0.0;
  std::vector<int> lost_values;  ///< the cell value of each component simplification left empty
};
Components polygonizeMask(const std::vector<std::uint8_t>& mask, int width, int height, double resolution,
                          double tolerance, const std::string& source);
Components polygonizeLabels(const std::vector<std::uint16_t>& labels, int width, int height, double resolution,
                            double tolerance, const std::string& source);

}  // namespace coverbench::import_detail
