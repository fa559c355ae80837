#pragma once
/// SVG pictures of a wall and a path: wall, obstacles, free region, swept band, coverage layer
/// (uncovered reachable area, areas passed twice or more), path (tool on solid, transit dashed, a
/// gantry's lifted moves dotted in purple),
/// start and end, segments that fail the exact check. Scaled to a fixed picture size so a 20 m facade and a
/// 1 m strip are equally readable; a scale bar gives metres.

#include <string>
#include <vector>

#include "coverbench/deposition.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/motion.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

struct SvgContent {
  const Wall* wall = nullptr;
  ToolParams tool;
  VehicleModel vehicle;  ///< a gantry's tool-off moves are drawn as lifted
  const Region* free = nullptr;  ///< optional: the free centre region F
  const Path* path = nullptr;    ///< optional
  /// optional coverage layer: R, drawn in red where the tool's band does not pass (an SVG mask of
  /// the painted runs stroked at the tool's width, which is S exactly)
  const Region* reachable = nullptr;
  const Region* overlap = nullptr;    ///< optional coverage layer: passed over twice or more
  /// optional pass-count layers over `overlap`: passed over three times or more, four or more
  const Region* three_passes = nullptr;
  const Region* four_passes = nullptr;
  /// optional: indices of segments that fail the exact validity check, drawn in red over the
  /// path; the picture's frame grows to hold every waypoint, so a path that leaves the wall is seen.
  const std::vector<std::size_t>* violating = nullptr;
  std::string title;
};

std::string renderSvg(const SvgContent& content);

/// The size in pixels of a picture of `path` (optional) on `wall`: its SVG's width and height.
struct PictureSize {
  double width = 0.0, height = 0.0;
};
PictureSize pictureSize(const Wall& wall, const Path* path);

/// The picture of a path on its wall with the free region, and (with `coverage_layer`, for a
/// path that can be scored) the coverage layer and the segments that fail the exact check.
/// The overlap layer is drawn with at most `overlap_strips` scanline strips over the wall's
/// height (1500: finer than the picture's pixels; galleries of thumbnails use fewer). Segments
/// before `first_judged_segment` are not marked (a repaired path's executed part, driven before
/// the obstacles appeared, is judged on the wall it had then).
/// With `pass_counts`, the overlap is drawn by pass count (2, 3, 4 or more) in three shades.
std::string pathPicture(const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle, const Path& path,
                        const std::string& title, bool coverage_layer = true, double overlap_strips = 1500.0,
                        std::size_t first_judged_segment = 0, bool pass_counts = false);

/// The coat a path leaves (deposition.hpp; the tool must have a flux profile): the wall with R's
/// thickness in blocks about 3 px wide, each coloured by its mean's ratio to R's mean (blues
/// thinner than 0.9, green within 10 %, oranges to dark red thicker than 1.1), obstacles on top,
/// a colour scale in micrometres and the five metrics. The blocks are rectangles, or with
/// `as_image` one embedded PNG of a pixel a block, drawn unsmoothed: the same picture in a file
/// tens of times smaller (the report's gallery and the explorer use it). Throws as deposition() does.
std::string coatPicture(const Wall& wall, const ToolParams& tool, const Path& path, const MotionLimits& limits,
                        const VehicleModel& vehicle, const std::string& title, bool as_image = false);
/// The same picture from a coat already computed with blocks of coatBlockCells(wall, tool) cells
/// (coat(), or the one computeMetrics hands out), so the metrics and the picture share one computation.
std::string coatPicture(const Wall& wall, const ToolParams& tool, const Coat& coat, const std::string& title,
                        bool as_image = false);
/// The raster cells a block of the coat's picture is wide (about 3 px at the picture's scale).
std::size_t coatBlockCells(const Wall& wall, const ToolParams& tool);

/// The data that plays a picture's path back in place (reports/python/coverbench_report/player.js):
/// a script calling coverbenchPlayback({...}) with the path in the picture's pixels (the frame
/// of pathPicture), the tool's width, and when the time model has the tool at each waypoint.
/// x, y and t are integers, each the step from the one before (x and y in tenths of a pixel, t
/// in hundredths of a second), as base-64 varints (svg.cpp's varints); `waits` lists [segment,
/// hundredths of a second] a gantry waits before a segment, `arcs` [segment, bulge in millionths,
/// signed as the picture turns], `on` one digit per segment.
std::string playbackScript(const std::string& id, const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle,
                           const Path& path, const MotionLimits& limits);

}  // namespace coverbench
