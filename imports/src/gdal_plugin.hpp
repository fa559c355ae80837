#pragma once
// GDAL is loaded only by the commands that import (issue: start-up in milliseconds): gdal_io.cpp
// is built as a plug-in, libcoverbench_gdal.so, which the importer opens on first use
// (wall_import.cpp, through openPlugin: coverbench/plugin.hpp). The plug-in asks nothing of the program that opens it but these functions,
// passed to it when it is opened, so it opens the same way in the command, the tests and the
// Python module (whose symbols no plug-in can see).

#include <string>

#include "gdal_io.hpp"

namespace coverbench::import_detail {

/// What the plug-in uses of CoverBench's own code.
struct GdalHost {
  /// Throws InputError(source, field, problem): the importer's one way to refuse.
  void (*input_error)(const std::string& source, const std::string& field, const std::string& problem);
  bool (*point_in_ring)(Point p, const Ring& ring);
  std::string (*short_number)(double v);
};

/// What the plug-in offers: gdal_io.hpp's functions.
struct GdalApi {
  int abi;  ///< kGdalPluginAbi of the plug-in's build
  RawSet (*read_vector_file)(const std::string& path, const std::string& format, const ImportOptions& options);
  RawSet (*read_dxf_file)(const std::string& path, const ImportOptions& options);
  RawSet (*read_wkt_text)(const std::string& text, const std::string& source, const ImportOptions& options);
  void (*place_bare_set)(RawSet& set, const std::string& source, const ImportOptions& options);
  FreeMask (*read_free_cells)(const std::string& path, const std::string& source, const std::string& field, const MapRule& rule,
                              double resolution);
  Components (*polygonize_mask)(const std::vector<std::uint8_t>& mask, int width, int height, double resolution, double tolerance,
                                const std::string& source);
  LabelImage (*read_labels)(const std::string& path, const std::string& source, const std::string& field, int width, int height,
                            const std::string& map_image);
  Components (*polygonize_labels)(const std::vector<std::uint16_t>& labels, int width, int height, double resolution,
                                  double tolerance, const std::string& source);
};

/// Changes whenever GdalHost, GdalApi or the types they pass change: a plug-in of another build
/// is refused, not called.
inline constexpr int kGdalPluginAbi = 2;

/// The plug-in's one exported symbol: const void* coverbench_gdal_plugin(const void* host), which
/// takes a GdalHost and returns a GdalApi.
inline constexpr const char* kGdalPluginEntry = "coverbench_gdal_plugin";

}  // namespace coverbench::import_detail
