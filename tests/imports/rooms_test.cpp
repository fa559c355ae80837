// Rooms from a segmentation image (`dataset import MAP.yaml --rooms SEGMENTATION`, docs/datasets.md):
// a map and its labels written here, each room's wall, name and area and every dropped pixel
// against hand counts, the identity "kept = the map's free - dropped", and hostile segmentations
// refused with one line and nothing written.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/wall_import.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

constexpr double kPixel = 0.05 * 0.05;  // the test map's pixel area, m^2

/// 16 x 8 pixels at 0.05 m (row 0 at the top). Occupied (0) all round; inside, columns 1-14 of
/// rows 1-6 are free (254) but for two walls with a door each: column 5 (door at row 3) and
/// column 10 (door at row 4); and one unknown (128) pixel at column 2, row 5. Free: 84 - 5 - 5
/// - 1 = 73 pixels: room A (columns 1-4) 23, room B (6-9) 24, room C (11-14) 24, the doors 2.
std::vector<std::vector<int>> houseMap() {
  std::vector<std::vector<int>> rows(8, std::vector<int>(16, 0));
  for (int r = 1; r <= 6; ++r)
    for (int c = 1; c <= 14; ++c) rows[r][c] = (c == 5 && r != 3) || (c == 10 && r != 4) ? 0 : 254;
  rows[5][2] = 128;
  return rows;
}

/// The labels: A is 10 (its 24 pixels, the unknown one among them) and 10 also marks the wall
/// pixel at column 5, row 1; B is 20, and 20 also marks one pixel of C's (column 14, row 6),
/// detached from B; C is 30 but for that pixel and a closet of 2 pixels, label 40 (columns 13-14,
/// row 1); 50 marks the occupied corner (0, 0) alone. The doors are 0.
std::vector<std::vector<int>> houseLabels() {
  std::vector<std::vector<int>> rows(8, std::vector<int>(16, 0));
  for (int r = 1; r <= 6; ++r)
    for (int c = 1; c <= 14; ++c) rows[r][c] = c <= 4 ? 10 : (c >= 6 && c <= 9) ? 20 : c >= 11 ? 30 : 0;
  rows[1][5] = 10;
  rows[6][14] = 20;
  rows[1][13] = rows[1][14] = 40;
  rows[0][0] = 50;
  return rows;
}

class Rooms : public test::CommandTest {
 protected:
  std::string writeBytes(const std::string& name, const std::string& bytes) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
  /// The house map (house.yaml, house.pgm) and its labels (labels.pgm); the YAML's path.
  std::string writeHouse() {
    writeBytes("house.pgm", test::pgm(houseMap()));
    writeBytes("labels.pgm", test::pgm(houseLabels()));
    return write("house.yaml", "image: house.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  }
  ImportResult importRooms(const std::string& map, const std::string& segmentation, double min_room_area = 0.01) {
    ImportOptions o;
    o.rooms = segmentation;
    o.min_room_area = min_room_area;
    return importWalls({map}, o);
  }
  std::string seg(const std::string& name) { return (dir_ / name).string(); }
};

/// A wall's free area: its boundary less its holes.
double freeArea(const Wall& w) {
  double a = signedArea(w.boundary);
  for (const Obstacle& o : w.obstacles) a -= signedArea(o.polygon);
  return a;
}

TEST_F(Rooms, OneWallPerRoomAndEveryDroppedPixelCounted) {
  const std::string map = writeHouse();
  const ImportResult result = importRooms(map, seg("labels.pgm"));
  // Rooms 10, 20 and 30 are walls; 40 (2 pixels, 0.005 m^2) is under --min-room-area 0.01; 50
  // has no free pixel.
  ASSERT_EQ(result.walls.size(), 3u);
  const std::vector<std::string> names = {"house-room-10", "house-room-20", "house-room-30"};
  const std::vector<int> labels = {10, 20, 30};
  const std::vector<double> kept = {23, 24, 21};  // A less its unknown pixel; B; C less the closet and B's pixel
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(result.walls[i].wall.name, names[i]);
    EXPECT_EQ(result.walls[i].room, labels[i]);
    EXPECT_EQ(result.walls[i].feature, "room " + std::to_string(labels[i]));
    // Axis-aligned pixel edges keep every corner at half a pixel's tolerance: the wall's area is
    // its pixels'.
    EXPECT_NEAR(freeArea(result.walls[i].wall), kept[i] * kPixel, 1e-9) << names[i];
  }
  ASSERT_EQ(result.walls[0].wall.obstacles.size(), 1u);  // A's unknown pixel is a hole
  EXPECT_NEAR(signedArea(result.walls[0].wall.obstacles[0].polygon), kPixel, 1e-12);
  const Box a = boundingBox(result.walls[0].wall.boundary);  // columns 1-4, rows 1-6 of 8
  EXPECT_NEAR(a.min_x, 0.05, 1e-9);
  EXPECT_NEAR(a.max_x, 0.25, 1e-9);
  EXPECT_NEAR(a.min_y, 0.05, 1e-9);
  EXPECT_NEAR(a.max_y, 0.35, 1e-9);

  ASSERT_EQ(result.rooms.size(), 1u);
  const RoomsReport& report = result.rooms[0];
  EXPECT_EQ(report.free_pixels, 73u);
  EXPECT_EQ(report.unlabelled_free_pixels, 2u);  // the doors
  ASSERT_EQ(report.rooms.size(), 5u);
  struct Expected {
    int label;
    std::string wall, dropped;
    std::size_t free, parts, kept, not_free;
  };
  const std::vector<Expected> expected = {
      {10, "house-room-10", "", 23, 1, 23, 2},  // the unknown pixel and the wall pixel are not free
      {20, "house-room-20", "", 25, 2, 24, 0},  // its pixel in C is a second part, dropped
      {30, "house-room-30", "", 21, 1, 21, 0},
      {40, "", "under --min-room-area", 2, 1, 0, 0},
      {50, "", "no free pixel", 0, 0, 0, 1}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const RoomReport& r = report.rooms[i];
    const Expected& e = expected[i];
    EXPECT_EQ(r.label, e.label);
    EXPECT_EQ(r.wall, e.wall) << e.label;
    EXPECT_EQ(r.dropped, e.dropped) << e.label;
    EXPECT_EQ(r.free_pixels, e.free) << e.label;
    EXPECT_EQ(r.parts, e.parts) << e.label;
    EXPECT_EQ(r.kept_pixels, e.kept) << e.label;
    EXPECT_EQ(r.not_free_pixels, e.not_free) << e.label;
  }
  // The identity: the rooms' areas are the map's free area less what was dropped. Dropped: the 2
  // doors, B's detached pixel, the closet's 2. In pixels exactly; in m^2 as the walls measure it.
  EXPECT_EQ(report.droppedPixels(), 5u);
  EXPECT_EQ(report.keptPixels(), 68u);
  EXPECT_EQ(report.keptPixels(), report.free_pixels - report.droppedPixels());
  EXPECT_EQ(report.notFreePixels(), 3u);
  double walls_area = 0.0;
  for (const ImportedWall& w : result.walls) walls_area += freeArea(w.wall);
  EXPECT_NEAR(walls_area, report.area(report.free_pixels) - report.area(report.droppedPixels()), 1e-9);
  EXPECT_NEAR(walls_area, (73 - 5) * kPixel, 1e-9);

  // Without --min-room-area the closet is a wall of its own, and the sum still holds.
  const ImportResult all = importRooms(map, seg("labels.pgm"), 0.0);
  ASSERT_EQ(all.walls.size(), 4u);
  EXPECT_EQ(all.walls[3].wall.name, "house-room-40");
  EXPECT_NEAR(freeArea(all.walls[3].wall), 2 * kPixel, 1e-12);
  EXPECT_EQ(all.rooms[0].droppedPixels(), 3u);
  EXPECT_EQ(all.rooms[0].keptPixels(), all.rooms[0].free_pixels - all.rooms[0].droppedPixels());
}

TEST_F(Rooms, TheCommandWritesTheRoomsAndSaysWhatItDropped) {
  const std::string map = writeHouse();
  std::string out;
  const std::string ds = (dir_ / "ds").string();
  ASSERT_EQ(run("dataset import " + map + " --rooms " + seg("labels.pgm") + " --min-room-area 0.01 --out " + ds, &out).exit_code, 0)
      << out;
  const Dataset d = readDataset(ds);
  ASSERT_EQ(d.walls.size(), 3u);
  EXPECT_EQ(d.walls[1].name, "house-room-20");
  EXPECT_NE(out.find("3 of 5 labels are walls; 68 of the map's 73 pixels free kept (0.17 m^2 of 0.1825 m^2), 5 dropped "
                     "(0.0125 m^2): 2 unlabelled, 3 of rooms; 3 pixels labelled but not free in the map\n"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("  room 20: house-room-20, 24 of 25 pixels free kept (0.06 m^2), 1 of 2 parts dropped (1 pixel, 0.0025 m^2)\n"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("  room 40: dropped (under --min-room-area): 2 pixels free (0.005 m^2)\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  room 50: dropped (no free pixel): 0 pixels free (0 m^2); 1 pixel labelled but not free\n"),
            std::string::npos)
      << out;
  const std::string manifest = slurp(ds + "/manifest.json");
  EXPECT_NE(manifest.find("\"rooms\": \"" + seg("labels.pgm") + "\", \"min_room_area\": 0.01"), std::string::npos)
      << manifest;
  EXPECT_NE(manifest.find("\"sha256\": \"" + sha256Hex(slurp(seg("labels.pgm"))) + "\""), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"feature\": \"room 30\""), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"room\": 30}"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"free_pixels\": 73, \"kept_pixels\": 68, \"dropped_pixels\": 5, \"unlabelled_free_pixels\": 2, "
                          "\"labelled_not_free_pixels\": 3, \"free_area\": 0.1825, \"kept_area\": 0.17, \"dropped_area\": 0.0125"),
            std::string::npos)
      << manifest;
  EXPECT_NE(manifest.find("{\"label\": 40, \"wall\": \"\", \"dropped\": \"under --min-room-area\", \"free_pixels\": 2, \"parts\": 1, "
                          "\"kept_pixels\": 0, \"dropped_pixels\": 2, \"not_free_pixels\": 0, \"kept_area\": 0.0, \"dropped_area\": 0.005}"),
            std::string::npos)
      << manifest;
  // Same input, same bytes.
  ASSERT_EQ(run("dataset import " + map + " --rooms " + seg("labels.pgm") + " --min-room-area 0.01 --out " + ds + "2").exit_code, 0);
  EXPECT_EQ(slurp(ds + "2/manifest.json"), manifest);
  // A link to the segmentation is read as the file it names (as the map's image is).
  fs::create_symlink(seg("labels.pgm"), seg("link.pgm"));
  EXPECT_EQ(importRooms(map, seg("link.pgm")).rooms[0].keptPixels(), 68u);
}

TEST_F(Rooms, AConfigImportsAMapsRooms) {
  writeHouse();
  const std::string config = write("exp.yaml",
                                   "name: rooms\noutput: out\n"
                                   "datasets:\n  - import: house.yaml\n    rooms: labels.pgm\n    min_room_area: 0.01\n"
                                   "planners: [zigzag]\ntool: {width: 0.1, clearance: 0.01}\n");
  const ExperimentConfig c = loadExperimentConfig(config);
  ASSERT_EQ(c.datasets.size(), 1u);
  EXPECT_EQ(c.datasets[0].count, 3u);
  const std::vector<WallEntry> walls = loadWalls(c);
  ASSERT_EQ(walls.size(), 3u);
  EXPECT_EQ(walls[2].wall.name, "house-room-30");
  write("all.yaml", "name: x\noutput: out\ndatasets:\n  - import: house.yaml\n    rooms: labels.pgm\n    all_components: true\n"
                    "planners: [zigzag]\n");
  EXPECT_EQ(test::inputError([&] { loadExperimentConfig((dir_ / "all.yaml").string()); }),
            (dir_ / "all.yaml").string() + ":5: datasets[0].rooms: keeps each room's largest part: --all-components does not apply");
}

TEST_F(Rooms, HostileSegmentationsAreRefusedWithOneLine) {
  const std::string map = writeHouse();
  auto refused = [&](const std::string& segmentation) { return test::inputError([&] { importRooms(map, segmentation); }); };
  const std::string image = (dir_ / "house.pgm").string();
  // Another size than the map's image: both named.
  auto narrow = houseLabels();
  for (auto& row : narrow) row.pop_back();
  writeBytes("narrow.pgm", test::pgm(narrow));
  EXPECT_EQ(refused(seg("narrow.pgm")), map + ": --rooms: '" + seg("narrow.pgm") + "' is 15 x 8 pixels but the map's image '" + image +
                                            "' is 16 x 8: a segmentation labels the map's own pixels");
  // Not an image.
  writeBytes("labels.txt", "room 1: kitchen\n");
  EXPECT_EQ(refused(seg("labels.txt")).rfind(map + ": --rooms: cannot read the image '" + seg("labels.txt") + "': ", 0), 0u)
      << refused(seg("labels.txt"));
  // Over the map image's pixel limit, from the header alone.
  writeBytes("huge.pgm", "P5\n30000 30000\n255\n" + std::string(1000, '\x01'));
  EXPECT_EQ(refused(seg("huge.pgm")), map + ": --rooms: '" + seg("huge.pgm") + "' declares 30000 x 30000 pixels, over the limit of 10^8");
  // A FIFO is refused, not waited on; a missing file and a folder likewise.
  ASSERT_EQ(::mkfifo(seg("fifo.pgm").c_str(), 0600), 0);
  EXPECT_EQ(refused(seg("fifo.pgm")), map + ": --rooms: '" + seg("fifo.pgm") + "' is not a file");
  EXPECT_EQ(refused(seg("missing.pgm")), map + ": --rooms: '" + seg("missing.pgm") + "' is not a file");
  // A coloured pixel: labels are grey values.
  std::string ppm = "P6\n16 8\n255\n";
  for (const auto& row : houseLabels())
    for (int v : row) ppm += std::string(3, static_cast<char>(v));
  ppm[12 + 3 * (2 * 16 + 3)] = static_cast<char>(255);  // column 3, row 2: red
  writeBytes("colour.ppm", ppm);
  EXPECT_EQ(refused(seg("colour.ppm")), map + ": --rooms: '" + seg("colour.ppm") +
                                            "' has a pixel that is not grey at column 3, row 2 (255, 10, 10): each room's label is one grey value");
  // More labels than rooms a map can sensibly have (16 bits: 1200 labels).
  std::vector<std::vector<int>> big_map(40, std::vector<int>(30, 254)), big_labels(40, std::vector<int>(30, 0));
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 30; ++c) big_labels[r][c] = 1 + r * 30 + c;
  writeBytes("big.pgm", test::pgm(big_map));
  writeBytes("many.pgm", test::pgm(big_labels, 65535));
  const std::string big = write("big.yaml", "image: big.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(test::inputError([&] { importRooms(big, seg("many.pgm")); }),
            big + ": --rooms: '" + seg("many.pgm") + "' holds 1200 labels, over the limit of 1000 rooms");
  // No label at all.
  writeBytes("empty.pgm", test::pgm(std::vector<std::vector<int>>(8, std::vector<int>(16, 0))));
  EXPECT_EQ(refused(seg("empty.pgm")), map + ": --rooms: '" + seg("empty.pgm") + "' labels no room (every pixel is 0)");
  // What --rooms applies to.
  const std::string wkt = write("room.wkt", "POLYGON ((0 0, 4 0, 4 3, 0 3, 0 0))");
  EXPECT_EQ(test::inputError([&] { importRooms(wkt, seg("labels.pgm")); }),
            wkt + ": --rooms: needs a map_server map (a YAML naming its image), not wkt");
  ImportOptions two;
  two.rooms = seg("labels.pgm");
  EXPECT_EQ(test::inputError([&] { importWalls({map, map}, two); }),
            "--rooms: (value): labels the rooms of one map: give its YAML as the only source");
  two.all_components = true;
  EXPECT_EQ(test::inputError([&] { importWalls({map}, two); }),
            "--rooms: (value): keeps each room's largest part: --all-components does not apply");
  ImportOptions alone;
  alone.min_room_area = 1;
  EXPECT_EQ(test::inputError([&] { importWalls({map}, alone); }), "--min-room-area: (value): applies to --rooms only");
}

// A path that is not UTF-8, and a refusal through the command: one line, exit 2, nothing written.
TEST_F(Rooms, TheCommandRefusesWithOneLineAndWritesNothing) {
  const std::string map = writeHouse();
  writeBytes("narrow.pgm", "P5\n3 3\n255\n" + std::string(9, '\x01'));
  const std::string ds = (dir_ / "ds").string();
  const test::CommandRun bad = run("dataset import " + map + " --rooms " + seg("narrow.pgm") + " --out " + ds);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("is 3 x 3 pixels but the map's image"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(ds));
  // A path that is not UTF-8 cannot be recorded in the manifest: refused by name (a map's was an
  // internal error, exit 70, from the JSON writer).
  const std::string odd = seg("labels\xff.pgm");
  fs::copy_file(seg("labels.pgm"), odd);
  const test::CommandRun latin = run("dataset import " + map + " --rooms '" + odd + "' --out " + ds);
  EXPECT_EQ(latin.exit_code, 2);
  EXPECT_EQ(latin.err, "coverbench: " + map + ": --rooms: '" + seg("labels\xef\xbf\xbd.pgm") +
                           "' is not a valid UTF-8 path (the manifest records each file's path as text): rename it\n");
  EXPECT_FALSE(fs::exists(ds));
  // A path with a line break: refused on one line, the break shown as '?', whether the file is
  // there or not.
  fs::copy_file(seg("labels.pgm"), seg("two\nlines.pgm"));
  for (const std::string name : {"two\nlines.pgm", "none\n.pgm"}) {
    const test::CommandRun broken = run("dataset import " + map + " --rooms '" + seg(name) + "' --out " + ds);
    EXPECT_EQ(broken.exit_code, 2);
    std::string shown = seg(name);
    std::replace(shown.begin(), shown.end(), '\n', '?');
    EXPECT_EQ(broken.err, "coverbench: " + map + ": --rooms: '" + shown +
                              "' holds a control character (a line break, a tab): rename it\n");
    EXPECT_FALSE(fs::exists(ds));
  }
  const std::string odd_map = (dir_ / "house\xff.yaml").string();
  fs::copy_file(map, odd_map);
  const test::CommandRun odd_run = run("dataset import '" + odd_map + "' --out " + ds);
  EXPECT_EQ(odd_run.exit_code, 2);
  EXPECT_EQ(odd_run.err, "coverbench: " + (dir_ / "house\xef\xbf\xbd.yaml").string() +
                             ": (path): is not a valid UTF-8 path (the manifest records each file's path as text): rename it\n");
  EXPECT_FALSE(fs::exists(ds));
}

}  // namespace
}  // namespace coverbench
