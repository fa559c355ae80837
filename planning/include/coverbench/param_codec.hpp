#pragma once
/// The one codec of planner parameters: every entrance (command line, experiment config, manifest,
/// Python, the server) reads a value or a spec here, and every exit (run keys, configuration ids,
/// labels, plan files, the results database, the protocol, listings) writes it here. A value has
/// one canonical text (paramText): a run key's `param.k=v`, a configuration's id and its label
/// are all made of it.
#include <nlohmann/json_fwd.hpp>

#include <string>
#include <utility>
#include <vector>

#include "coverbench/planner.hpp"

namespace coverbench {

/// A parameter given by name with its value read (a configuration's settings, in the order given).
using ParamSettings = std::vector<std::pair<std::string, ParamValue>>;

// --- text -----------------------------------------------------------------------------------------

/// The canonical text of a value: numbers in the fewest digits (at least ten) that read back as
/// the same double, integers in decimal, true/false, a choice's name.
std::string paramText(const ParamValue& value);
/// "number", "integer", "bool" or "choice".
const char* paramTypeName(ParamType type);
/// The declared parameter `name` of `planner`; InputError naming `source` and the key when it has
/// none (listing those it has).
const ParamSpec& paramSpec(const PlannerInfo& planner, const std::string& name, const std::string& source);
/// A value read from text against its spec (a number, an integer, true/false/1/0/on/off, one of the
/// choices), in range; InputError naming `source` and the parameter otherwise.
ParamValue parseParam(const ParamSpec& spec, const std::string& text, const std::string& source);
/// Settings `key=value` read against the planner's declarations, each once.
ParamSettings parseSettings(const PlannerInfo& planner, const std::vector<std::pair<std::string, std::string>>& settings,
                            const std::string& source);
/// Every declared parameter: its default, unless `settings` gives it.
Params withDefaults(const PlannerInfo& planner, const ParamSettings& settings);
/// parseSettings and withDefaults: unknown keys, unreadable values and values out of range throw
/// InputError naming `source` and the key.
Params resolveParams(const PlannerInfo& planner, const std::vector<std::pair<std::string, std::string>>& settings,
                     const std::string& source = "--param");
/// The identity text of resolved values: a line "\n<prefix>k=v" per parameter, in name order
/// (configuration ids hash it with no prefix, run keys with "param.").
std::string paramsIdentity(const Params& params, const std::string& prefix);
/// "k=v, k=v" (settings in their order, or every resolved value in name order).
std::string paramsList(const ParamSettings& settings);
std::string paramsList(const Params& params);
/// A configuration's label: the planner's name, and the settings given in brackets:
/// "zigzag" or "zigzag(overlap=0.1, sweep_angle=90)".
std::string configLabel(const std::string& planner, const ParamSettings& settings);

// --- JSON -----------------------------------------------------------------------------------------

/// A value as JSON: a number, an integer, a bool or a string.
nlohmann::ordered_json paramJson(const ParamValue& value);
/// Resolved values as a JSON object by name (full precision).
nlohmann::ordered_json paramsJson(const Params& params);
/// A spec as JSON: name, type, default, unit, description, and min and max (numbers and
/// integers) or choices (a choice), as manifests declare and listings show it.
nlohmann::ordered_json paramSpecJson(const ParamSpec& spec);
/// A spec read from JSON as paramSpecJson writes it (a manifest's `params[i]`, at `where`):
/// InputError naming `source` and the field for anything else.
ParamSpec paramSpecFromJson(const nlohmann::json& spec, const std::string& source, const std::string& where);
/// A value given as JSON (a request's, a stored run's) as the text parseParam reads: a string as
/// it is, any other scalar as JSON writes it.
std::string paramTextOfJson(const nlohmann::json& value);
/// A planner configuration's resolved parameters as a results database stores them, as a JSON
/// object: stored as one (full precision); databases before that stored "key=value, ..." text at
/// ten significant digits, read here as numbers, true/false or text.
nlohmann::ordered_json storedParamsJson(const std::string& stored);
/// The same as one line for people: "key=value, ..." (each value as paramTextOfJson gives it).
std::string storedParamsLine(const std::string& stored);
/// Values given as a JSON object of name: value (a value a string or a JSON scalar, read as its
/// text), resolved against the planner's declarations as resolveParams does.
ParamSettings parseSettingsJson(const PlannerInfo& planner, const nlohmann::json& object, const std::string& source);

}  // namespace coverbench
