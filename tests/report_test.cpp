// The metric registry and the report data: one home for metric metadata, checked against the
// engine, the docs and the database; the gallery's choice of walls; pictures that show a path's
// failures.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "coverbench/metric_spec.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/report_data.hpp"
#include "coverbench/svg.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

TEST(MetricRegistry, ListsExactlyTheEngineMetricsInOrderThenTheMeasuredOnes) {
  Wall wall;
  wall.name = "w";
  wall.boundary = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  Path path;
  path.waypoints = {{0.2, 0.5}, {1.8, 0.5}};
  path.tool_on = {true};
  std::vector<std::string> engine;
  for (const NamedMetric& m : flatten(computeMetrics(wall, ToolParams{0.1, 0.02}, path))) engine.push_back(m.name);
  std::vector<std::string> registry, measured;
  for (const MetricSpec& s : metricSpecs()) (s.kind == MetricKind::Measured ? measured : registry).push_back(s.name);
  EXPECT_EQ(engine, registry);
  EXPECT_EQ(measured, (std::vector<std::string>{"plan_time_ms", "peak_memory_bytes"}));
  std::set<std::string> names;
  for (const MetricSpec& s : metricSpecs()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name << " twice";
    EXPECT_FALSE(s.description.empty()) << s.name;
    EXPECT_FALSE(s.unit.empty()) << s.name;
    EXPECT_GE(s.tie_absolute, 0.0);
    EXPECT_GE(s.tie_relative, 0.0);
    if (s.headline) EXPECT_NE(s.better, 0) << s.name << ": a headline metric needs a direction";
  }
  // The headline is what the issue asks a researcher to see first.
  std::vector<std::string> headline;
  for (const MetricSpec& s : metricSpecs())
    if (s.headline) headline.push_back(s.name);
  EXPECT_EQ(headline, (std::vector<std::string>{"coverage_reachable", "coverage_wall", "overlap", "length_ratio", "turns_30",
                                                "duration_s", "plan_time_ms", "peak_memory_bytes"}));
}

TEST(MetricRegistry, TieBandsByHand) {
  const MetricSpec& coverage = *findMetricSpec("coverage_reachable");  // 0.001 absolute
  EXPECT_TRUE(tied(coverage, 0.9990, 0.9999));
  EXPECT_FALSE(tied(coverage, 0.9980, 0.9999));
  const MetricSpec& time = *findMetricSpec("plan_time_ms");  // 0.05 ms + 25 %
  EXPECT_TRUE(tied(time, 1.0, 1.3));   // 0.3 <= 0.05 + 0.25 * 1.3 = 0.375
  EXPECT_FALSE(tied(time, 1.0, 1.5));  // 0.5 > 0.05 + 0.375
  EXPECT_TRUE(tied(*findMetricSpec("turns_30"), 4, 4));
  EXPECT_FALSE(tied(*findMetricSpec("turns_30"), 4, 5));
  EXPECT_EQ(findMetricSpec("no_such_metric"), nullptr);
}

TEST(MetricRegistry, DocsHoldTheGeneratedTable) {
  std::ifstream in(std::string(COVERBENCH_SOURCE_DIR) + "/docs/metrics.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  const std::string begin = "<!-- metric registry: begin -->\n", end = "<!-- metric registry: end -->";
  const std::size_t a = docs.find(begin), b = docs.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(docs.substr(a + begin.size(), b - a - begin.size()), metricSpecsMarkdown())
      << "docs/metrics.md and the registry disagree: paste `build/coverbench metric-specs` between the markers";
}

ResultRow row(const std::string& column, const std::string& wall, const std::string& status, double coverage,
              double overlap, double ratio) {
  ResultRow r;
  r.planner = r.config = column;
  r.key = column + "-" + wall;
  r.wall = r.wall_name = r.pairing = wall;
  r.dataset = "d";
  r.status = status;
  r.valid = status == "ok" || status == "partial";
  r.metrics = {{"coverage_reachable", coverage}, {"overlap", overlap}, {"length_ratio", ratio}};
  return r;
}

TEST(Gallery, MedianWallAndEachColumnsWorstWallOnce) {
  ResultSet rs;
  rs.baseline = "a";
  rs.planners = {"a", "b", "c"};
  // a's length ratios 1.1, 1.3, 1.2 on w1..w3: median wall w3. a's worst: lowest coverage, w2.
  // b timed out on w1: its worst. c's worst is w2 too (highest overlap at equal coverage).
  rs.runs = {row("a", "w1", "ok", 1.0, 0.1, 1.1),       row("a", "w2", "ok", 0.97, 0.1, 1.3),
             row("a", "w3", "ok", 1.0, 0.1, 1.2),       row("b", "w1", "timeout", NAN, NAN, NAN),
             row("b", "w2", "ok", 1.0, 0.1, 1.0),       row("b", "w3", "ok", 1.0, 0.1, 1.0),
             row("c", "w1", "ok", 1.0, 0.2, 1.0),       row("c", "w2", "ok", 1.0, 0.3, 1.0),
             row("c", "w3", "ok", 1.0, 0.1, 1.0)};
  const std::vector<GallerySection> g = selectGallery(rs, {"d"});
  ASSERT_EQ(g.size(), 1u);
  ASSERT_EQ(g[0].walls.size(), 3u);
  EXPECT_EQ(g[0].walls[0].wall, "w3");
  EXPECT_EQ(g[0].walls[0].why, "median wall (a's length ratio)");
  EXPECT_EQ(g[0].walls[1].wall, "w2");
  EXPECT_EQ(g[0].walls[1].why, "worst for a; worst for c");
  EXPECT_EQ(g[0].walls[2].wall, "w1");
  EXPECT_EQ(g[0].walls[2].why, "worst for b");
  ASSERT_EQ(g[0].walls[2].pictures.size(), 3u);  // every column's run on the wall
  EXPECT_EQ(g[0].walls[2].pictures[1].status, "timeout");
}

TEST(Pictures, FailedSegmentsAreMarkedAndAPathLeavingTheWallStaysInThePicture) {
  Wall wall;
  wall.name = "w";
  wall.boundary = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  Path path;  // the second segment leaves the wall by 1 m
  path.waypoints = {{0.2, 0.5}, {1.8, 0.5}, {3.0, 0.5}};
  path.tool_on = {true, true};
  const Validity v = checkValidity(wall, ToolParams{0.1, 0.02}, path);
  EXPECT_EQ(v.violating, (std::vector<std::size_t>{1}));
  const std::string svg = pathPicture(wall, ToolParams{0.1, 0.02}, path, "t");
  EXPECT_NE(svg.find("class=\"violation\""), std::string::npos);
  EXPECT_NE(svg.find("fails the exact check (1 segments)"), std::string::npos);
  // The frame holds x = 3 m: 3 m across 1000 px gives k = 333.3 px/m, so x = 3 m is drawn at
  // 24 + 3 k = 1024 px (with the wall's frame alone it would be at 24 + 3 * 500 = 1524, outside).
  EXPECT_NE(svg.find("1024.00,"), std::string::npos);
  const std::string clean = pathPicture(wall, ToolParams{0.1, 0.02}, Path{{{0.2, 0.5}, {1.8, 0.5}}, {true}}, "t");
  EXPECT_EQ(clean.find("class=\"violation\""), std::string::npos);
}

}  // namespace
}  // namespace coverbench
