// The metric registry and the report data: one home for metric metadata, checked against the
// engine, the docs and the database; the gallery's choice of walls; pictures that show a path's
// failures.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "coverbench/deposition.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/ompl_export.hpp"
#include "coverbench/report_data.hpp"
#include "coverbench/svg.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

TEST(MetricRegistry, ListsExactlyTheEngineMetricsInOrderThenTheExactJudgesThenTheMeasuredOnes) {
  Wall wall;
  wall.name = "w";
  wall.boundary = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  Path path;
  path.waypoints = {{0.2, 0.5}, {1.8, 0.5}};
  path.tool_on = {true};
  std::vector<std::string> engine;
  MotionLimits with_turn_cost;  // the cost per turn is listed only when set
  with_turn_cost.turn_cost_s = 1.0;
  ToolParams coat{0.1, 0.02};  // the deposition metrics are listed only for a tool with a flux profile
  coat.profile.kind = FluxProfile::Kind::Uniform;
  for (const NamedMetric& m : flatten(computeMetrics(wall, coat, path, {}, with_turn_cost)))
    engine.push_back(m.name);
  for (const char* name : kExactJudgeMetrics) engine.push_back(name);  // an experiment with `judge: exact`
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
    if (s.headline) { EXPECT_NE(s.better, 0) << s.name << ": a headline metric needs a direction"; }
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
  r.status = parseRunStatus(status).value();
  r.valid = hasPath(r.status);
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
  const std::string svg = pathPicture(wall, ToolParams{0.1, 0.02}, VehicleModel{}, path, "t");
  EXPECT_NE(svg.find("class=\"violation\""), std::string::npos);
  EXPECT_NE(svg.find("fails the exact check (1 segments)"), std::string::npos);
  // The frame holds x = 3 m: 3 m across 1000 px gives k = 333.3 px/m, so x = 3 m is drawn at
  // 24 + 3 k = 1024 px (with the wall's frame alone it would be at 24 + 3 * 500 = 1524, outside).
  EXPECT_NE(svg.find("1024.00,"), std::string::npos);
  const std::string clean = pathPicture(wall, ToolParams{0.1, 0.02}, VehicleModel{}, Path{{{0.2, 0.5}, {1.8, 0.5}}, {true}, {}}, "t");
  EXPECT_EQ(clean.find("class=\"violation\""), std::string::npos);
}

TEST(Pictures, TheUncoveredLayerIsReachableAreaMaskedByTheToolsBand) {
  Wall wall;
  wall.name = "w";
  wall.boundary = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  // A painted square loop 1 m across: unpainted are the rim between it and the wall's edge and
  // the patch inside it. Both are red because the red is all of R, hidden only under the band the
  // tool sweeps: the painted runs stroked at the tool's width, round caps and joins (S exactly).
  Path path;
  path.waypoints = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}, {0.5, 0.5}};
  path.tool_on = {true, true, true, true};
  const std::string svg = pathPicture(wall, ToolParams{0.1, 0.02}, VehicleModel{}, path, "t");
  const std::size_t fill = svg.find("\" fill=\"#e8383d\" fill-opacity=\"0.75\" fill-rule=\"evenodd\" stroke=\"none\" mask=\"url(#unswept)\"");
  ASSERT_NE(fill, std::string::npos) << svg;
  const std::size_t start = svg.rfind("<path d=\"", fill);
  const std::string red = svg.substr(start, fill - start);
  // R of an empty 2 m square is one ring: the wall less its clearance, corners rounded by r.
  EXPECT_EQ(std::count(red.begin(), red.end(), 'z'), 1) << red;
  // k = min(1000 / 2, 700 / 2) = 350 px/m: the tool's 0.1 m is 35 px; the mask is the whole picture,
  // 2 x 350 + 2 x 24 px wide and 44 + 700 + 24 + 82 px high.
  EXPECT_NE(svg.find("<mask id=\"unswept\" maskUnits=\"userSpaceOnUse\" x=\"0\" y=\"0\" width=\"748.00\" height=\"850.00\">"
                     "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/><use xlink:href=\"#paint\" fill=\"none\" "
                     "stroke=\"#000000\" stroke-width=\"35.00\" stroke-linecap=\"round\" stroke-linejoin=\"round\"/></mask>"),
            std::string::npos)
      << svg;
  EXPECT_LT(svg.find("<g id=\"paint\">"), svg.find("<mask id=\"unswept\""));
}

TEST(Pictures, PathDataIsTheFirstPointAbsoluteThenStepsInHundredthsOfAPixel) {
  Wall wall;
  wall.name = "w";
  wall.boundary = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  // k = min(1000 / 2, 700 / 1) = 500 px/m, x -> 24 + 500 x, y -> 44 + 500 (1 - y).
  Path path;
  path.waypoints = {{0.2, 0.5}, {1.8, 0.5}, {1.8, 0.7}, {1.20002, 0.61}, {0.2, 0.5}};
  path.tool_on = {true, true, true, false};
  const std::string svg = pathPicture(wall, ToolParams{0.1, 0.02}, VehicleModel{}, path, "t", false);
  // The wall: (24, 544) then level, plumb, level steps and a close.
  EXPECT_NE(svg.find("<path d=\"M24,544h1000v-500h-1000z\""), std::string::npos) << svg;
  // Painted: (124, 294), 800 px right, 100 px up, then to (624.01, 239) as -299.99, +45.
  EXPECT_NE(svg.find("<g id=\"paint\">\n<path d=\"M124,294h800v-100l-299.99,45\"/>"), std::string::npos) << svg;
  // The tool-off run starts where painting ended and steps -500.01 px, +55 px.
  EXPECT_NE(svg.find("<path d=\"M624.01,239l-500.01,55\"/>"), std::string::npos) << svg;

  // Every 64th point is absolute: 70 points 1 cm apart, i.e. 5 px steps from (124, 294).
  Path row;
  for (int i = 0; i < 70; ++i) row.moveTo({0.2 + 0.01 * i, 0.5}, true);
  const std::string long_run = pathPicture(wall, ToolParams{0.1, 0.02}, VehicleModel{}, row, "t", false);
  std::string expected = "<path d=\"M124,294";
  for (int i = 1; i < 70; ++i) expected += i == 64 ? "L444,294" : "h5";
  EXPECT_NE(long_run.find(expected + "\"/>"), std::string::npos) << long_run;
}

/// The player's varints read back (zigzag, 5 bits a character, lowest first, 32 added: more follow).
std::vector<long long> readVarints(const std::string& text) {
  static const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::vector<long long> out;
  unsigned long long z = 0;
  int shift = 0;
  for (char ch : text) {
    const auto c = static_cast<unsigned long long>(digits.find(ch));
    z |= (c & 31u) << shift;
    shift += 5;
    if (c & 32u) continue;
    out.push_back(z % 2 ? -static_cast<long long>((z + 1) / 2) : static_cast<long long>(z / 2));
    z = 0;
    shift = 0;
  }
  return out;
}

TEST(Pictures, PlaybackDataByHand) {
  Wall wall;
  wall.name = "w";
  wall.boundary = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  // x -> 24 + 500 x, y -> 44 + 500 (1 - y) px, as in the picture; 1 m at v = 1 m/s, a = 1 m/s^2
  // takes 2 s (1 / v + v / a), stopping at the right-angle turn.
  Path path;
  path.waypoints = {{0.2, 0.5}, {1.2, 0.5}, {1.2, 0.3}, {0.2, 0.3}};
  path.tool_on = {true, false, true};
  MotionLimits limits;
  limits.speed = 1.0;
  limits.acceleration = 1.0;
  const std::string js = playbackScript("gallery/a.js", wall, ToolParams{0.1, 0.02}, VehicleModel{}, path, limits);
  ASSERT_EQ(js.rfind("coverbenchPlayback(", 0), 0u);
  const auto d = nlohmann::json::parse(js.substr(19, js.size() - 19 - 3));
  EXPECT_EQ(d["id"], "gallery/a.js");
  EXPECT_EQ(d["size"], nlohmann::json::array({1048.0, 44 + 500 + 24 + 82}));
  EXPECT_DOUBLE_EQ(d["tool_px"].get<double>(), 50.0);
  EXPECT_EQ(d["on"], "101");
  // Tenths of a pixel: (124, 294), (624, 294), (624, 394), (124, 394), as steps.
  EXPECT_EQ(readVarints(d["x"]), (std::vector<long long>{1240, 5000, 0, -5000}));
  EXPECT_EQ(readVarints(d["y"]), (std::vector<long long>{2940, 0, 1000, 0}));
  // Hundredths of a second: 1 m in 2 s; 0.2 m (under v^2 / a) in 2 sqrt(0.2) = 0.894 s; 1 m in 2 s.
  EXPECT_EQ(readVarints(d["t"]), (std::vector<long long>{0, 200, 89, 200}));
  EXPECT_EQ(d["end_cs"], 489);
  EXPECT_EQ(d["waits"], nlohmann::json::array());
  EXPECT_EQ(d["model"], limits.describe());
  EXPECT_EQ(d["bad"], nlohmann::json::array());  // a valid path: nothing marked
  // A window under the second painted pass (y = 0.3): that segment (2) is marked, and only it.
  Wall windowed = wall;
  windowed.obstacles.push_back(Obstacle{ObstacleType::Rect, {{0.5, 0.25}, {0.7, 0.25}, {0.7, 0.35}, {0.5, 0.35}}, {}, 0.0, "window"});
  const std::string marked = playbackScript("gallery/b.js", windowed, ToolParams{0.1, 0.02}, VehicleModel{}, path, limits);
  EXPECT_EQ(nlohmann::json::parse(marked.substr(19, marked.size() - 19 - 3))["bad"], nlohmann::json::array({2}));
  // Negative steps of every size read back.
  Path zig;
  for (int i = 0; i < 40; ++i) zig.moveTo({0.1 + 0.045 * i, i % 2 ? 0.1 : 0.9 - 0.02 * i}, true);
  const auto z = nlohmann::json::parse(
      [&] { const std::string s = playbackScript("z", wall, ToolParams{0.1, 0.02}, VehicleModel{}, zig, limits); return s.substr(19, s.size() - 22); }());
  long long y = 0;
  std::size_t i = 0;
  for (long long step : readVarints(z["y"])) {
    y += step;
    EXPECT_EQ(y, std::llround((44 + 500 * (1 - zig.waypoints[i].y)) * 10)) << i;
    ++i;
  }
  EXPECT_EQ(i, zig.waypoints.size());
}

}  // namespace
}  // namespace coverbench

namespace coverbench {
namespace {

TEST(OmplExport, ALogByHandForTwoRunsOneOfThemFailed) {
  ResultSet rs;
  rs.experiment = "e";
  rs.planners = {"zigzag"};
  rs.metric_order = {"valid", "coverage_reachable", "plan_time_ms", "peak_memory_bytes"};
  ResultRow ok;
  ok.planner = ok.config = "zigzag";
  ok.key = "k1";
  ok.wall_name = "wall; one";
  ok.tool = ToolParams{0.1, 0.02};
  ok.dataset = "fam";
  ok.wall = "w1";
  ok.status = RunStatus::Partial;
  ok.valid = true;
  ok.metrics = {{"valid", 1.0}, {"coverage_reachable", 0.75}, {"plan_time_ms", 2.5}, {"peak_memory_bytes", 3145728.0}};
  ResultRow failed = ok;
  failed.key = "k2";
  failed.wall_name = "two";
  failed.wall = "w2";
  failed.status = RunStatus::Timeout;
  failed.valid = false;
  failed.metrics = {{"plan_time_ms", 1500.0}};
  ResultRow other = ok;  // another dataset: its own log
  other.dataset = "suite";
  other.key = "k3";
  rs.runs = {ok, failed, other};
  ExperimentRecord rec;
  rec.name = "my exp";
  rec.config_hash = "abc";
  rec.config_text = "name: my exp\n";
  rec.facts = {{"host", "node 7"}, {"started (UTC)", "2026-11-23T10:00:00Z"}, {"CPU", "X"}, {"cores", "2"},
               {"OS", "Linux"}, {"memory", "1.0 GiB"}};
  rec.datasets = {{"fam", "family fam", "", 2}, {"suite", "suite s", "", 1}};
  rec.planners = {{"zigzag", "zigzag", "overlap=0, sweep_angle=90"}};
  OmplLogSettings settings;
  settings.time_limit_s = 60;
  settings.memory_limit_mb = 2048;
  settings.seed = 1;
  const std::vector<OmplLog> logs = omplBenchmarkLogs(rs, rec, settings);
  ASSERT_EQ(logs.size(), 2u);
  EXPECT_EQ(logs[0].file_name, "my_exp.fam.log");
  EXPECT_EQ(logs[1].file_name, "my_exp.suite.log");
  EXPECT_EQ(logs[0].runs, 2u);
  const std::string expected =
      "CoverBench version " COVERBENCH_TEST_VERSION "\n"
      "Experiment my_exp.fam\n"
      "6 experiment properties\n"
      "dataset STRING = fam\n"
      "walls INTEGER = 2\n"
      "tool_widths STRING = 0.1\n"
      "clearances STRING = 0.02\n"
      "config_sha256 STRING = abc\n"
      "coverbench_experiment STRING = my exp\n"
      "Running on node_7\n"
      "Starting at 2026-11-23T10:00:00Z\n"
      "<<<|\nname: my exp\n|>>>\n"
      "<<<|\nCPU: X\ncores: 2\nOS: Linux\nmemory: 1.0 GiB\n|>>>\n"
      "1 is the random seed\n"
      "60 seconds per run\n"
      "2048 MB per run\n"
      "2 runs per planner\n"
      "1.5025 seconds spent to collect the data\n"
      "1 enum types\n"
      "run_status|ok|partial|no_reachable_area|invalid_input|timeout|memory_limit|crash|error|invalid_output|metrics_error\n"
      "1 planners\n"
      "zigzag\n"
      "5 common properties\n"
      "planner = zigzag\noverlap = 0\nsweep_angle = 90\ntool_width = 0.1\nclearance = 0.02\n"
      "9 properties for each run\n"
      "time REAL\nmemory REAL\nsolved BOOLEAN\napproximate solution BOOLEAN\nrun_status ENUM\nvalid BOOLEAN\n"
      "coverage_reachable REAL\nwall STRING\nrun_key STRING\n"
      "2 runs\n"
      "0.0025; 3; 1; 1; 1; 1; 0.75; wall, one; k1; \n"
      "1.5; nan; 0; 0; 4; nan; nan; two; k2; \n"
      ".\n";
  EXPECT_EQ(logs[0].text, expected);
}

/// Two rows of a uniform tool (s = 0.5 m) that tile a 2 x 1 m wall exactly.
struct TwoRows {
  Wall wall;
  ToolParams tool{0.5, 0.0};
  Path path;
  TwoRows() {
    wall.name = "two rows";
    wall.boundary = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    tool.profile.kind = FluxProfile::Kind::Uniform;
    path.moveTo({0.25, 0.25}, false);
    path.moveTo({1.75, 0.25}, true);
    path.moveTo({1.75, 0.75}, true);
    path.moveTo({0.25, 0.75}, true);
  }
};

// The coat's picture: its blocks' colours are the shares the metrics state (a uniform tool whose
// two passes tile a wall exactly: green where both rows run at speed, thicker where the tool
// brakes and turns, bare blue nowhere inside R but at the corners the rows' caps do not reach),
// and its scale and figures in micrometres.
TEST(CoatPicture, ShowsTheCoatByItsRatioToTheMeanWithItsScaleAndFigures) {
  TwoRows rows;
  const Wall& wall = rows.wall;
  ToolParams& tool = rows.tool;
  const Path& path = rows.path;
  const std::string svg = coatPicture(wall, tool, path, MotionLimits{}, VehicleModel{}, "t");
  const Deposition d = deposition(wall, tool, path, tool.profile);
  ASSERT_GT(d.even_share, 0.3);
  ASSERT_GT(d.thick_share, 0.0);
  EXPECT_NE(svg.find("<g class=\"coat\""), std::string::npos);
  EXPECT_NE(svg.find("fill=\"#41ab5d\""), std::string::npos);  // within 10 %
  EXPECT_NE(svg.find("coat thickness, \u00b5m (green: within 10 % of the mean)"), std::string::npos);
  char figures[200];
  std::snprintf(figures, sizeof figures, "CV %.2f; within 10 %%: %.2f %%", d.cv, 100.0 * d.even_share);
  EXPECT_NE(svg.find(figures), std::string::npos) << figures;
  // The scale's ticks: 0, 0.9, 1.1 and 2 times the mean, in micrometres to a tenth.
  for (double r : {0.9, 1.1}) {
    const std::string tick = ">" + shortNumber(std::round(r * d.mean_um * 10.0) / 10.0) + "</text>";
    EXPECT_NE(svg.find(tick), std::string::npos) << tick;
  }
  // As one image (the gallery's and the explorer's): a PNG of a pixel a block in place of the
  // rectangles, the rest of the picture the same; from a raster already computed, the same bytes.
  const std::string image = coatPicture(wall, tool, path, MotionLimits{}, VehicleModel{}, "t", true);
  auto coatGroup = [](const std::string& text) {
    const std::size_t from = text.find("<g class=\"coat\""), to = text.find("</g>", from);
    return std::make_pair(text.substr(0, from) + text.substr(to), text.substr(from, to - from));
  };
  EXPECT_EQ(coatGroup(image).first, coatGroup(svg).first);
  EXPECT_NE(coatGroup(image).second.find("href=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // the PNG signature
  EXPECT_EQ(coatGroup(image).second.find("<rect"), std::string::npos);
  EXPECT_NE(coatGroup(svg).second.find("<rect"), std::string::npos);
  EXPECT_EQ(coatPicture(wall, tool, coat(wall, tool, path, tool.profile, {}, {}, coatBlockCells(wall, tool)), "t", true), image);
  // No profile: no picture.
  EXPECT_THROW(coatPicture(wall, ToolParams{0.5, 0.0}, path, MotionLimits{}, VehicleModel{}, "t"), std::exception);
}

// With a target thickness the blocks' ratios, the scale's ticks and its label are of the target,
// and the figures are the metrics' (shares of the target). The rows' steady coat is Q / (s v) =
// 1e-6 / (0.5 x 0.3) m = 6.667 um: aimed at it, the rows at speed are green; aimed at ten times
// the mean, no block is within 10 % of it.
TEST(CoatPicture, WithATargetTheColoursAndTheScaleAreOfTheTarget) {
  TwoRows rows;
  const Wall& wall = rows.wall;
  ToolParams& tool = rows.tool;
  const Path& path = rows.path;
  const double mean_um = deposition(wall, tool, path, tool.profile).mean_um;
  tool.profile.target = 1e6 * tool.profile.rate / (0.5 * 0.3);
  // The blocks (the coat's group; the scale below it has green too).
  auto blocks = [](const std::string& svg) {
    const std::size_t from = svg.find("<g class=\"coat\""), to = svg.find("</g>", from);
    return svg.substr(from, to - from);
  };
  const std::string steady = coatPicture(wall, tool, path, MotionLimits{}, VehicleModel{}, "t");
  EXPECT_NE(blocks(steady).find("fill=\"#41ab5d\""), std::string::npos);
  EXPECT_NE(steady.find("(green: within 10 % of the target, " + shortNumber(tool.profile.target) + " \u00b5m)"), std::string::npos);
  tool.profile.target = 10.0 * mean_um;
  const std::string far = coatPicture(wall, tool, path, MotionLimits{}, VehicleModel{}, "t");
  const Deposition d = deposition(wall, tool, path, tool.profile);
  EXPECT_EQ(d.mean_um, mean_um);
  EXPECT_EQ(d.even_share, 0.0);
  EXPECT_EQ(d.thin_share, 1.0);
  EXPECT_EQ(blocks(far).find("fill=\"#41ab5d\""), std::string::npos);
  EXPECT_NE(blocks(far).find("<rect"), std::string::npos);
  EXPECT_NE(far.find("within 10 % of the target, " + shortNumber(10.0 * mean_um) + " \u00b5m)"), std::string::npos);
  EXPECT_EQ(far.find("of the mean"), std::string::npos);
  for (double r : {0.9, 1.1, 2.0}) {
    const std::string tick = ">" + shortNumber(std::round(r * 10.0 * mean_um * 10.0) / 10.0);
    EXPECT_NE(far.find(tick), std::string::npos) << tick;
  }
  EXPECT_NE(far.find("within 10 %: 0.00 %, thinner: 100.00 %"), std::string::npos);
  EXPECT_NE(far.find(", target " + shortNumber(10.0 * mean_um) + " \u00b5m:</text>\n<text x=\"0\" y=\"66\">mean "), std::string::npos);
}

}  // namespace
}  // namespace coverbench
