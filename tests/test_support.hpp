#pragma once
/// Helpers shared by the tests: test data locations, wall builders, and property checkers that
/// say exactly what failed.

#include <gtest/gtest.h>

#include <filesystem>
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

/// A well-formed, exactly valid path, or a message naming the first offending segment.
testing::AssertionResult isValidPath(const Wall& wall, const ToolParams& tool, const Path& path);

/// A fixture with a fresh folder for each test (named after it), removed afterwards.
class TempDirTest : public testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::filesystem::path dir_;
};

}  // namespace coverbench::test
