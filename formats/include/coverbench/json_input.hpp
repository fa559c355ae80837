#pragma once
/// The one strict JSON reader for every file CoverBench reads (walls, plans, manifests): a text
/// file (no NUL byte, valid UTF-8), one JSON value with nothing after it, no duplicate keys.
/// Includes nlohmann/json.hpp: include it only from the translation units that parse JSON.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <set>
#include <string>

namespace coverbench {

/// The deepest nesting of arrays and objects any document may have (a wall file needs 5).
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Parses `text` strictly. Throws InputError(source, field, problem): field "(document)" for
/// syntax errors, NUL bytes, invalid UTF-8 and nesting deeper than kMaxJsonDepth; the key's path (e.g. `obstacles[2].x`) for a
/// duplicate key.
nlohmann::json parseJsonStrict(const std::string& text, const std::string& source);

/// Reads a parsed document's fields; every error is an InputError naming `source` and the field
/// (its path in the document, as the caller spells it: `params[2].default`).
class JsonFields {
 public:
  explicit JsonFields(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const;
  /// Every key of `obj` is one of `allowed` ("unknown key" at `where`.key otherwise).
  void onlyKeys(const nlohmann::json& obj, const std::string& where, const std::set<std::string>& allowed) const;
  /// obj[key], a string; "" when it is absent and not `required`.
  std::string text(const nlohmann::json& obj, const std::string& key, const std::string& field, bool required = true) const;
  /// `v`, a finite number.
  double number(const nlohmann::json& v, const std::string& field) const;

 private:
  std::string source_;
};

}  // namespace coverbench
