#pragma once
/// Helpers shared by the tests: test data locations, wall builders, and property checkers that
/// say exactly what failed.

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/metrics.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench::test {

std::string sourcePath(const std::string& relative);
/// Every wall file of the canonical dataset and the conformance set.
std::vector<std::string> conformanceWallFiles();

Wall rectWall(double width, double height, std::vector<Obstacle> obstacles = {});
Obstacle rect(double x, double y, double w, double h);
Obstacle circle(double x, double y, double radius);
/// A `width` x `height` rectangle wall turned by `degrees` about its corner, moved right by 1 m.
Wall turnedRectWall(double width, double height, double degrees);

/// Random walls for property tests: rectangles or polygons with rect, circle and polygon
/// obstacles that may overlap and touch the boundary. Deterministic for a seed.
Wall randomWall(unsigned seed);

/// Runs a registered planner with the given parameter settings (the rest at their defaults).
PlanResult planWith(const std::string& planner, const Wall& wall, const ToolParams& tool,
                    const std::vector<std::pair<std::string, std::string>>& settings = {});

/// A well-formed path that both the exact judge (no tolerance) and the fast engine find valid, or a
/// message naming the first offending segment.
testing::AssertionResult isValidPath(const Wall& wall, const ToolParams& tool, const Path& path,
                                     const VehicleModel& vehicle = {});

/// The first point of a 5 cm grid over the wall's bounding box, scanned from its lower-left (or
/// upper-right) corner, where the tool's centre may be (in F); nothing when there is none.
std::optional<Point> freePointNear(const Wall& wall, const ToolParams& tool, bool from_lower_left);

/// Every registered planner's name, for suites parameterised by planner, and the test name of one
/// (letters, digits and _ only).
std::vector<std::string> plannerNames();
std::string plannerTestName(const testing::TestParamInfo<std::string>& param_info);

/// The stride through the sample of the heaviest property tests: 1 (every case) unless
/// COVERBENCH_TEST_SAMPLE_STRIDE names a larger one. The sanitizer job sets 4
/// (scripts/sanitizers.sh): there the memory and undefined-behaviour checks are the point, and the
/// main job runs the whole sample. A malformed value fails loudly rather than thinning silently.
std::size_t sampleStride();
/// Every sampleStride()-th element of `all`, from the first.
template <class T>
std::vector<T> sampled(const std::vector<T>& all) {
  std::vector<T> kept;
  for (std::size_t i = 0; i < all.size(); i += sampleStride()) kept.push_back(all[i]);
  return kept;
}

/// The message of the InputError `action` throws ("" if it throws none).
std::string inputError(const std::function<void()>& action);

/// A binary PGM (P5) of `rows` (row 0 at the top) with maximum value `maxval` (two bytes a
/// sample above 255): a map image, or a segmentation's labels.
std::string pgm(const std::vector<std::vector<int>>& rows, int maxval = 255);

/// A fixture with a fresh folder for each test (named after it), removed afterwards.
class TempDirTest : public testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::filesystem::path dir_;
};

struct CommandRun {
  int exit_code;
  std::string err;
};

/// A TempDirTest that runs the coverbench binary as a user would, in a shell.
class CommandTest : public TempDirTest {
 protected:
  /// Runs `coverbench ARGS` (ARGS as shell words); stdout goes to `*out` if given.
  CommandRun run(const std::string& args, std::string* out = nullptr);
  static std::string slurp(const std::string& file);
  /// Writes `text` to a file of that name in the test's folder and returns its path.
  std::string write(const std::string& name, const std::string& text);
};

/// The rows a SQL statement yields on a database file, one line each ("a|b|NULL"); the
/// statement may also write (opened read-write).
std::string sqlRows(const std::string& database, const std::string& sql);
/// The runs stored in a results database that a runner may be writing; -1 while it has no runs
/// table (no file yet, or killed before its first transaction).
int storedRuns(const std::string& database);

/// A resolved parameter's value, by name (tests read values; planners receive their struct).
template <class T>
T param(const Params& params, const std::string& name) {
  return std::get<T>(params.all().at(name));
}
/// Every run of a results database as comparable text: integrity, key counts, and per key its
/// status, validity, reason, metrics, planner statistics and path; nothing measured.
std::string dumpRuns(const std::string& database);

}  // namespace coverbench::test
