// The wall parser accepts the documented format and rejects every bad input with one line that
// names the file, the field and the problem.
#include <gtest/gtest.h>

#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

struct BadWall {
  const char* label;
  const char* json;
  const char* field;
  const char* problem;  // a substring of the problem
};

class WallParserRejects : public testing::TestWithParam<BadWall> {};

TEST_P(WallParserRejects, WithFileFieldAndProblem) {
  const BadWall& bad = GetParam();
  try {
    parseWallJson(bad.json, "walls/bad.json");
    FAIL() << "accepted: " << bad.json;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "walls/bad.json");
    EXPECT_EQ(e.field(), bad.field) << e.what();
    EXPECT_NE(e.problem().find(bad.problem), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message must be one line";
    EXPECT_EQ(std::string(e.what()).rfind("walls/bad.json: " + std::string(bad.field) + ": ", 0), 0u) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllErrors, WallParserRejects,
    testing::Values(
        BadWall{"malformed", R"({"width": 5, "height": )", "(document)", "malformed JSON"},
        BadWall{"not_object", R"([1, 2])", "(document)", "JSON object"},
        BadWall{"missing_width", R"({"height": 2})", "width", "missing"},
        BadWall{"missing_height", R"({"width": 2})", "height", "missing"},
        BadWall{"string_number", R"({"width": "5", "height": 2})", "width", "must be a number"},
        BadWall{"zero_width", R"({"width": 0, "height": 2})", "width", "must be positive"},
        BadWall{"negative_height", R"({"width": 3, "height": -2})", "height", "must be positive"},
        BadWall{"absurd_width", R"({"width": 20000, "height": 2})", "width", "beyond 10 km"},
        BadWall{"overflowing", R"({"width": 1e999, "height": 2})", "(document)", "number overflow"},
        BadWall{"unknown_key", R"({"width": 3, "height": 2, "widht": 3})", "widht", "unknown key"},
        BadWall{"both_shapes", R"({"width": 3, "height": 2, "boundary": [[0,0],[1,0],[0,1]]})", "boundary",
                "not both"},
        BadWall{"two_points", R"({"boundary": [[0,0],[1,0]]})", "boundary", "at least 3"},
        BadWall{"bow_tie", R"({"boundary": [[0,0],[1,1],[1,0],[0,1]]})", "boundary", "self-intersecting"},
        BadWall{"bad_point", R"({"boundary": [[0,0],[1,0,3],[0,1]]})", "boundary[1]", "[x, y] pair"},
        BadWall{"nan_point", R"({"boundary": [[0,0],[1,"x"],[0,1]]})", "boundary[1][1]", "must be a number"},
        BadWall{"unknown_type", R"({"width": 3, "height": 2, "obstacles": [{"type": "hexagon"}]})",
                "obstacles[0].type", "unknown obstacle type"},
        BadWall{"missing_type", R"({"width": 3, "height": 2, "obstacles": [{"x": 1}]})", "obstacles[0].type",
                "missing"},
        BadWall{"missing_radius", R"({"width": 3, "height": 2, "obstacles": [{"type": "circle", "x": 1, "y": 1}]})",
                "obstacles[0].radius", "missing"},
        BadWall{"negative_radius",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "circle", "x": 1, "y": 1, "radius": -0.1}]})",
                "obstacles[0].radius", "must be positive"},
        BadWall{"zero_rect",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "rect", "x": 1, "y": 1, "width": 0, "height": 1}]})",
                "obstacles[0].width", "must be positive"},
        // Found by the wall parser's fuzzer: this rectangle was read, and its corners written back
        // as a polygon were refused as degenerate.
        BadWall{"rect_thinner_than_rounding",
                R"({"width": 5, "height": 5, "obstacles": [{"type": "rect", "x": 2.4, "y": 3.4, "width": 0.15, "height": 0.000000000000001}]})",
                "obstacles[0]", "rectangle is degenerate"},
        BadWall{"absurd_rect",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "rect", "x": 1, "y": 1, "width": 12000, "height": 1}]})",
                "obstacles[0].width", "beyond 10 km"},
        BadWall{"polygon_self_intersecting",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "polygon", "points": [[0.5,0.5],[1,1],[1,0.5],[0.5,1]]}]})",
                "obstacles[0].points", "self-intersecting"},
        BadWall{"outside",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "rect", "x": 1, "y": 1, "width": 1, "height": 1},
                    {"type": "rect", "x": 5, "y": 5, "width": 1, "height": 1}]})",
                "obstacles[1]", "entirely outside"},
        BadWall{"touching_from_outside",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "rect", "x": 3, "y": 0, "width": 1, "height": 1}]})",
                "obstacles[0]", "entirely outside"},
        BadWall{"nothing_left",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "rect", "x": -1, "y": -1, "width": 2.5, "height": 4},
                    {"type": "rect", "x": 1.4, "y": -1, "width": 3, "height": 4}]})",
                "obstacles", "nothing of the wall"},
        BadWall{"label_not_string",
                R"({"width": 3, "height": 2, "obstacles": [{"type": "circle", "x": 1, "y": 1, "radius": 0.1, "label": 3}]})",
                "obstacles[0].label", "must be a string"}),
    [](const testing::TestParamInfo<BadWall>& param_info) { return std::string(param_info.param.label); });

TEST(WallParser, ReadsTheDocumentedExample) {
  const Wall w = loadWallFile(test::sourcePath("datasets/canonical/living_room_north.json"));
  EXPECT_EQ(w.name, "living-room-north");
  ASSERT_EQ(w.boundary.size(), 4u);
  EXPECT_DOUBLE_EQ(signedArea(w.boundary), 5.0 * 2.6);
  ASSERT_EQ(w.obstacles.size(), 3u);
  EXPECT_EQ(w.obstacles[0].type, ObstacleType::Rect);
  EXPECT_EQ(w.obstacles[0].label, "window");
  EXPECT_DOUBLE_EQ(signedArea(w.obstacles[0].polygon), 1.44);
  EXPECT_EQ(w.obstacles[1].type, ObstacleType::Polygon);
  EXPECT_EQ(w.obstacles[2].type, ObstacleType::Circle);
  EXPECT_DOUBLE_EQ(w.obstacles[2].radius, 0.15);
}

TEST(WallParser, NormalisesClockwiseBoundaryAndClosingPoint) {
  const Wall w = parseWallJson(R"({"boundary": [[0,0],[0,2],[3,2],[3,0],[0,0]]})", "cw.json");
  ASSERT_EQ(w.boundary.size(), 4u);  // the repeated closing point is dropped
  EXPECT_DOUBLE_EQ(signedArea(w.boundary), 6.0);  // now counter-clockwise
}

TEST(WallParser, AcceptsObstaclesCrossingTheBoundaryAndOverlapping) {
  EXPECT_NO_THROW(parseWallJson(R"({"width": 3, "height": 2, "obstacles": [
      {"type": "rect", "x": -0.5, "y": 0.5, "width": 1, "height": 0.5},
      {"type": "rect", "x": 0.2, "y": 0.7, "width": 1, "height": 0.5},
      {"type": "circle", "x": 3, "y": 2, "radius": 0.3}]})",
                                "ok.json"));
}

TEST(WallParser, MissingFileIsAnInputError) {
  try {
    loadWallFile("/nonexistent/wall.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/wall.json: (file): cannot be read: no such file");
  }
}

TEST(WallParser, RoundTripsThroughJson) {
  const Wall w = loadWallFile(test::sourcePath("datasets/canonical/gable_round_window.json"));
  const Wall again = parseWallJson(wallToJson(w), "again.json");
  EXPECT_EQ(wallToJson(again), wallToJson(w));
}

}  // namespace
}  // namespace coverbench
