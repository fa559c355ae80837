#include "coverbench/json_input.hpp"

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

}  // namespace

json parseJsonStrict(const std::string& text, const std::string& source) {
  requireText(text, source);
  if (nestsDeeperThan(text, kMaxJsonDepth))
    throw InputError(source, "(document)", "arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  std::vector<Frame> stack;
  std::string duplicate;  // the path of the first duplicate key
  // A value starts inside an array: count it, so paths name the element.
  auto startValue = [&] {
    if (!stack.empty() && !stack.back().object) ++stack.back().index;
  };
  const json::parser_callback_t track = [&](int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        startValue();
        stack.push_back(Frame{event == json::parse_event_t::object_start, {}, {}, -1});
        break;
      case json::parse_event_t::key: {
        Frame& f = stack.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second && duplicate.empty()) duplicate = fieldPath(stack);
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack.pop_back();
        break;
      case json::parse_event_t::value:
        startValue();
        break;
    }
    return true;
  };
  json doc;
  try {
    doc = json::parse(text, track);
  } catch (const json::exception& e) {  // syntax errors, trailing data, number overflow
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(source, "(document)", "malformed JSON: " + what);
  }
  if (!duplicate.empty()) throw InputError(source, duplicate, "duplicate key (each key may appear once)");
  return doc;
}

}  // namespace coverbench
