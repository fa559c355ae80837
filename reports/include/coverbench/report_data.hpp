#pragma once
/// What a report needs beyond the results (records.hpp): the gallery of pictured walls, and the
/// report's data file
/// (report_data.json) that the analysis (reports/python) reads. Measurement and storage are
/// C++; statistics, plots and pages are the analysis' (docs/report.md).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/published.hpp"
#include "coverbench/records.hpp"

namespace coverbench {

/// One picture of the gallery: the run of one planner column on one wall.
struct GalleryPicture {
  std::string column, key, status;
  std::string file;  ///< relative to the report folder, set when drawn
  std::string note;  ///< what the picture leaves out, if anything
  std::string playback;  ///< its path's playback data (a script), relative to the report folder; empty: none
  long long width = 0, height = 0;  ///< the picture's size in pixels (the page reserves it before loading), set when drawn
  /// The coat's picture (a tool with a flux profile, a scorable path), relative to the report
  /// folder, and its size in pixels; empty: none (report_data.json then has no coat keys).
  std::string coat;
  long long coat_width = 0, coat_height = 0;
};
/// One pictured wall: why it was chosen and every column's run on it.
struct GalleryWall {
  std::string wall, wall_name, why;
  std::vector<GalleryPicture> pictures;
};
struct GallerySection {
  std::string title;
  std::vector<GalleryWall> walls;
};

/// The walls a report pictures, per dataset: the median wall (the baseline's length_ratio at the
/// dataset's median) and each column's worst wall (a failure or invalid path first, then the
/// lowest coverage of the reachable area, then the highest overlap), each wall once.
std::vector<GallerySection> selectGallery(const ResultSet& results, const std::vector<std::string>& dataset_order);

/// report_data.json: the record, the metric registry, every run (metrics as numbers, null when
/// not measured or infinite) and the gallery. Same inputs, same bytes.
/// With `published`, also its values and clock (key `published`; absent without, so such reports
/// stay as they were).
std::string reportDataJson(const ResultSet& results, const ExperimentRecord& record,
                           const std::vector<GallerySection>& gallery, const PublishedTable* published = nullptr);

}  // namespace coverbench
