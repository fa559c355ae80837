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

using test::pgm;  // a binary PGM of rows (test_support.hpp)

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
  EXPECT_EQ(test::inputError([&] { import(file, o); }),
            file + ": geometry 2: is a multipolygon of 2 parts, refused by --refuse-multipolygons (without it each part "
                   "becomes a wall)");
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
            degrees + ": (CRS): names no CRS and its coordinates look like degrees (longitude/latitude; as metres it would be "
                      "0.002 x 0.001 m): give --source-crs EPSG:4326, or --source-crs metres if they are metres");
  ImportOptions lonlat;
  lonlat.source_crs = "EPSG:4326";
  EXPECT_EQ(import(degrees, lonlat)[0].crs, "EPSG:32632");
  writeBytes("room.pgm", pgm(testMap()));
  const std::string thresholds = write("t.yaml", "image: room.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 1.5\n");
  EXPECT_EQ(test::inputError([&] { import(thresholds); }), thresholds + ": occupied_thresh: must be between 0 and 1, got 1.5");
  const std::string unknown = write("walls.xyz", "1 2 3");
  EXPECT_EQ(test::inputError([&] { import(unknown); }),
            unknown + ": --format: cannot tell the format from the name 'walls.xyz': give --format (auto, geojson, gml, kml, "
                      "shapefile, gpkg, dxf, wkt, polygon-text, yaml-polygon, map)");
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

// --- hardening: each test below failed on the importer before it (the comment says how) ------

// 1. Degrees read as metres. A 0.1 x 0.06 degree field without a CRS became a 0.1 m wall: the
// refusal needed an extent under 0.05. Now any file without a CRS whose coordinates all lie in
// degree range and within one degree is refused, polygon text and YAML too, unless --source-crs
// says what they are.
TEST_F(Import, CoordinatesThatLookLikeDegreesAreRefusedWithoutASourceCrs) {
  const std::string wkt = write("field.wkt", "POLYGON ((8.1 47.1, 8.2 47.1, 8.2 47.16, 8.1 47.16, 8.1 47.1))");
  EXPECT_EQ(test::inputError([&] { import(wkt); }),
            wkt + ": (CRS): names no CRS and its coordinates look like degrees (longitude/latitude; as metres it would be "
                  "0.1 x 0.06 m): give --source-crs EPSG:4326, or --source-crs metres if they are metres");
  writeBytes("lonlat/poly_1/outer_polygon", "8.1 47.1\n8.2 47.1\n8.2 47.16\n8.1 47.16\n");
  EXPECT_NE(test::inputError([&] { import((dir_ / "lonlat" / "poly_1").string()); })
                .find((dir_ / "lonlat" / "poly_1" / "outer_polygon").string() + ": (CRS): names no CRS"),
            std::string::npos);
  const std::string yaml = write("yard.yaml", "hull: [{x: 8.1, y: 47.1}, {x: 8.2, y: 47.1}, {x: 8.2, y: 47.16}]\n");
  EXPECT_NE(test::inputError([&] { import(yaml); }).find(yaml + ": (CRS): names no CRS"), std::string::npos);
  // Said to be metres: a 0.1 m x 0.06 m wall, as written.
  ImportOptions metres;
  metres.source_crs = "metres";
  const std::vector<ImportedWall> small = import(wkt, metres);
  ASSERT_EQ(small.size(), 1u);
  EXPECT_EQ(small[0].crs, "");
  EXPECT_NEAR(signedArea(small[0].wall.boundary), 0.1 * 0.06, 1e-9);
  // Said to be longitude/latitude: projected to UTM zone 32 (8.1..8.2 E), about 7.6 km x 6.7 km.
  ImportOptions lonlat;
  lonlat.source_crs = "EPSG:4326";
  const std::vector<ImportedWall> field = import(wkt, lonlat);
  EXPECT_EQ(field[0].crs, "EPSG:32632");
  EXPECT_GT(boundingBox(field[0].wall.boundary).width(), 7000.0);
  EXPECT_EQ(import((dir_ / "lonlat" / "poly_1").string(), lonlat)[0].crs, "EPSG:32632");
  // Metres near the origin, a metre or more across, are not degrees.
  EXPECT_EQ(import(write("room.wkt", "POLYGON ((0 0, 1.5 0, 1.5 1, 0 1, 0 0))"))[0].crs, "");
}

// 2. Map images by map_server's rule. A 16-bit image was read as 8 bits clamped at 255: every
// pixel above 255 (occupied ones included) read as white, free. A grey+alpha PNG had its alpha
// averaged into the grey: an unknown cell (205) with opaque alpha read as 230, free.

/// A PNG (RFC 2083) of `samples` (row-major, channels interleaved), colour type 0 (grey), 4
/// (grey+alpha) or 3 (palette indices, `palette` as r, g, b triples), 8 or 16 bits, with stored
/// (uncompressed) deflate blocks.
std::string png(int width, int height, int colour_type, int bits, const std::vector<int>& samples,
                const std::vector<int>& palette = {}) {
  static const std::vector<std::uint32_t> table = [] {
    std::vector<std::uint32_t> t(256);
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    std::uint32_t crc = 0xffffffffu;
    for (unsigned char ch : type + data) crc = table[(crc ^ ch) & 0xff] ^ (crc >> 8);
    return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc ^ 0xffffffffu);
  };
  const int channels = colour_type == 4 ? 2 : 1;
  std::string raw;
  for (int y = 0; y < height; ++y) {
    raw += '\0';  // filter: none
    for (int i = 0; i < width * channels; ++i) {
      const int v = samples.at(static_cast<std::size_t>(y * width * channels + i));
      if (bits == 16) raw += static_cast<char>(v >> 8);
      raw += static_cast<char>(v & 0xff);
    }
  }
  std::string z = "\x78\x01";
  std::uint32_t a = 1, b = 0;
  for (unsigned char ch : raw) a = (a + ch) % 65521, b = (b + a) % 65521;
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const std::size_t len = std::min<std::size_t>(65535, raw.size() - at);
    z += static_cast<char>(at + len >= raw.size() ? 1 : 0);
    z += static_cast<char>(len & 0xff);
    z += static_cast<char>(len >> 8);
    z += static_cast<char>(~len & 0xff);
    z += static_cast<char>((~len >> 8) & 0xff);
    z += raw.substr(at, len);
  }
  z += be32((b << 16) | a);
  const std::string header = be32(static_cast<std::uint32_t>(width)) + be32(static_cast<std::uint32_t>(height)) +
                             std::string{static_cast<char>(bits), static_cast<char>(colour_type), 0, 0, 0};
  std::string plte;
  for (int v : palette) plte += static_cast<char>(v);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + (plte.empty() ? "" : chunk("PLTE", plte)) +
         chunk("IDAT", z) + chunk("IEND", "");
}


std::vector<int> flat(const std::vector<std::vector<int>>& rows, int scale, int alpha = -1) {
  std::vector<int> out;
  for (const auto& row : rows)
    for (int v : row) {
      out.push_back(v * scale);
      if (alpha >= 0) out.push_back(alpha);
    }
  return out;
}

/// The free area of a map's only wall.
double freeArea(const ImportedWall& w) {
  double a = signedArea(w.wall.boundary);
  for (std::size_t i = 0; i < w.wall.obstacles.size(); ++i) a -= holeArea(w.wall, i);
  return a;
}

TEST_F(Import, SixteenBitMapsGiveTheWallsOfTheirEightBitCopies) {
  // testMap: 132 free pixels, an occupied block of 8 and an unknown (128) block of 4 as holes.
  // 16 bits: each value v as v * 257, the same shade on 0..65535.
  const auto rows = testMap();
  writeBytes("m8.pgm", pgm(rows));
  std::vector<std::vector<int>> rows16 = rows;
  for (auto& row : rows16)
    for (int& v : row) v *= 257;
  writeBytes("m16.pgm", pgm(rows16, 65535));
  writeBytes("m8.png", png(20, 10, 0, 8, flat(rows, 1)));
  writeBytes("m16.png", png(20, 10, 0, 16, flat(rows, 257)));
  std::vector<std::vector<ImportedWall>> maps;
  for (const char* image : {"m8.pgm", "m16.pgm", "m8.png", "m16.png"})
    maps.push_back(import(write(std::string(image) + ".yaml", "image: " + std::string(image) + "\nresolution: 0.05\norigin: [0, 0, 0]\n")));
  for (const auto& walls : maps) {
    ASSERT_EQ(walls.size(), 1u);
    ASSERT_EQ(walls[0].wall.obstacles.size(), 2u);
    EXPECT_NEAR(freeArea(walls[0]), 132 * 0.05 * 0.05, 1e-9);
    EXPECT_EQ(walls[0].wall.boundary, maps[0][0].wall.boundary);
    EXPECT_EQ(walls[0].wall.obstacles[0].polygon, maps[0][0].wall.obstacles[0].polygon);
    EXPECT_EQ(walls[0].wall.obstacles[1].polygon, maps[0][0].wall.obstacles[1].polygon);
  }
  // A PGM's maximum value is its white: 1000 here.
  std::vector<std::vector<int>> rows1000 = rows;
  for (auto& row : rows1000)
    for (int& v : row) v = v * 1000 / 255;
  writeBytes("m1000.pgm", pgm(rows1000, 1000));
  const auto m1000 = import(write("m1000.yaml", "image: m1000.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"));
  EXPECT_NEAR(freeArea(m1000[0]), 132 * 0.05 * 0.05, 1e-9);
}

TEST_F(Import, AlphaIsNotAveragedIntoTheGrey) {
  // testMap with map_server's unknown grey (205: occupancy 0.196, not below free_thresh 0.196)
  // in the unknown block: 132 free pixels with or without an opaque alpha channel.
  auto rows = testMap();
  for (auto& row : rows)
    for (int& v : row)
      if (v == 128) v = 205;
  writeBytes("grey.png", png(20, 10, 0, 8, flat(rows, 1)));
  writeBytes("alpha.png", png(20, 10, 4, 8, flat(rows, 1, 255)));
  writeBytes("alpha16.png", png(20, 10, 4, 16, flat(rows, 257, 65535)));
  for (const char* image : {"grey.png", "alpha.png", "alpha16.png"}) {
    const auto walls = import(write(std::string(image) + ".yaml", "image: " + std::string(image) + "\nresolution: 0.05\norigin: [0, 0, 0]\n"));
    ASSERT_EQ(walls.size(), 1u) << image;
    EXPECT_NEAR(freeArea(walls[0]), 132 * 0.05 * 0.05, 1e-9) << image;
    EXPECT_EQ(walls[0].wall.obstacles.size(), 2u) << image;
  }
  // A palette PNG: the shade is the mean of the index's colour, not the index (index 1, white,
  // read as a grey of 1 made every pixel occupied).
  std::vector<int> indices;
  for (const auto& row : rows)
    for (int v : row) indices.push_back(v == 0 ? 0 : v == 254 ? 1 : 2);
  writeBytes("palette.png", png(20, 10, 3, 8, indices, {0, 0, 0, 254, 254, 254, 200, 210, 205}));
  const auto paletted = import(write("palette.yaml", "image: palette.png\nresolution: 0.05\norigin: [0, 0, 0]\n"));
  ASSERT_EQ(paletted.size(), 1u);
  EXPECT_NEAR(freeArea(paletted[0]), 132 * 0.05 * 0.05, 1e-9);
  EXPECT_EQ(paletted[0].wall.obstacles.size(), 2u);
  // In scale mode a transparent pixel is unknown: a free pixel (254) with alpha 0 is a hole.
  std::vector<int> samples = flat(rows, 1, 255);
  samples[static_cast<std::size_t>(2 * (2 * 20 + 12) + 1)] = 0;  // row 2, column 12: free, now transparent
  writeBytes("clear.png", png(20, 10, 4, 8, samples));
  const auto trinary = import(write("clear_t.yaml", "image: clear.png\nresolution: 0.05\norigin: [0, 0, 0]\n"));
  EXPECT_NEAR(freeArea(trinary[0]), 132 * 0.05 * 0.05, 1e-9);
  const auto scale = import(write("clear_s.yaml", "image: clear.png\nresolution: 0.05\norigin: [0, 0, 0]\nmode: scale\n"));
  EXPECT_NEAR(freeArea(scale[0]), 131 * 0.05 * 0.05, 1e-9);
}

// 3. A map import kept its largest free component and recorded "component 1 of 1" with the
// others gone without a word. Now the feature counts them all, the wall records how many were
// left out and their area, the manifest says so and the command prints it.
TEST_F(Import, AMapSaysWhichFreeComponentsItLeftOut) {
  auto rows = testMap();
  rows[0][15] = rows[0][16] = rows[0][17] = 254;  // a second free component of 3 pixels, top right
  rows[1][15] = rows[1][16] = rows[1][17] = 0;
  rows[0][2] = 254;  // a third of 1 pixel, top left (row 1 below it is occupied)
  rows[1][2] = 0;
  writeBytes("room.pgm", pgm(rows));
  const std::string map = write("room.yaml", "image: room.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  const std::vector<ImportedWall> walls = import(map);
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_EQ(walls[0].feature, "component 1 of 3");
  EXPECT_EQ(walls[0].dropped_components, 2u);
  EXPECT_NEAR(walls[0].dropped_component_area, 4 * 0.05 * 0.05, 1e-12);
  EXPECT_NEAR(freeArea(walls[0]), (132 - 3 - 1) * 0.05 * 0.05, 1e-9);  // row 1 lost 4 free pixels to the cuts
  ImportOptions all;
  all.all_components = true;
  const std::vector<ImportedWall> every = import(map, all);
  ASSERT_EQ(every.size(), 3u);
  EXPECT_EQ(every[2].feature, "component 3 of 3");
  EXPECT_EQ(every[0].dropped_components, 0u);
  std::string out;
  ASSERT_EQ(run("dataset import " + map + " --out " + (dir_ / "ds").string(), &out).exit_code, 0) << out;
  EXPECT_NE(out.find("(2 free map components left out, 0.01 m^2)"), std::string::npos) << out;
  const std::string manifest = slurp((dir_ / "ds" / "manifest.json").string());
  EXPECT_NE(manifest.find("\"feature\": \"component 1 of 3\""), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"dropped_components\": 2, \"dropped_component_area\": 0.01"), std::string::npos) << manifest;
}

// 4. Resources. A 1 KB PGM declaring 30000 x 30000 pixels allocated 3.5 GB and exited 70; a
// resolution of 1e155 hung in GEOS; a coordinate of 1e155 or a --transform scale of 1e300 went
// on into the geometry; NaN in GeoJSON got GDAL's internal hint. Each is now one line before any
// work.
TEST_F(Import, AbsurdSizesAreRefusedBeforeAnyWork) {
  writeBytes("huge.pgm", "P5\n30000 30000\n255\n" + std::string(1000, '\xff'));
  const std::string huge = write("huge.yaml", "image: huge.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(test::inputError([&] { import(huge); }),
            huge + ": image: '" + (dir_ / "huge.pgm").string() + "' declares 30000 x 30000 pixels, over the limit of 10^8");
  writeBytes("short.pgm", "P5\n100 100\n255\n" + std::string(1000, '\xff'));
  const std::string cut = write("short.yaml", "image: short.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(test::inputError([&] { import(cut); }),
            cut + ": image: '" + (dir_ / "short.pgm").string() + "' declares 100 x 100 pixels (10015 bytes) but holds 1015 bytes");
  writeBytes("room.pgm", pgm(testMap()));
  const std::string far = write("far.yaml", "image: room.pgm\nresolution: 1e155\norigin: [0, 0, 0]\n");
  EXPECT_EQ(test::inputError([&] { import(far); }), far + ": resolution: must be between 0.001 and 100 metres per pixel, got 1e+155");
  writeBytes("strip.pgm", pgm(std::vector<std::vector<int>>(3, std::vector<int>(120, 254))));
  const std::string wide = write("wide.yaml", "image: strip.pgm\nresolution: 100\norigin: [0, 0, 0]\n");
  EXPECT_EQ(test::inputError([&] { import(wide); }),
            wide + ": resolution: 100 m per pixel makes the 120 x 3 image 12000 m across, over 10 km");
  const std::string big = write("big.wkt", "POLYGON ((0 0, 1e155 0, 1e155 1, 0 1, 0 0))");
  EXPECT_EQ(test::inputError([&] { import(big); }),
            big + ": geometry 1: has a coordinate beyond 1e8 (1e+155, 0): no wall is drawn in such units");
  // NaN in GeoJSON (GDAL reads it): one line of ours, not GDAL's hint.
  const std::string nan = write("nan.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
      [[8.0, 47.0], [NaN, 47.0], [8.001, 47.001], [8.0, 47.001], [8.0, 47.0]]]}}]})");
  EXPECT_EQ(test::inputError([&] { import(nan); }), nan + ": feature 1: has a coordinate that is not a finite number (nan, 47)");
  ImportOptions blown;
  blown.transform = parseTransform("scale=1e300", "--transform", "(value)");
  const std::string room = write("room.wkt", "POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0))");
  EXPECT_EQ(test::inputError([&] { import(room, blown); }),
            room + ": geometry 1 (outer ring): has a point (4e+300, 0) beyond 1e8 m once placed (--transform?)");
}

// 5. Messages and what folders hold. Before: a bare PNG said "give --format" though no format
// read it; --format map parsed a PNG as YAML; a YAML key that is a list exited 70; --format
// polygon-text on the folder of instances wanted an outer_polygon there; a folder of folders of
// files held "nothing to import"; an opening across two DXF boundaries became a hole of the
// first only; WKT after a NUL byte was dropped without a word.
TEST_F(Import, ImagesAloneAndBadYamlGetOneClearLine) {
  writeBytes("room.png", png(20, 10, 0, 8, flat(testMap(), 1)));
  const std::string image = (dir_ / "room.png").string();
  const std::string needed = image + ": (file): is an image without its map_server YAML, which gives its scale and place: "
                                     "write room.yaml holding `image: room.png`, `resolution: METRES_PER_PIXEL` and "
                                     "`origin: [X, Y, YAW]` beside it and import that";
  EXPECT_EQ(test::inputError([&] { import(image); }), needed);
  ImportOptions as_map;
  as_map.format = "map";
  EXPECT_EQ(test::inputError([&] { import(image, as_map); }),
            image + ": --format: is an image without its map_server YAML, which gives its scale and place: write room.yaml "
                    "holding `image: room.png`, `resolution: METRES_PER_PIXEL` and `origin: [X, Y, YAW]` beside it and import that");
  // A key that is a list: one line and exit 2, as any other input error (it was exit 70).
  const std::string key = write("key.yaml", "? [a, b]\n: 1\nhull: [{x: 0, y: 0}, {x: 4, y: 0}, {x: 4, y: 3}]\n");
  EXPECT_EQ(test::inputError([&] { import(key); }), key + ": line 1: a key must be a plain name, got a list");
  const test::CommandRun bad = run("dataset import " + key + " --out " + (dir_ / "ds").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "ds"));
  const std::string name = write("name.yaml", "name: {a: 1}\nhull: [{x: 0, y: 0}, {x: 4, y: 0}, {x: 4, y: 3}]\n");
  EXPECT_EQ(test::inputError([&] { import(name); }), name + ": name: must be text");
  // The refusal of a multipolygon names the flag that exists.
  const std::string multi = write("multi.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon", "coordinates": [
      [[[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]], [[[10, 0], [14, 0], [14, 3], [10, 3], [10, 0]]]]}}]})");
  ImportOptions refuse;
  refuse.split_multipolygons = false;
  refuse.source_crs = "metres";
  EXPECT_EQ(test::inputError([&] { import(multi, refuse); }),
            multi + ": feature 1: is a multipolygon of 2 parts, refused by --refuse-multipolygons (without it each part becomes a wall)");
}

TEST_F(Import, APointOutsideLongitudeLatitudeIsNamedNotGdalsHint) {
  // Latitude 95 in GeoJSON: GDAL's "partial is possible if you define
  // OGR_ENABLE_PARTIAL_REPROJECTION configuration option" reached the user.
  const std::string file = write("lat95.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
      [[8.0, 47.0], [8.001, 47.0], [8.001, 95.0], [8.0, 47.001], [8.0, 47.0]]]}}]})");
  EXPECT_EQ(test::inputError([&] { import(file); }),
            file + ": feature 1: has a point (8.001, 95) outside longitude/latitude range for its geographic CRS EPSG:4326");
}

TEST_F(Import, FoldersOfFoldersAndPolygonTextSetsAreSearched) {
  writeBytes("eth/poly_007/outer_polygon", "0 0\n20 0\n20 10\n0 10\n");
  writeBytes("eth/poly_008/outer_polygon", "0 0\n5 0\n5 5\n");
  ImportOptions polygon_text;
  polygon_text.format = "polygon-text";
  const std::vector<ImportedWall> set = import((dir_ / "eth").string(), polygon_text);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set[1].wall.name, "poly_008");
  writeBytes("tree/site_a/rooms/a.wkt", "POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0))");
  writeBytes("tree/site_b/b.wkt", "POLYGON ((0 0, 3 0, 3 3, 0 3, 0 0))");
  writeBytes("tree/site_b/notes.txt", "not a wall");
  const std::vector<ImportedWall> tree = import((dir_ / "tree").string());
  ASSERT_EQ(tree.size(), 2u);
  EXPECT_DOUBLE_EQ(signedArea(tree[0].wall.boundary), 12.0);
  EXPECT_DOUBLE_EQ(signedArea(tree[1].wall.boundary), 9.0);
}

TEST_F(Import, AnOpeningAcrossTwoDxfBoundariesIsAHoleInBoth) {
  // Two 5 x 4 walls side by side (x 0..5 and 5..10) and a 2 x 2 opening across the line
  // between them (x 4..6, y 1..3): 1 x 2 of it in each.
  const std::string file = write("two.dxf", "0\nSECTION\n2\nENTITIES\n" + lwpolyline("walls", {{0, 0}, {5, 0}, {5, 4}, {0, 4}}) +
                                                lwpolyline("walls", {{5, 0}, {10, 0}, {10, 4}, {5, 4}}) +
                                                lwpolyline("openings", {{4, 1}, {6, 1}, {6, 3}, {4, 3}}) + "0\nENDSEC\n0\nEOF\n");
  ImportOptions o;
  o.dxf_boundary_layer = "walls";
  o.dxf_obstacle_layers = {"openings"};
  const std::vector<ImportedWall> walls = import(file, o);
  ASSERT_EQ(walls.size(), 2u);
  for (const ImportedWall& w : walls) {
    ASSERT_EQ(w.wall.obstacles.size(), 1u) << w.wall.name;
    EXPECT_DOUBLE_EQ(holeArea(w.wall, 0), 4.0);
    const Region free = subtract(regionFromRings({w.wall.boundary}), regionFromRings({w.wall.obstacles[0].polygon}));
    EXPECT_NEAR(area(free), 20.0 - 2.0, 1e-6) << w.wall.name;
  }
}

TEST_F(Import, AWallNamedManifestIsWrittenBesideTheManifest) {
  // A wall named "manifest" took manifest.json, which the manifest needs: "written twice".
  const std::string wkt = write("manifest.wkt", "POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0))");
  std::string out;
  ASSERT_EQ(run("dataset import " + wkt + " --out " + (dir_ / "ds").string(), &out).exit_code, 0) << out;
  const Dataset d = readDataset((dir_ / "ds").string());
  ASSERT_EQ(d.walls.size(), 1u);
  EXPECT_EQ(d.walls[0].name, "manifest");
  EXPECT_EQ(d.entries[0].file, "manifest-2.json");
}

TEST_F(Import, WktWithANulByteIsRefused) {
  const std::string file =
      writeBytes("rooms.wkt", std::string("POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0))\n", 36) + std::string(1, '\0') +
                                  "POLYGON ((10 0, 14 0, 14 3, 10 3, 10 0))\n");
  EXPECT_EQ(test::inputError([&] { import(file); }), file + ": (text): contains a NUL byte at offset 36 (not a WKT text file)");
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
