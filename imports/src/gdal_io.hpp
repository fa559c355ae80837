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

/// A grey image (PGM, PNG; colour channels averaged as map_server does), row 0 at the top.
struct GreyImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> values;  ///< width * height, row-major
};
GreyImage readGreyImage(const std::string& path, const std::string& source, const std::string& field);

/// The polygons of the cells where `mask` is non-zero (4-connected components), in metres with
/// the image's lower-left corner at (0, 0) and `resolution` metres per pixel, each simplified
/// within `tolerance` (topology kept). Sorted by area, largest first.
std::vector<RawPolygon> polygonizeMask(const std::vector<std::uint8_t>& mask, int width, int height, double resolution,
                                       double tolerance, const std::string& source);

}  // namespace coverbench::import_detail
