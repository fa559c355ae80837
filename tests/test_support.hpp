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

/// Random walls for property tests: rectangles or polygons with rect, circle and polygon
/// obstacles that may overlap and touch the boundary. Deterministic for a seed.
Wall randomWall(unsigned seed);

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
