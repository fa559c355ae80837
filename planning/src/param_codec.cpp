// The one codec of planner parameters (param_codec.hpp): values and specs to and from text and JSON.
#include "coverbench/param_codec.hpp"

#include "coverbench/json_input.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace coverbench {

using nlohmann::json;
using nlohmann::ordered_json;

std::string paramText(const ParamValue& value) {
  struct Visitor {
    std::string operator()(double d) const {
      // Ten significant digits as before (so keys of such values stay), more when ten do not read
      // back: two values that differ in the eleventh digit are two configurations.
      char buf[64];
      for (int digits = 10; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, d);
        if (std::strtod(buf, nullptr) == d) break;
      }
      return buf;
    }
    std::string operator()(long long i) const { return std::to_string(i); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return s; }
  };
  return std::visit(Visitor{}, value);
}

const char* paramTypeName(ParamType type) {
  switch (type) {
    case ParamType::Number: return "number";
    case ParamType::Integer: return "integer";
    case ParamType::Bool: return "bool";
    case ParamType::Choice: return "choice";
  }
  return "number";
}

const ParamSpec& paramSpec(const PlannerInfo& planner, const std::string& name, const std::string& source) {
  for (const ParamSpec& s : planner.params)
    if (s.name == name) return s;
  std::string known;
  for (const ParamSpec& s : planner.params) known += (known.empty() ? "" : ", ") + s.name;
  throw InputError(source, shownBytes(name),
                   "planner '" + planner.name + "' has no such parameter (it has: " + (known.empty() ? "none" : known) + ")");
}

ParamValue parseParam(const ParamSpec& spec, const std::string& text, const std::string& source) {
  auto fail = [&](const std::string& problem) -> ParamValue { throw InputError(source, spec.name, problem); };
  switch (spec.type) {
    case ParamType::Number: {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(v)) return fail("'" + shownBytes(text) + "' is not a finite number");
      // strtod also reads hexadecimal ("0x10" as 16), which no parameter means.
      // (Nor leading white space, which strtod skips.)
      if (text.find_first_of("xX") != std::string::npos || std::isspace(static_cast<unsigned char>(text[0])))
        return fail("'" + shownBytes(text) + "' is not a decimal number");
      if (v < spec.min || v > spec.max)
        return fail(shownBytes(text) + " is out of range [" + paramText(spec.min) + ", " + paramText(spec.max) + "]" +
                    (spec.unit.empty() ? "" : " " + spec.unit));
      return v == 0.0 ? 0.0 : v;  // -0 is 0: one configuration, one key
    }
    case ParamType::Integer: {
      char* end = nullptr;
      const long long v = std::strtoll(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0' || std::isspace(static_cast<unsigned char>(text[0])))
        return fail("'" + shownBytes(text) + "' is not an integer");
      if (static_cast<double>(v) < spec.min || static_cast<double>(v) > spec.max)
        return fail(shownBytes(text) + " is out of range [" + paramText(spec.min) + ", " + paramText(spec.max) + "]");
      return v;
    }
    case ParamType::Bool:
      if (text == "true" || text == "1" || text == "on") return true;
      if (text == "false" || text == "0" || text == "off") return false;
      return fail("'" + shownBytes(text) + "' is not a boolean (true or false)");
    case ParamType::Choice:
      for (const std::string& c : spec.choices)
        if (c == text) return text;
      {
        std::string list;
        for (const std::string& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
        return fail("'" + shownBytes(text) + "' is not one of: " + list);
      }
  }
  return fail("unsupported parameter type");
}

ParamSettings parseSettings(const PlannerInfo& planner, const std::vector<std::pair<std::string, std::string>>& settings,
                            const std::string& source) {
  ParamSettings out;
  for (const auto& [key, text] : settings) out.emplace_back(key, parseParam(paramSpec(planner, key, source), text, source));
  return out;
}

Params withDefaults(const PlannerInfo& planner, const ParamSettings& settings) {
  Params params;
  for (const ParamSpec& spec : planner.params) params.set(spec.name, spec.default_value);
  for (const auto& [key, value] : settings) params.set(key, value);
  return params;
}

Params resolveParams(const PlannerInfo& planner, const std::vector<std::pair<std::string, std::string>>& settings,
                     const std::string& source) {
  return withDefaults(planner, parseSettings(planner, settings, source));
}

std::string paramsIdentity(const Params& params, const std::string& prefix) {
  std::string out;
  for (const auto& [k, v] : params.all()) out += "\n" + prefix + k + "=" + paramText(v);
  return out;
}

std::string paramsList(const ParamSettings& settings) {
  std::string out;
  for (const auto& [k, v] : settings) out += (out.empty() ? "" : ", ") + k + "=" + paramText(v);
  return out;
}

std::string paramsList(const Params& params) {
  return paramsList(ParamSettings(params.all().begin(), params.all().end()));
}

std::string configLabel(const std::string& planner, const ParamSettings& settings) {
  return settings.empty() ? planner : planner + "(" + paramsList(settings) + ")";
}

ordered_json paramJson(const ParamValue& value) {
  return std::visit([](const auto& v) { return ordered_json(v); }, value);
}

ordered_json paramsJson(const Params& params) {
  ordered_json out = ordered_json::object();
  for (const auto& [k, v] : params.all()) out[k] = paramJson(v);
  return out;
}

ordered_json paramSpecJson(const ParamSpec& s) {
  ordered_json spec = {{"name", s.name}, {"type", paramTypeName(s.type)}, {"default", paramJson(s.default_value)},
                       {"unit", s.unit}, {"description", s.description}};
  if (s.type == ParamType::Number || s.type == ParamType::Integer) spec["min"] = s.min, spec["max"] = s.max;
  if (s.type == ParamType::Choice) spec["choices"] = s.choices;
  return spec;
}

ParamSpec paramSpecFromJson(const json& p, const std::string& source, const std::string& where) {
  const JsonFields r(source);
  if (!p.is_object()) r.fail(where, "must be an object");
  r.onlyKeys(p, where, {"name", "type", "default", "min", "max", "choices", "unit", "description"});
  ParamSpec s;
  s.name = r.text(p, "name", where + ".name");
  if (s.name.empty() || s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos)
    r.fail(where + ".name", "must be lower-case letters, digits and _");
  const std::string type = r.text(p, "type", where + ".type");
  s.unit = r.text(p, "unit", where + ".unit", false);
  s.description = r.text(p, "description", where + ".description");
  if (!p.contains("default")) r.fail(where + ".default", "missing");
  const json& d = p["default"];
  auto range = [&] {
    for (const char* k : {"min", "max"})
      if (!p.contains(k)) r.fail(where + "." + k, "missing (a number needs its range)");
    s.min = r.number(p["min"], where + ".min");
    s.max = r.number(p["max"], where + ".max");
    if (s.min > s.max) r.fail(where + ".max", "is below min");
  };
  if (type == "number") {
    s.type = ParamType::Number;
    range();
    const double v = r.number(d, where + ".default");
    if (v < s.min || v > s.max) r.fail(where + ".default", "is outside [min, max]");
    s.default_value = v;
  } else if (type == "integer") {
    s.type = ParamType::Integer;
    range();
    if (!d.is_number_integer()) r.fail(where + ".default", "must be an integer");
    const auto v = d.get<long long>();
    if (static_cast<double>(v) < s.min || static_cast<double>(v) > s.max) r.fail(where + ".default", "is outside [min, max]");
    s.default_value = v;
  } else if (type == "bool") {
    s.type = ParamType::Bool;
    if (!d.is_boolean()) r.fail(where + ".default", "must be true or false");
    s.default_value = d.get<bool>();
  } else if (type == "choice") {
    s.type = ParamType::Choice;
    if (!p.contains("choices") || !p["choices"].is_array() || p["choices"].empty())
      r.fail(where + ".choices", "must be a non-empty list of strings");
    for (const json& c : p["choices"]) {
      if (!c.is_string()) r.fail(where + ".choices", "must be a non-empty list of strings");
      s.choices.push_back(c.get<std::string>());
    }
    if (!d.is_string() || std::find(s.choices.begin(), s.choices.end(), d.get<std::string>()) == s.choices.end())
      r.fail(where + ".default", "must be one of the choices");
    s.default_value = d.get<std::string>();
  } else {
    r.fail(where + ".type", "must be number, integer, bool or choice, not '" + shownBytes(type) + "'");
  }
  return s;
}

std::string paramTextOfJson(const json& value) { return value.is_string() ? value.get<std::string>() : value.dump(); }

ParamSettings parseSettingsJson(const PlannerInfo& planner, const json& object, const std::string& source) {
  if (!object.is_object()) throw InputError(source, "(value)", "must be an object of name: value");
  std::vector<std::pair<std::string, std::string>> texts;
  for (const auto& [key, value] : object.items()) texts.emplace_back(key, paramTextOfJson(value));
  return parseSettings(planner, texts, source);
}

namespace {

/// A value of the older stored text as JSON: a number when all of it reads as one, true/false,
/// else text.
ordered_json legacyStoredValue(const std::string& v) {
  if (v == "true" || v == "false") return v == "true";
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (!v.empty() && end == v.c_str() + v.size()) {
    if (v.find_first_of(".eEnN") == std::string::npos) return std::strtoll(v.c_str(), nullptr, 10);
    return d;
  }
  return v;
}

}  // namespace

ordered_json storedParamsJson(const std::string& stored) {
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
    if (eq != std::string::npos) out[part.substr(0, eq)] = legacyStoredValue(part.substr(eq + 1));
    at = end + 2;
  }
  return out;
}

std::string storedParamsLine(const std::string& stored) {
  std::string out;
  const ordered_json params = storedParamsJson(stored);
  for (const auto& [name, value] : params.items())
    out += (out.empty() ? "" : ", ") + name + "=" + paramTextOfJson(value);
  return out;
}

}  // namespace coverbench
