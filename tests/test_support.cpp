#include "test_support.hpp"

#include "coverbench/workspace.hpp"

#include <sqlite3.h>

#include <unistd.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include "coverbench/clearance.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"

namespace coverbench::test {

std::string sourcePath(const std::string& relative) { return std::string(COVERBENCH_SOURCE_DIR) + "/" + relative; }

void TempDirTest::SetUp() {
  dir_ = std::filesystem::temp_directory_path() /
         ("coverbench_" + std::to_string(::getpid()) + "_" + testing::UnitTest::GetInstance()->current_test_suite()->name() +
          "_" + testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir_);
  std::filesystem::create_directories(dir_);
}

void TempDirTest::TearDown() { std::filesystem::remove_all(dir_); }

CommandRun CommandTest::run(const std::string& args, std::string* out) {
  const std::string err_file = (dir_ / "stderr.txt").string(), out_file = (dir_ / "stdout.txt").string();
  const std::string cmd = std::string(COVERBENCH_BINARY) + " " + args + " > " + out_file + " 2> " + err_file;
  const int status = std::system(cmd.c_str());
  if (out) *out = slurp(out_file);
  return {WEXITSTATUS(status), slurp(err_file)};
}

std::string CommandTest::slurp(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string CommandTest::write(const std::string& name, const std::string& text) {
  const std::filesystem::path p = dir_ / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string sqlRows(const std::string& database, const std::string& sql) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(database.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr), SQLITE_OK) << database;
  // A runner may be writing it (tests poll a shard while it runs): wait for its transaction
  // instead of failing at once with "database is locked".
  sqlite3_busy_timeout(db, 10000);
  std::string out;
  sqlite3_stmt* s = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK) << sql << ": " << sqlite3_errmsg(db);
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
    for (int c = 0; c < sqlite3_column_count(s); ++c) {
      const unsigned char* t = sqlite3_column_text(s, c);
      out += (c ? "|" : "") + std::string(t ? reinterpret_cast<const char*>(t) : "NULL");
    }
    out += "\n";
  }
  EXPECT_EQ(rc, SQLITE_DONE) << sql << ": " << sqlite3_errmsg(db);
  sqlite3_finalize(s);
  sqlite3_close(db);
  return out;
}

int storedRuns(const std::string& database) {
  if (!std::filesystem::exists(database) ||
      sqlRows(database, "SELECT COUNT(*) FROM sqlite_master WHERE name = 'runs'") != "1\n")
    return -1;
  return std::stoi(sqlRows(database, "SELECT COUNT(*) FROM runs"));
}

std::string dumpRuns(const std::string& database) {
  std::string out;
  for (const char* sql : {"PRAGMA integrity_check", "SELECT COUNT(*), COUNT(DISTINCT key) FROM runs",
                          "SELECT key, status, valid, reason FROM runs ORDER BY key",
                          "SELECT run_key, name, quote(value) FROM metrics ORDER BY run_key, name",
                          "SELECT run_key, name, quote(value) FROM planner_stats ORDER BY run_key, name",
                          "SELECT run_key, waypoints, hex(data) FROM paths ORDER BY run_key"})
    out += sqlRows(database, sql);
  return out;
}

std::vector<std::string> conformanceWallFiles() {
  std::vector<std::string> files;
  for (const char* dir : {"datasets/canonical", "datasets/conformance"})
    for (const auto& e : std::filesystem::directory_iterator(sourcePath(dir)))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

Wall rectWall(double width, double height, std::vector<Obstacle> obstacles) {
  Wall w;
  w.name = "test";
  w.boundary = {{0, 0}, {width, 0}, {width, height}, {0, height}};
  w.obstacles = std::move(obstacles);
  return w;
}

Obstacle rect(double x, double y, double w, double h) {
  Obstacle o;
  o.type = ObstacleType::Rect;
  o.polygon = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
  return o;
}

PlanResult planWith(const std::string& planner, const Wall& wall, const ToolParams& tool,
                    const std::vector<std::pair<std::string, std::string>>& settings) {
  const PlannerInfo& info = findPlanner(planner);
  Problem problem;
  problem.wall = &wall;
  problem.tool = tool;
  problem.params = resolveParams(info, settings);
  return runPlanner(info, problem, Budget());
}

Wall turnedRectWall(double width, double height, double degrees) {
  Wall wall;
  wall.name = "turned";
  const double c = std::cos(degrees * M_PI / 180.0), sn = std::sin(degrees * M_PI / 180.0);
  for (const Point p : {Point{0, 0}, Point{width, 0}, Point{width, height}, Point{0, height}})
    wall.boundary.push_back({p.x * c - p.y * sn + 1.0, p.x * sn + p.y * c});
  return wall;
}

Obstacle circle(double x, double y, double radius) {
  Obstacle o;
  o.type = ObstacleType::Circle;
  o.center = {x, y};
  o.radius = radius;
  return o;
}

Wall randomWall(unsigned seed) {
  std::mt19937 rng(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const double w = uniform(1.0, 8.0), h = uniform(1.0, 4.0);
  Wall wall = rectWall(w, h);
  wall.name = "random-" + std::to_string(seed);
  if (seed % 3 == 0) {  // a gable or a sloped top: a polygon boundary
    const double peak = h + uniform(0.3, 1.5);
    wall.boundary = {{0, 0}, {w, 0}, {w, h}, {uniform(0.2, 0.8) * w, peak}, {0, h}};
  }
  const int count = std::uniform_int_distribution<int>(0, 6)(rng);
  for (int i = 0; i < count; ++i) {
    const double x = uniform(-0.2, w), y = uniform(-0.2, h);
    switch (std::uniform_int_distribution<int>(0, 2)(rng)) {
      case 0: wall.obstacles.push_back(rect(x, y, uniform(0.05, 1.5), uniform(0.05, 1.5))); break;
      case 1: wall.obstacles.push_back(circle(x, y, uniform(0.03, 0.6))); break;
      default: {
        Obstacle o;
        o.type = ObstacleType::Polygon;
        const double size = uniform(0.1, 0.8), turn = uniform(0, M_PI);
        for (int k = 0; k < 3; ++k)
          o.polygon.push_back({x + size * std::cos(turn + 2.1 * k), y + size * std::sin(turn + 2.1 * k)});
        if (signedArea(o.polygon) < 0) std::reverse(o.polygon.begin(), o.polygon.end());
        wall.obstacles.push_back(o);
      }
    }
  }
  // Keep only obstacles the validator accepts (inside the wall, something left to cover).
  Wall kept = wall;
  kept.obstacles.clear();
  for (const Obstacle& o : wall.obstacles) {
    Wall trial = kept;
    trial.obstacles.push_back(o);
    try {
      validateWall(trial, wall.name);
      kept = trial;
    } catch (const InputError&) {
    }
  }
  return kept;
}

testing::AssertionResult isValidPath(const Wall& wall, const ToolParams& tool, const Path& path,
                                     const VehicleModel& vehicle) {
  if (path.waypoints.empty()) return testing::AssertionFailure() << "path has no waypoints";
  if (path.tool_on.size() + 1 != path.waypoints.size())
    return testing::AssertionFailure() << "tool_on has " << path.tool_on.size() << " entries for "
                                       << path.waypoints.size() << " waypoints";
  for (const Point& p : path.waypoints)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return testing::AssertionFailure() << "non-finite waypoint";
  // The exact judge first: it shares no code with the planners (or with the fast engine, whose
  // ClearanceField is also the planners' collision check), and has no tolerance.
  const judge::ExactValidity exact = judge::judgeValidity(wall, tool, path, vehicle);
  if (!exact.valid) {
    const std::size_t i = exact.violating.front();
    const Point a = path.waypoints[i], b = path.waypoints[std::min(i + 1, path.waypoints.size() - 1)];
    return testing::AssertionFailure() << "the exact judge finds " << exact.violations << " violating segments ("
                                       << exact.outside_boundary << " leave the wall, " << exact.too_close
                                       << " too close to an obstacle); first is #" << i << " (" << a.x << ", " << a.y
                                       << ") -> (" << b.x << ", " << b.y << ")";
  }
  const Validity v = checkValidity(wall, tool, path, vehicle);
  if (v.valid) return testing::AssertionSuccess();
  // Name the first offending segment.
  const ClearanceField field(wall);
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    if (vehicle.liftsTool() && !path.tool_on[i]) {
      if (std::find(v.violating.begin(), v.violating.end(), i) == v.violating.end()) continue;
      return testing::AssertionFailure() << v.violations << " violating segments; first is #" << i << " (" << a.x
                                         << ", " << a.y << ") -> (" << b.x << ", " << b.y
                                         << "), lifted, leaves the wall's bounding box";
    }
    if (!field.segmentFree(a, b, tool.radius(), tool.clearance, -kValidityTolerance)) {
      const SegmentClearance c = field.measure(a, b);
      return testing::AssertionFailure()
             << v.violations << " violating segments; first is #" << i << " (" << a.x << ", " << a.y << ") -> ("
             << b.x << ", " << b.y << "), tool " << (path.tool_on[i] ? "on" : "off") << ", inside=" << c.inside
             << ", boundary distance " << c.boundary_distance << ", obstacle distance " << c.obstacle_distance;
    }
  }
  return testing::AssertionFailure() << v.violations << " violating segments";
}

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const PlannerInfo& p : registeredPlanners()) names.push_back(p.name);
  return names;
}

std::string plannerTestName(const testing::TestParamInfo<std::string>& param_info) {
  std::string name = param_info.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

std::size_t sampleStride() {
  static const std::size_t stride = [] {
    const char* text = std::getenv("COVERBENCH_TEST_SAMPLE_STRIDE");
    if (text == nullptr || *text == '\0') return std::size_t{1};
    char* end = nullptr;
    const unsigned long value = std::strtoul(text, &end, 10);
    if (*end != '\0' || value < 1 || value > 100) {
      std::fprintf(stderr, "COVERBENCH_TEST_SAMPLE_STRIDE: expected a whole number from 1 to 100, got '%s'\n", text);
      std::abort();
    }
    return static_cast<std::size_t>(value);
  }();
  return stride;
}

std::string pgm(const std::vector<std::vector<int>>& rows, int maxval) {
  std::string s = "P5\n" + std::to_string(rows[0].size()) + " " + std::to_string(rows.size()) + "\n" + std::to_string(maxval) + "\n";
  for (const auto& row : rows)
    for (int v : row) s += maxval > 255 ? std::string{static_cast<char>(v >> 8), static_cast<char>(v & 0xff)} : std::string(1, static_cast<char>(v));
  return s;
}

std::string inputError(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::optional<Point> freePointNear(const Wall& wall, const ToolParams& tool, bool from_lower_left) {
  const Workspace ws(wall, tool);
  const Box b = boundingBox(wall.boundary);
  for (double y = 0; y <= b.height(); y += 0.05)
    for (double x = 0; x <= b.width(); x += 0.05) {
      const Point p = from_lower_left ? Point{b.min_x + x, b.min_y + y} : Point{b.max_x - x, b.max_y - y};
      for (const PolygonWithHoles& poly : ws.free())
        if (pointInPolygon(poly, p)) return p;
    }
  return std::nullopt;
}

}  // namespace coverbench::test
