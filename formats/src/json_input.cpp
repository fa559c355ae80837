#include "coverbench/json_input.hpp"

#include <cmath>
#include <set>
#include <vector>

#include "coverbench/files.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {
namespace {

using nlohmann::json;

/// Where the parser is: one frame per open object or array, for duplicate keys and field paths.
struct Frame {
  bool object = false;
  std::set<std::string> keys;
  std::string key;         ///< the object's current key
  long long index = -1;    ///< the array's current element
};

std::string fieldPath(const std::vector<Frame>& stack) {
  std::string out;
  for (const Frame& f : stack) {
    if (f.object && !f.key.empty()) out += (out.empty() ? "" : ".") + f.key;
    if (!f.object && f.index >= 0) out += "[" + std::to_string(f.index) + "]";
  }
  return out.empty() ? "(document)" : out;
}

/// Whether arrays and objects nest deeper than `most` anywhere in `text` (read on the bytes,
/// strings skipped), so that nothing deeper is built, printed or freed by recursion.
bool nestsDeeperThan(const std::string& text, std::size_t most) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > most) return true;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return false;
}

/// The first duplicate key's path, found by a SAX pass (no document built). nlohmann's callback
/// parser, which this replaces, scans a whole array each time one of its objects closes (to drop
/// discarded values): quadratic in the elements, 9 s for a wall of 100,000 obstacles.
class DuplicateKeys final : public nlohmann::json_sax<json> {
 public:
  const std::string& duplicate() const { return duplicate_; }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    Frame& f = stack_.back();
    f.key = k;
    if (f.keys.insert(k).second) return true;
    duplicate_ = fieldPath(stack_);
    return false;  // the first is enough
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  /// A value starts inside an array: count it, so paths name the element.
  bool value() {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
    return true;
  }
  bool open(bool object) {
    value();
    stack_.push_back(Frame{object, {}, {}, -1});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  std::vector<Frame> stack_;
  std::string duplicate_;
};

}  // namespace

json parseJsonStrict(const std::string& text, const std::string& source) {
  requireText(text, source);
  if (nestsDeeperThan(text, kMaxJsonDepth))
    throw InputError(source, "(document)", "arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, trailing data, number overflow
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(source, "(document)", "malformed JSON: " + what);
  }
  // Well formed: now each object's keys, once each.
  DuplicateKeys keys;
  json::sax_parse(text, &keys);
  if (!keys.duplicate().empty()) throw InputError(source, keys.duplicate(), "duplicate key (each key may appear once)");
  return doc;
}

void JsonFields::fail(const std::string& field, const std::string& problem) const { throw InputError(source_, field, problem); }

void JsonFields::onlyKeys(const nlohmann::json& obj, const std::string& where, const std::set<std::string>& allowed) const {
  for (const auto& [key, value] : obj.items())
    if (!allowed.count(key)) fail(where.empty() ? key : where + "." + key, "unknown key");
}

std::string JsonFields::text(const nlohmann::json& obj, const std::string& key, const std::string& field, bool required) const {
  if (!obj.contains(key)) {
    if (required) fail(field, "missing");
    return "";
  }
  if (!obj[key].is_string()) fail(field, "must be a string");
  return obj[key].get<std::string>();
}

double JsonFields::number(const nlohmann::json& v, const std::string& field) const {
  if (!v.is_number()) fail(field, "must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(field, "must be finite");
  return d;
}

}  // namespace coverbench
