#pragma once
/// Seeded generators of realistic walls, named suites, and dataset folders (wall files plus a
/// manifest with content hashes). Same family, index and seed: the same wall, byte for byte, on
/// every machine (see datasets/README.md for how that is kept).
#include <cstdint>
#include <string>
#include <vector>

#include "coverbench/wall.hpp"

namespace coverbench {

/// A generator family or a fixed suite, for listings and documentation.
struct FamilyInfo {
  std::string name;
  std::string summary;
  bool fixed_suite = false;  ///< a suite ignores the seed and has a fixed number of walls
};
const std::vector<FamilyInfo>& wallFamilies();
/// Throws InputError(source, field, ...) when `family` is not a known family or suite.
const FamilyInfo& findFamily(const std::string& family, const std::string& source, const std::string& field);

/// Wall number `index` of `family` for `seed`. It does not depend on how many walls are asked
/// for, so a dataset of 10 walls is the first 10 of a dataset of 1000. Every wall passes
/// validateWall. For a fixed suite, `index` must be below its size and the seed is ignored.
Wall generateWall(const std::string& family, std::uint64_t seed, std::size_t index);
/// The walls 0..count-1 (for a suite: all of them when count is 0, else the first `count`).
std::vector<Wall> generateWalls(const std::string& family, std::uint64_t seed, std::size_t count);
/// Number of walls in a fixed suite.
std::size_t suiteSize(const std::string& suite);

/// One wall of a dataset folder.
struct DatasetEntry {
  std::string file;    ///< file name inside the folder
  std::string name;    ///< the wall's name
  std::string family;  ///< generator family, suite, or "file" for walls read from a folder
  std::string sha256;  ///< of the file's bytes
};
struct Dataset {
  std::string family;
  std::uint64_t seed = 0;
  std::vector<DatasetEntry> entries;
  std::vector<Wall> walls;  ///< same order as entries
  /// For imported walls (family "import"): the manifest's "import" object as JSON text (sources
  /// with their hashes, the options, each wall's source and origin); empty otherwise.
  std::string import_record;
};

/// Writes the walls and `manifest.json` into `dir` (created if missing). Refuses a folder that
/// already holds a different dataset. Returns the manifest as written.
Dataset writeDataset(const std::string& dir, const std::string& family, std::uint64_t seed,
                     const std::vector<Wall>& walls, const std::string& import_record = "");
/// Reads a dataset folder: with a manifest, the files it lists (hashes checked); without one,
/// every *.json wall file in name order. Throws InputError naming the file and the problem.
Dataset readDataset(const std::string& dir);
/// A human summary of a dataset folder (counts, sizes, obstacle kinds), several lines.
std::string describeDataset(const Dataset& dataset);

}  // namespace coverbench
