#pragma once
// The rooms of a map (`dataset import MAP.yaml --rooms SEGMENTATION`): the importer's map reader
// (wall_import.cpp) hands its free cells to readRooms (map_rooms.cpp), which makes a polygon of
// each labelled room through the same GDAL plug-in and vectoriser as the map's free space.

#include <string>
#include <vector>

#include "gdal_plugin.hpp"

namespace coverbench::import_detail {

/// The GDAL plug-in, opened by the first call (wall_import.cpp).
const GdalApi& gdal();

/// Refuses a path that is not valid UTF-8, which the manifest could not record, or that holds a
/// control character (a line break would split the one line of an error or a summary)
/// (`source`: `field`).
void requireUtf8Path(const std::string& path, const std::string& source, const std::string& field);

/// One polygon per kept room of the segmentation image `segmentation` (read in `map_path`'s
/// errors as field "--rooms"), in label order, in the map image's frame (lower-left corner at
/// (0, 0)), named `stem`-room-LABEL; `report` says what each room kept and dropped. Adds the
/// image to `extra_sources`. Throws InputError before anything is returned.
RawSet readRooms(const std::string& map_path, const std::string& image_path, const std::string& stem, FreeMask mask,
                 double resolution, double tolerance, const ImportOptions& options, std::vector<ImportedSource>& extra_sources,
                 RoomsReport& report);

/// The manifest's "rooms" object: the totals on one line, then a line per label.
std::string roomsRecordJson(const RoomsReport& report);

}  // namespace coverbench::import_detail
