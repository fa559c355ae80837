// Wall generators and dataset folders: deterministic bytes, valid walls over thousands of seeds,
// manifests that catch edited files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "coverbench/datasets.hpp"
#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> generatorFamilies() {
  std::vector<std::string> out;
  for (const FamilyInfo& f : wallFamilies())
    if (!f.fixed_suite) out.push_back(f.name);
  return out;
}

TEST(Datasets, SameFamilySeedAndIndexGiveTheSameBytes) {
  for (const std::string& family : generatorFamilies())
    for (std::uint64_t seed : {1ULL, 2ULL, 987654321ULL}) {
      const std::string a = wallToJson(generateWall(family, seed, 3));
      const std::string b = wallToJson(generateWall(family, seed, 3));
      EXPECT_EQ(a, b) << family;
      EXPECT_NE(a, wallToJson(generateWall(family, seed + 1, 3))) << family << ": the seed must matter";
      EXPECT_NE(a, wallToJson(generateWall(family, seed, 4))) << family << ": the index must matter";
    }
}

TEST(Datasets, WallDoesNotDependOnHowManyAreGenerated) {
  for (const char* family : {"residential", "random", "narrow"}) {
    const std::vector<Wall> few = generateWalls(family, 5, 3), many = generateWalls(family, 5, 20);
    for (std::size_t i = 0; i < few.size(); ++i) EXPECT_EQ(wallToJson(few[i]), wallToJson(many[i])) << family << " " << i;
  }
}

TEST(Datasets, GoldenHashesPinTheBytesAcrossMachinesAndVersions) {
  // If a generator changes on purpose, these change with it (and datasets/README.md says so).
  // If they change by accident (a compiler, a libm, a refactoring), this fails.
  const std::map<std::string, std::string> golden = {
#include "data/dataset_golden.inc"
  };
  for (const auto& [family, hash] : golden) EXPECT_EQ(sha256Hex(wallToJson(generateWall(family, 1, 0))), hash) << family;
  EXPECT_EQ(golden.size(), generatorFamilies().size());
}

class GeneratedFamily : public testing::TestWithParam<std::string> {};

TEST_P(GeneratedFamily, ThousandsOfSeedsAllPassTheValidatorAndRoundTrip) {
  const std::string family = GetParam();
  // Thousands of walls per family; fewer where each wall is large or heavy to validate (circles;
  // a field's trees are circles of up to 10 m, traced to 1e-6 m: 2000 fields took 567 s under
  // the sanitizers).
  const int count = family == "stress" ? 40 : family == "field" ? 200 : family == "facade" ? 500
                  : (family == "industrial" || family == "gable" || family == "stairwell") ? 1000 : 2000;
  for (int seed = 0; seed < count; ++seed) {
    const Wall w = generateWall(family, static_cast<std::uint64_t>(seed), 0);
    ASSERT_NO_THROW(validateWall(w, w.name)) << family << " seed " << seed;
    const std::string text = wallToJson(w);
    Wall again;
    ASSERT_NO_THROW(again = parseWallJson(text, w.name)) << text;
    ASSERT_EQ(wallToJson(again), text) << "round trip changes the bytes";
  }
}

INSTANTIATE_TEST_SUITE_P(AllFamilies, GeneratedFamily, testing::ValuesIn(generatorFamilies()),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(Datasets, FamiliesHaveTheirDocumentedShape) {
  for (int seed = 0; seed < 200; ++seed) {
    const Wall r = generateWall("residential", seed, 0);
    const Box b = boundingBox(r.boundary);
    EXPECT_GE(b.height(), 2.4);
    EXPECT_LE(b.height(), 3.0);
    for (const Obstacle& o : r.obstacles)
      if (o.label == "door") {
        EXPECT_EQ(boundingBox(o.polygon).min_y, 0.0) << "doors stand on the floor";
      }
    const Wall s = generateWall("stress", seed % 5, 0);
    EXPECT_GE(s.obstacles.size(), 100u);
    EXPECT_GE(boundingBox(s.boundary).width(), 40.0);
    bool circle = false;
    for (const Obstacle& o : generateWall("industrial", seed, 0).obstacles) circle = circle || o.type == ObstacleType::Circle;
    EXPECT_TRUE(circle) << "industrial walls have pipes, seed " << seed;
  }
  EXPECT_EQ(suiteSize("seed-cases"), 9u);
  EXPECT_EQ(generateWalls("seed-cases", 0, 0).size(), 9u);
}

class DatasetFolder : public test::TempDirTest {};

TEST_F(DatasetFolder, WriteReadAndHashes) {
  const std::vector<Wall> walls = generateWalls("gable", 3, 5);
  const Dataset written = writeDataset(dir_.string(), "gable", 3, walls);
  ASSERT_EQ(written.entries.size(), 5u);
  const std::string manifest = readFile((dir_ / "manifest.json").string());
  // Writing the same dataset again changes nothing; a different one is refused.
  EXPECT_NO_THROW(writeDataset(dir_.string(), "gable", 3, walls));
  EXPECT_EQ(readFile((dir_ / "manifest.json").string()), manifest);
  EXPECT_THROW(writeDataset(dir_.string(), "gable", 4, generateWalls("gable", 4, 5)), InputError);
  const Dataset read = readDataset(dir_.string());
  ASSERT_EQ(read.walls.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(wallToJson(read.walls[i]), wallToJson(walls[i]));
    EXPECT_EQ(read.entries[i].sha256, sha256Hex(readFile((dir_ / read.entries[i].file).string())));
  }
  EXPECT_NE(describeDataset(read).find("walls: 5"), std::string::npos);
  // An edited wall file no longer matches its manifest entry.
  std::ofstream(dir_ / read.entries[2].file, std::ios::app) << " ";
  try {
    readDataset(dir_.string());
    FAIL() << "an edited file must be detected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("walls[2].sha256"), std::string::npos) << e.what();
  }
}

TEST_F(DatasetFolder, NonEmptyFolderWithoutManifestIsRefused) {
  std::ofstream(dir_ / "notes.txt") << "mine";
  EXPECT_THROW(writeDataset(dir_.string(), "random", 1, generateWalls("random", 1, 2)), InputError);
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
}

}  // namespace
}  // namespace coverbench
