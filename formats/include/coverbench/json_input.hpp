#pragma once
/// The one strict JSON reader for every file CoverBench reads (walls, plans, manifests): a text
/// file (no NUL byte, valid UTF-8), one JSON value with nothing after it, no duplicate keys.
/// Includes nlohmann/json.hpp: include it only from the translation units that parse JSON.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>

namespace coverbench {

/// The deepest nesting of arrays and objects any document may have (a wall file needs 5).
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Parses `text` strictly. Throws InputError(source, field, problem): field "(document)" for
/// syntax errors, NUL bytes, invalid UTF-8 and nesting deeper than kMaxJsonDepth; the key's path (e.g. `obstacles[2].x`) for a
/// duplicate key.
nlohmann::json parseJsonStrict(const std::string& text, const std::string& source);

}  // namespace coverbench
