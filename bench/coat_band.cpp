// Where a coat is uneven (docs/deposition.md, "Where the coat is uneven"): a plan file's coat, with
// the plan's tool and flux profile and the default time model, split between the band of the
// reachable region R within r (the tool's radius) of R's edge, where only a fan's outer half can
// reach, and the rest of R. One JSON line per plan:
//   build/bench/coverbench_coat_band WALL.json PLAN.json [WALL.json PLAN.json ...]
// The raster is the metrics' (the same cells, Gauss points and values); a wall whose raster is
// past kCoatBandSamples is refused (this tool holds it whole).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "coverbench/deposition.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/wall_file.hpp"

namespace {

using namespace coverbench;

void split(const std::string& wall_file, const std::string& plan_file) {
  const Wall wall = loadWallFile(wall_file);
  const LoadedPlan plan = loadPlanFile(plan_file);
  if (!plan.tool_width || !plan.profile) throw std::runtime_error(plan_file + ": needs tool_width and profile");
  ToolParams tool{*plan.tool_width, plan.clearance.value_or(0.0)};
  tool.profile = *plan.profile;
  const Region reachable = reachableRegion(wall, tool);
  const Region inner = offsetRegion(reachable, -tool.radius(), kMetricArcTolerance);
  const Box box = boundingBox(reachable);
  DepositionGrid grid;
  grid.cell = depositionCell(tool, tool.profile);
  grid.gauss = true;
  grid.x0 = box.min_x;
  grid.y0 = box.min_y;
  grid.nx = 2 * static_cast<std::size_t>(std::ceil(box.width() / grid.cell));
  grid.ny = 2 * static_cast<std::size_t>(std::ceil(box.height() / grid.cell));
  if (grid.nx * grid.ny > kCoatBandSamples) throw std::runtime_error(wall_file + ": raster past kCoatBandSamples");
  depositionField(plan.path, tool, tool.profile, segmentSpeeds(plan.path), MotionLimits{}.speed, grid);
  const std::vector<char> all = rasterMask(reachable, grid), in = rasterMask(inner, grid);
  std::vector<char> band(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) band[k] = all[k] && !in[k];
  const double target = tool.profile.target;
  const Deposition whole = depositionStats(grid, all, target), edge = depositionStats(grid, band, target),
                   rest = depositionStats(grid, in, target);
  std::printf(
      "{\"wall\": \"%s\", \"reachable_area\": %.6g, \"band_share\": %.6g, \"even_share\": %.6g, \"band\": {\"even\": %.6g, "
      "\"thin\": %.6g, \"thick\": %.6g}, \"rest\": {\"even\": %.6g, \"thin\": %.6g, \"thick\": %.6g}}\n",
      wall.name.c_str(), area(reachable), static_cast<double>(edge.cells) / static_cast<double>(whole.cells), whole.even_share,
      edge.even_share, edge.thin_share, edge.thick_share, rest.even_share, rest.thin_share, rest.thick_share);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc % 2 == 0) {
    std::fprintf(stderr, "usage: %s WALL.json PLAN.json [WALL.json PLAN.json ...]\n", argv[0]);
    return 2;
  }
  try {
    for (int i = 1; i + 1 < argc; i += 2) split(argv[i], argv[i + 1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coverbench_coat_band: %s\n", e.what());
    return 1;
  }
  return 0;
}
