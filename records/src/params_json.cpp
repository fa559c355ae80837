// A planner configuration's resolved parameters as stored: a JSON object (full precision); older
// databases stored "key=value, ..." text at ten significant digits.
#include <nlohmann/json.hpp>

#include <cstdlib>

#include "coverbench/records.hpp"

namespace coverbench {
namespace {

using nlohmann::ordered_json;

/// A value of the older text as JSON: a number when all of it reads as one, true/false, else text.
ordered_json legacyValue(const std::string& v) {
  if (v == "true" || v == "false") return v == "true";
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (!v.empty() && end == v.c_str() + v.size()) {
    if (v.find_first_of(".eEnN") == std::string::npos) return std::strtoll(v.c_str(), nullptr, 10);
    return d;
  }
  return v;
}

ordered_json paramsObject(const std::string& stored) {
  if (!stored.empty() && stored.front() == '{') {
    ordered_json j = ordered_json::parse(stored, nullptr, false);
    if (j.is_object()) return j;
  }
  ordered_json out = ordered_json::object();
  std::size_t at = 0;
  while (at < stored.size()) {
    std::size_t end = stored.find(", ", at);
    if (end == std::string::npos) end = stored.size();
    const std::string part = stored.substr(at, end - at);
    const std::size_t eq = part.find('=');
    if (eq != std::string::npos) out[part.substr(0, eq)] = legacyValue(part.substr(eq + 1));
    at = end + 2;
  }
  return out;
}

}  // namespace

std::string paramsJson(const std::string& stored) { return paramsObject(stored).dump(); }

std::string paramsLine(const std::string& stored) {
  std::string out;
  const ordered_json params = paramsObject(stored);
  for (const auto& [name, value] : params.items())
    out += (out.empty() ? "" : ", ") + name + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
  return out;
}

}  // namespace coverbench
