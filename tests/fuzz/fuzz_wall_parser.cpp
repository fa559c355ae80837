// The wall parser on any bytes: a wall, or InputError naming the source. Anything else escaping
// (another exception type, a crash, a sanitizer report) is a finding. A parsed wall must write
// back to JSON that parses to the same JSON (the canonical form is a fixed point).
#include <cstdint>
#include <string>

#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace coverbench;
  const std::string text(reinterpret_cast<const char*>(data), size);
  Wall wall;
  try {
    wall = parseWallJson(text, "fuzz.json");
  } catch (const InputError& e) {
    if (e.source().empty() || e.problem().empty()) fuzz::broken(std::string("InputError without source or problem: ") + e.what());
    return 0;
  }
  const std::string once = wallToJson(wall);
  std::string twice;
  try {
    twice = wallToJson(parseWallJson(once, "canonical.json"));
  } catch (const InputError& e) {
    fuzz::broken(std::string("a parsed wall's own JSON is refused: ") + e.what());
  }
  if (once != twice) fuzz::broken("the canonical JSON of a wall is not a fixed point");
  return 0;
}
