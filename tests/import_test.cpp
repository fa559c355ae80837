// Importing maps and polygons (docs/datasets.md): one file per format, written here, checked
// against hand-computed areas, hole counts and positions; bad input refused with one line; every
// planner plans every imported wall validly; the command and the config's `import:` kind.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/wall_import.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

class Import : public test::CommandTest {
 protected:
  std::vector<ImportedWall> import(const std::string& source, ImportOptions options = {}) {
    return importWalls({source}, options).walls;
  }
  std::string writeBytes(const std::string& name, const std::string& bytes) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
};

double holeArea(const Wall& w, std::size_t i) { return signedArea(w.obstacles.at(i).polygon); }

// --- GeoJSON in longitude/latitude, projected to its UTM zone --------------------------------

// A field 0.001 deg square on the equator, centred on 9 deg E (zone 32's central meridian), with a
// 0.0002 deg square hole whose lower-left corner is 0.0004 deg east and north of the field's.
// There UTM is the transverse Mercator at scale k0 = 0.9996: east-west, k0 * a * dlon (radians)
// on the equator; north-south, k0 * the meridian arc, a (1 - e^2) * dlat at the equator (WGS84:
// a = 6378137 m, e^2 = 0.00669438). Both hold to 1e-6 over 100 m there.
TEST_F(Import, GeoJsonInDegreesIsProjectedToItsUtmZone) {
  const std::string field = write("field.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "north_field"}, "geometry": {"type": "Polygon", "coordinates": [
      [[8.9995, 0.0], [9.0005, 0.0], [9.0005, 0.001], [8.9995, 0.001], [8.9995, 0.0]],
      [[8.9999, 0.0004], [9.0001, 0.0004], [9.0001, 0.0006], [8.9999, 0.0006], [8.9999, 0.0004]]]}}]})");
  const std::vector<ImportedWall> walls = import(field);
  ASSERT_EQ(walls.size(), 1u);
  const Wall& w = walls[0].wall;
  const double k0 = 0.9996, a = 6378137.0, e2 = 0.00669438, rad = M_PI / 180.0;
  const double metres_east = k0 * a * rad, metres_north = k0 * a * (1 - e2) * rad;  // per degree
  EXPECT_EQ(w.name, "north_field");
  EXPECT_EQ(walls[0].crs, "EPSG:32632");
  ASSERT_EQ(w.obstacles.size(), 1u);
  EXPECT_NEAR(signedArea(w.boundary), 0.001 * metres_east * 0.001 * metres_north, 0.01);
  EXPECT_NEAR(holeArea(w, 0), 0.0002 * metres_east * 0.0002 * metres_north, 0.001);
  // UTM easting 500000 at the central meridian: beyond 10 km, so each wall is moved to its corner
  // (whole metres) and the manifest keeps where that was.
  const Box box = boundingBox(w.boundary);
  EXPECT_NEAR(walls[0].origin_x + box.min_x, 500000.0 - 0.0005 * metres_east, 0.01);
  EXPECT_NEAR(walls[0].origin_y + box.min_y, 0.0, 0.01);
  EXPECT_GE(box.min_x, 0.0);
  EXPECT_LT(box.min_x, 1.0);
  const Box hole = boundingBox(w.obstacles[0].polygon);
  EXPECT_NEAR(hole.min_x - box.min_x, 0.0004 * metres_east, 0.01);
  EXPECT_NEAR(hole.min_y - box.min_y, 0.0004 * metres_north, 0.01);
}

TEST_F(Import, AChosenCrsAndANameFieldAreUsed) {
  const std::string field = write("f.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"id": "A7"}, "geometry": {"type": "Polygon", "coordinates": [
      [[8.9995, 0.0], [9.0005, 0.0], [9.0005, 0.001], [8.9995, 0.001], [8.9995, 0.0]]]}}]})");
  ImportOptions o;
  o.name_field = "id";
  o.crs = "EPSG:32633";  // the next zone: the same field, off its central meridian
  const std::vector<ImportedWall> walls = import(field, o);
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_EQ(walls[0].wall.name, "A7");
  EXPECT_EQ(walls[0].crs, "EPSG:32633");
  EXPECT_LT(walls[0].origin_x, 500000.0 - 600000.0);  // 6 degrees west of zone 33's meridian
  o.name_field = "owner";
  EXPECT_EQ(test::inputError([&] { import(field, o); }), field + ": --name-field: no attribute 'owner' (attributes: id)");
}

// --- DXF: a boundary layer and an obstacle layer, with a block insert --------------------------

std::string lwpolyline(const std::string& layer, const std::vector<Point>& points) {
  std::string s = "0\nLWPOLYLINE\n8\n" + layer + "\n90\n" + std::to_string(points.size()) + "\n70\n1\n";
  for (const Point& p : points) s += "10\n" + shortNumber(p.x) + "\n20\n" + shortNumber(p.y) + "\n";
  return s;
}

TEST_F(Import, DxfLayersBecomeBoundaryAndObstaclesAndBlocksArePlaced) {
  // A 10 x 8 wall on layer "walls"; on "openings" a 2 x 2 window at (2, 3), a round window of
  // radius 1 at (7, 5), and a 1 x 0.5 block inserted at (6, 1) scaled by 2 and turned 90 degrees:
  // the 2 x 1 rectangle turned about its insertion point covers x 5..6, y 1..3. A line on
  // "furniture" is ignored (the obstacle layer is named).
  const std::string blocks = "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n8\n0\n2\nWIN\n70\n0\n10\n0\n20\n0\n30\n0\n3\nWIN\n" +
                             lwpolyline("0", {{0, 0}, {1, 0}, {1, 0.5}, {0, 0.5}}) + "0\nENDBLK\n8\n0\n0\nENDSEC\n";
  const std::string entities = lwpolyline("walls", {{0, 0}, {10, 0}, {10, 8}, {0, 8}}) +
                               lwpolyline("openings", {{2, 3}, {4, 3}, {4, 5}, {2, 5}}) +
                               "0\nCIRCLE\n8\nopenings\n10\n7\n20\n5\n30\n0\n40\n1\n" +
                               "0\nINSERT\n8\nopenings\n2\nWIN\n10\n6\n20\n1\n30\n0\n41\n2\n42\n2\n50\n90\n" +
                               lwpolyline("furniture", {{8, 0.5}, {9, 0.5}, {9, 1}, {8, 1}});
  const std::string file = write("plan.dxf", "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n0\nENDSEC\n" + blocks +
                                                 "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n");
  ImportOptions o;
  o.dxf_boundary_layer = "walls";
  o.dxf_obstacle_layers = {"openings"};
  const std::vector<ImportedWall> walls = import(file, o);
  ASSERT_EQ(walls.size(), 1u);
  const Wall& w = walls[0].wall;
  EXPECT_DOUBLE_EQ(signedArea(w.boundary), 80.0);
  ASSERT_EQ(w.obstacles.size(), 3u);
  EXPECT_DOUBLE_EQ(holeArea(w, 0), 4.0);
  EXPECT_NEAR(holeArea(w, 1), M_PI, 0.01 * M_PI);  // the circle, as GDAL's polyline of it
  EXPECT_NEAR(boundingBox(w.obstacles[1].polygon).min_x, 6.0, 0.01);
  EXPECT_DOUBLE_EQ(holeArea(w, 2), 2.0);
  const Box inserted = boundingBox(w.obstacles[2].polygon);
  EXPECT_NEAR(inserted.min_x, 5.0, 1e-9);
  EXPECT_NEAR(inserted.max_x, 6.0, 1e-9);
  EXPECT_NEAR(inserted.min_y, 1.0, 1e-9);
  EXPECT_NEAR(inserted.max_y, 3.0, 1e-9);
  // Every other layer as obstacles: the furniture joins them.
  o.dxf_obstacle_layers.clear();
  EXPECT_EQ(import(file, o)[0].wall.obstacles.size(), 4u);
  o.dxf_boundary_layer = "outline";
  EXPECT_EQ(test::inputError([&] { import(file, o); }),
            file + ": --boundary-layer: no closed polyline on layer 'outline' (layers: furniture, openings, walls)");
}

// --- map_server occupancy grids ------------------------------------------------------------------

/// A binary PGM (P5) of `rows` (row 0 at the top).
std::string pgm(const std::vector<std::vector<int>>& rows) {
  std::string s = "P5\n" + std::to_string(rows[0].size()) + " " + std::to_string(rows.size()) + "\n255\n";
  for (const auto& row : rows)
    for (int v : row) s += static_cast<char>(v);
  return s;
}

/// 20 x 10 pixels: occupied (0) all round; free (254) inside; an occupied block of 4 x 2 pixels and
/// an unknown (128: occupancy 0.5, between the thresholds) block of 2 x 2. Free: 18 * 8 - 8 - 4 =
/// 132 pixels.
std::vector<std::vector<int>> testMap() {
  std::vector<std::vector<int>> rows(10, std::vector<int>(20, 0));
  for (int r = 1; r <= 8; ++r)
    for (int c = 1; c <= 18; ++c) rows[r][c] = 254;
  for (int r = 3; r <= 4; ++r)
    for (int c = 5; c <= 8; ++c) rows[r][c] = 0;
  for (int r = 6; r <= 7; ++r)
    for (int c = 14; c <= 15; ++c) rows[r][c] = 128;
  return rows;
}

TEST_F(Import, OccupancyGridFreeCellsBecomeAWallAtTheMapsOrigin) {
  writeBytes("room.pgm", pgm(testMap()));
  const std::string map = write("room.yaml",
                                "image: room.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\n"
                                "occupied_thresh: 0.65\nfree_thresh: 0.196\nnegate: 0\n");
  const std::vector<ImportedWall> walls = import(map);
  ASSERT_EQ(walls.size(), 1u);
  const Wall& w = walls[0].wall;
  EXPECT_EQ(w.name, "room");
  ASSERT_EQ(w.obstacles.size(), 2u);
  // Axis-aligned pixel edges: simplification at half a pixel keeps every corner, so the area is
  // exact here; in general it moves by at most the perimeter times the tolerance.
  const double free_area = signedArea(w.boundary) - holeArea(w, 0) - holeArea(w, 1);
  EXPECT_NEAR(free_area, 132 * 0.05 * 0.05, 1e-9);
  EXPECT_NEAR(holeArea(w, 0) + holeArea(w, 1), 12 * 0.05 * 0.05, 1e-9);
  // The lower-left free pixel is column 1, row 8 of 10 (1 up from the bottom): (0.05, 0.05) from
  // the origin.
  const Box box = boundingBox(w.boundary);
  EXPECT_NEAR(box.min_x, -1.0 + 0.05, 1e-9);
  EXPECT_NEAR(box.min_y, -2.0 + 0.05, 1e-9);
  EXPECT_NEAR(box.width(), 18 * 0.05, 1e-9);
  EXPECT_NEAR(box.height(), 8 * 0.05, 1e-9);
  // A folder with --format map imports its map YAMLs (and not their images on their own).
  ImportOptions as_maps;
  as_maps.format = "map";
  EXPECT_EQ(importWalls({dir_.string()}, as_maps).walls.size(), 1u);
}

TEST_F(Import, OccupancyGridYawNegateComponentsAndSmallHoles) {
  auto rows = testMap();
  // A second free component: one pixel row at the top right, 3 pixels, cut off by occupied cells.
  rows[0][15] = rows[0][16] = rows[0][17] = 254;
  rows[1][15] = rows[1][16] = rows[1][17] = 0;
  writeBytes("room.pgm", pgm(rows));
  // Turned a quarter turn about the origin (2, 3): map x becomes world y.
  const std::string map = write("room.yaml", "image: room.pgm\nresolution: 0.05\norigin: [2.0, 3.0, 1.5707963267948966]\n");
  ImportOptions o;
  o.all_components = true;
  o.min_hole_area = 5 * 0.05 * 0.05;  // drops the 4-pixel unknown block, keeps the 8-pixel one
  const std::vector<ImportedWall> walls = import(map, o);
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(walls[0].wall.name, "room_1");
  EXPECT_EQ(walls[0].wall.obstacles.size(), 1u);
  EXPECT_EQ(walls[0].dropped_holes, 1u);
  EXPECT_NEAR(walls[0].dropped_hole_area, 4 * 0.05 * 0.05, 1e-9);
  EXPECT_NEAR(signedArea(walls[1].wall.boundary), 3 * 0.05 * 0.05, 1e-9);
  const Box box = boundingBox(walls[0].wall.boundary);
  EXPECT_NEAR(box.min_x, 2.0 - 9 * 0.05, 1e-9);  // map y 0.05..0.45 turns to world x -0.45..-0.05
  EXPECT_NEAR(box.max_x, 2.0 - 0.05, 1e-9);
  EXPECT_NEAR(box.min_y, 3.0 + 0.05, 1e-9);
  EXPECT_NEAR(box.max_y, 3.0 + 19 * 0.05, 1e-9);
  // Negated: dark is free. The occupied frame and block become free, so the free component is
  // the whole image less what was free.
  write("neg.yaml", "image: room.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 1\n");
  const std::vector<ImportedWall> negated = import((dir_ / "neg.yaml").string());
  ASSERT_EQ(negated.size(), 1u);
  EXPECT_GT(signedArea(negated[0].wall.boundary), 0.0);
}

// --- WKT, polygon text, YAML hull/holes ------------------------------------------------------------

TEST_F(Import, WktPolygonsWithHolesAndMultipolygons) {
  const std::string file = write("rooms.wkt",
                                 "POLYGON ((0 0, 10 0, 10 6, 0 6, 0 0), (1 1, 3 1, 3 2, 1 2, 1 1), (5 3, 7 3, 6 5, 5 3))\n"
                                 "MULTIPOLYGON (((20 0, 24 0, 24 3, 20 3, 20 0)), ((30 0, 31 0, 31 1, 30 1, 30 0)))\n");
  const std::vector<ImportedWall> walls = import(file);
  ASSERT_EQ(walls.size(), 3u);
  EXPECT_EQ(walls[0].wall.name, "rooms_1");
  EXPECT_DOUBLE_EQ(signedArea(walls[0].wall.boundary), 60.0);
  ASSERT_EQ(walls[0].wall.obstacles.size(), 2u);
  EXPECT_DOUBLE_EQ(holeArea(walls[0].wall, 0), 2.0);
  EXPECT_DOUBLE_EQ(holeArea(walls[0].wall, 1), 2.0);  // the triangle: base 2, height 2
  EXPECT_EQ(walls[1].feature, "geometry 2 part 1");
  EXPECT_DOUBLE_EQ(signedArea(walls[1].wall.boundary), 12.0);
  EXPECT_DOUBLE_EQ(boundingBox(walls[2].wall.boundary).min_x, 30.0);
  ImportOptions o;
  o.split_multipolygons = false;
  EXPECT_EQ(test::inputError([&] { import(file, o); }), file + ": geometry 2: is a multipolygon of 2 parts");
}

TEST_F(Import, PolygonTextFoldersAreNamedAfterTheirFolder) {
  // The published layout: `x y` lines, one file for the outer ring, one for the holes with rings
  // separated by blank lines.
  writeBytes("eth/poly_007/outer_polygon", "0 0\n20 0\n20 10\n0 10\n");
  writeBytes("eth/poly_007/holes", "2 2\n4 2\n4 5\n2 5\n\n10 6\n13 6\n13 8\n");
  writeBytes("eth/poly_008/outer_polygon", "0 0\n5 0\n5 5\n");
  const std::vector<ImportedWall> walls = import((dir_ / "eth").string());
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(walls[0].wall.name, "poly_007");
  EXPECT_DOUBLE_EQ(signedArea(walls[0].wall.boundary), 200.0);
  ASSERT_EQ(walls[0].wall.obstacles.size(), 2u);
  EXPECT_DOUBLE_EQ(holeArea(walls[0].wall, 0), 6.0);
  EXPECT_DOUBLE_EQ(holeArea(walls[0].wall, 1), 3.0);  // a triangle: base 3, height 2
  EXPECT_EQ(walls[1].wall.name, "poly_008");
  EXPECT_DOUBLE_EQ(signedArea(walls[1].wall.boundary), 12.5);
  writeBytes("bad/outer_polygon", "0 0\n20 zero\n20 10\n");
  EXPECT_EQ(test::inputError([&] { import((dir_ / "bad").string()); }),
            (dir_ / "bad" / "outer_polygon").string() + ": line 2: must be two numbers, x y");
}

TEST_F(Import, YamlHullAndHoles) {
  const std::string file = write("yard.yaml",
                                 "hull: [{x: 0, y: 0}, {x: 8, y: 0}, {x: 8, y: 4}, {x: 0, y: 4}]\n"
                                 "holes:\n  - [{x: 1, y: 1}, {x: 2, y: 1}, {x: 2, y: 3}, {x: 1, y: 3}]\n");
  const std::vector<ImportedWall> walls = import(file);
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_EQ(walls[0].wall.name, "yard");
  EXPECT_DOUBLE_EQ(signedArea(walls[0].wall.boundary), 32.0);
  ASSERT_EQ(walls[0].wall.obstacles.size(), 1u);
  EXPECT_DOUBLE_EQ(holeArea(walls[0].wall, 0), 2.0);
  EXPECT_DOUBLE_EQ(boundingBox(walls[0].wall.obstacles[0].polygon).min_x, 1.0);
  write("bad.yaml", "hull: [{x: 0, y: 0}, {x: 8}, {x: 8, y: 4}]\n");
  EXPECT_EQ(test::inputError([&] { import((dir_ / "bad.yaml").string()); }),
            (dir_ / "bad.yaml").string() + ": hull[1].y: missing");
}

TEST_F(Import, TransformsAreAppliedInOrder) {
  const std::string file = write("r.wkt", "POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0))");
  ImportOptions o;
  o.transform = parseTransform("scale=0.5 rotate=90 translate=10,1", "--transform", "(value)");
  const Wall w = import(file, o)[0].wall;
  // Scaled to 2 x 1, turned a quarter about the origin (x -1..0, y 0..2), moved by (10, 1).
  const Box b = boundingBox(w.boundary);
  EXPECT_NEAR(b.min_x, 9.0, 1e-9);
  EXPECT_NEAR(b.max_x, 10.0, 1e-9);
  EXPECT_NEAR(b.min_y, 1.0, 1e-9);
  EXPECT_NEAR(b.max_y, 3.0, 1e-9);
  EXPECT_EQ(test::inputError([&] { parseTransform("shear=2", "--transform", "(value)"); }),
            "--transform: (value): 'shear=2' is not translate=X,Y, rotate=DEGREES or scale=S (or scale=SX,SY)");
}

// --- bad input: one line, the file, the field and the problem ----------------------------------

TEST_F(Import, BadInputIsRefusedWithOneLine) {
  const std::string points = write("points.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [9.0, 0.0]}}]})");
  EXPECT_EQ(test::inputError([&] { import(points); }), points + ": (features): holds no polygon (lines and points are not areas)");
  const std::string bowtie = write("bowtie.wkt", "POLYGON ((0 0, 4 4, 4 0, 0 4, 0 0))");
  EXPECT_NE(test::inputError([&] { import(bowtie); }).find(bowtie + ": geometry 1: is not a valid polygon"), std::string::npos);
  const std::string degrees = write("field.wkt", "POLYGON ((8.1 47.1, 8.102 47.1, 8.102 47.101, 8.1 47.101, 8.1 47.1))");
  EXPECT_EQ(test::inputError([&] { import(degrees); }),
            degrees + ": (CRS): names no CRS and its coordinates look like degrees (longitude/latitude): give --source-crs EPSG:4326");
  ImportOptions lonlat;
  lonlat.source_crs = "EPSG:4326";
  EXPECT_EQ(import(degrees, lonlat)[0].crs, "EPSG:32632");
  writeBytes("room.pgm", pgm(testMap()));
  const std::string thresholds = write("t.yaml", "image: room.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 1.5\n");
  EXPECT_EQ(test::inputError([&] { import(thresholds); }), thresholds + ": occupied_thresh: must be between 0 and 1, got 1.5");
  const std::string unknown = write("walls.xyz", "1 2 3");
  EXPECT_EQ(test::inputError([&] { import(unknown); }),
            unknown + ": --format: cannot tell the format from the name 'walls.xyz': give --format");
  ImportOptions bad_format;
  bad_format.format = "svg";
  EXPECT_EQ(test::inputError([&] { import(unknown, bad_format); }), "--format: (value): unknown format 'svg'");
}

TEST_F(Import, TheCommandWritesADatasetOrNothing) {
  const std::string wkt = write("rooms.wkt", "POLYGON ((0 0, 10 0, 10 6, 0 6, 0 0), (1 1, 3 1, 3 2, 1 2, 1 1))");
  std::string out;
  ASSERT_EQ(run("dataset import " + wkt + " --out " + (dir_ / "ds").string(), &out).exit_code, 0) << out;
  const Dataset d = readDataset((dir_ / "ds").string());
  ASSERT_EQ(d.walls.size(), 1u);
  EXPECT_EQ(d.family, "import");
  const std::string manifest = slurp((dir_ / "ds" / "manifest.json").string());
  EXPECT_NE(manifest.find("\"sha256\": \"" + sha256Hex(slurp(wkt))), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"origin\": \"auto\""), std::string::npos) << manifest;
  // Same input, same bytes.
  ASSERT_EQ(run("dataset import " + wkt + " --out " + (dir_ / "ds2").string()).exit_code, 0);
  EXPECT_EQ(slurp((dir_ / "ds2" / "manifest.json").string()), manifest);
  // A bad second source: exit 2, one line, no folder.
  const std::string bowtie = write("bowtie.wkt", "POLYGON ((0 0, 4 4, 4 0, 0 4, 0 0))");
  const test::CommandRun bad = run("dataset import " + wkt + " " + bowtie + " --out " + (dir_ / "ds3").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "ds3"));
}

TEST_F(Import, AConfigImportsAsADatasetKind) {
  writeBytes("fields/a.wkt", "POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0), (1 1, 2 1, 2 2, 1 2, 1 1))");
  writeBytes("fields/b.wkt", "POLYGON ((0 0, 3 0, 3 3, 0 3, 0 0))");
  const std::string config = write("exp.yaml",
                                   "name: imported\noutput: out\n"
                                   "datasets:\n  - import: fields/\n    format: wkt\n    transform: scale=0.5\n"
                                   "planners: [zigzag]\ntool: {width: 0.2, clearance: 0.02}\n");
  const ExperimentConfig c = loadExperimentConfig(config);
  ASSERT_EQ(c.datasets.size(), 1u);
  EXPECT_EQ(c.datasets[0].label, "fields");
  EXPECT_EQ(c.datasets[0].count, 2u);
  const std::vector<WallEntry> walls = loadWalls(c);
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_DOUBLE_EQ(signedArea(walls[0].wall.boundary), 3.0);  // 4 x 3 scaled by a half
  write("crs.yaml", "name: x\noutput: out\ndatasets:\n  - import: fields/\n    source_crs: EPSG:99999999\nplanners: [zigzag]\n");
  EXPECT_EQ(test::inputError([&] { loadExperimentConfig((dir_ / "crs.yaml").string()); }),
            (dir_ / "crs.yaml").string() + ":5: datasets[0].source_crs: 'EPSG:99999999' is not a CRS PROJ knows");
  write("bad.yaml", "name: x\noutput: out\ndatasets:\n  - folder: fields/\n    format: wkt\nplanners: [zigzag]\n");
  EXPECT_EQ(test::inputError([&] { loadExperimentConfig((dir_ / "bad.yaml").string()); }),
            (dir_ / "bad.yaml").string() + ":5: datasets[0].format: is an import option: it needs import: FILE_OR_FOLDER");
}

// --- every planner plans every imported test wall -------------------------------------------

class ImportedWallsPlan : public test::TempDirTest, public testing::WithParamInterface<std::string> {};

TEST_P(ImportedWallsPlan, EveryImportedTestWallValidlyFromTheStartToTheEnd) {
  auto put = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return (dir_ / name).string();
  };
  std::vector<std::string> sources = {
      put("rooms.wkt", "POLYGON ((0 0, 5 0, 5 3, 0 3, 0 0), (1 1, 2 1, 2 2, 1 2, 1 1), (3 1.5, 4 1.5, 3.5 2.5, 3 1.5))"),
      put("yard.yaml", "hull: [{x: 0, y: 0}, {x: 4, y: 0}, {x: 4, y: 3}, {x: 2, y: 4}, {x: 0, y: 3}]\n"
                       "holes:\n  - [{x: 1, y: 1}, {x: 1.5, y: 1}, {x: 1.5, y: 2}, {x: 1, y: 2}]\n"),
  };
  put("room.pgm", pgm(testMap()));
  sources.push_back(put("room.yaml", "image: room.pgm\nresolution: 0.2\norigin: [0, 0, 0.3]\n"));
  sources.push_back(put("field.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
      [[8.99998, 0.0], [9.00002, 0.0], [9.00002, 0.00003], [8.99998, 0.00003], [8.99998, 0.0]],
      [[8.99999, 0.00001], [9.0, 0.00001], [9.0, 0.00002], [8.99999, 0.00002], [8.99999, 0.00001]]]}}]})"));
  sources.push_back(put("hall.dxf", "0\nSECTION\n2\nENTITIES\n" + lwpolyline("boundary", {{0, 0}, {6, 0}, {6, 3}, {0, 3}}) +
                                        lwpolyline("windows", {{1, 1}, {2, 1}, {2, 2}, {1, 2}}) +
                                        "0\nCIRCLE\n8\nwindows\n10\n4\n20\n1.5\n30\n0\n40\n0.6\n0\nENDSEC\n0\nEOF\n"));
  fs::create_directories(dir_ / "poly_1");
  put("poly_1/outer_polygon", "0 0\n5 0\n6 4\n0 3\n");
  put("poly_1/holes", "1 1\n2 1\n2 2\n\n3 1\n4 1\n4 2\n3 2\n");
  sources.push_back((dir_ / "poly_1").string());
  const ToolParams tool{0.2, 0.02};
  const std::vector<ImportedWall> walls = importWalls(sources, {}).walls;
  ASSERT_EQ(walls.size(), 6u);
  for (const ImportedWall& imported : walls) {
    // From a start near the lower-left corner to an end near the upper-right one.
    Wall wall = imported.wall;
    wall.start = test::freePointNear(wall, tool, true);
    wall.end = test::freePointNear(wall, tool, false);
    ASSERT_TRUE(wall.start && wall.end) << wall.name;
    const PlanResult result = test::planWith(GetParam(), wall, tool);
    ASSERT_TRUE(result.status == PlanStatus::Ok || result.status == PlanStatus::Partial) << wall.name << ": " << result.reason;
    EXPECT_TRUE(result.path.waypoints.front() == *wall.start) << wall.name;
    EXPECT_TRUE(result.path.waypoints.back() == *wall.end) << wall.name;
    EXPECT_TRUE(test::isValidPath(wall, tool, result.path)) << wall.name;
  }
}

INSTANTIATE_TEST_SUITE_P(AllPlanners, ImportedWallsPlan, testing::ValuesIn(test::plannerNames()), test::plannerTestName);

}  // namespace
}  // namespace coverbench
