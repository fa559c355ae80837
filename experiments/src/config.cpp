// The experiment config: YAML (yaml-cpp), checked completely before any run, errors with lines.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <type_traits>

#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/external_planner.hpp"
#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/registry.hpp"
#include "config_reader.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;
using config_yaml::Reader;
using config_yaml::readProfile;
using config_yaml::readTools;
using config_yaml::Yaml;
using config_yaml::YamlEntry;

/// One planner configuration: resolved parameters, its label, and its content hash.
PlannerConfig makeConfig(const PlannerInfo& info, ParamSettings settings) {
  PlannerConfig pc;
  pc.planner = info.name;
  pc.params = withDefaults(info, settings);
  pc.label = configLabel(info.name, settings);
  pc.settings = std::move(settings);
  pc.id = sha256Hex("planner=" + info.name + paramsIdentity(pc.params, ""));
  return pc;
}

/// The `motion:` section: the time model of duration_s (docs/metrics.md#time-models).
MotionLimits readMotion(Reader& r, const Yaml& m, const std::string& where = "motion") {
  r.onlyKeys(m, where, {"speed", "acceleration", "stops", "stop_angle", "turn_cost_s", "rotation_speed"});
  MotionLimits limits;
  // At least a micrometre a second (kMinMotion): slower, a duration or a constant gun's coat may
  // pass what a double holds.
  if (const Yaml* v = m.find("speed")) limits.speed = r.number(*v, where + ".speed", kMinMotion, kMaxMotion);
  if (const Yaml* v = m.find("acceleration"))  // "inf": no ramp
    limits.acceleration =
        r.text(*v, where + ".acceleration") == "inf" ? HUGE_VAL : r.number(*v, where + ".acceleration", kMinMotion, kMaxMotion);
  if (const Yaml* v = m.find("rotation_speed")) limits.rotation_speed = r.number(*v, where + ".rotation_speed", 0, 100);
  if (const Yaml* v = m.find("stops")) {
    const std::string stops = r.text(*v, where + ".stops");
    if (stops == "waypoints") limits.stops = MotionLimits::Stops::Waypoints;
    else if (stops != "turns") r.fail(*v, where + ".stops", "must be turns or waypoints, got '" + shownBytes(stops) + "'");
  }
  if (const Yaml* v = m.find("stop_angle")) {
    if (limits.stops == MotionLimits::Stops::Waypoints) r.fail(*v, where + ".stop_angle", "applies to stops: turns only");
    limits.stop_angle_deg = r.number(*v, where + ".stop_angle", 0, 180, true, true);
  }
  if (const Yaml* v = m.find("turn_cost_s")) limits.turn_cost_s = r.number(*v, where + ".turn_cost_s", 0, 3600);
  return limits;
}

/// One config file being read: its reader, its path, and how a relative path in it resolves
/// (against the file's folder).
struct ConfigFile {
  Reader& r;
  const std::string& path;
  fs::path base;
  std::string resolve(const std::string& p) const {
    return fs::path(p).is_absolute() ? p : (base / p).lexically_normal().string();
  }
};

/// An `import:` dataset: its options, and its walls imported now, so a bad source stops the config
/// here, before any run.
void readImportDataset(const ConfigFile& f, const Yaml& d, const std::string& where, const Yaml& import, DatasetSpec& spec) {
  Reader& r = f.r;
  spec.kind = DatasetSpec::Kind::Import;
  spec.folder = f.resolve(r.text(import, where + ".import"));
  if (d.find("count") || d.find("seed")) r.fail(d, where, "an import has a fixed set of walls: no count or seed");
  ImportOptions& o = spec.import_options;
  auto text_of = [&](const char* key, std::string& into) {
    if (const Yaml* n = d.find(key)) into = r.text(*n, where + "." + key);
  };
  text_of("format", o.format);
  text_of("crs", o.crs);
  text_of("source_crs", o.source_crs);
  text_of("name_field", o.name_field);
  text_of("boundary_layer", o.dxf_boundary_layer);
  text_of("origin", o.origin);
  if (const Yaml* n = d.find("split_multipolygons")) o.split_multipolygons = r.boolean(*n, where + ".split_multipolygons");
  if (const Yaml* n = d.find("all_components")) o.all_components = r.boolean(*n, where + ".all_components");
  if (const Yaml* n = d.find("min_hole_area")) o.min_hole_area = r.number(*n, where + ".min_hole_area", 0, 1e8);
  if (const Yaml* n = d.find("simplify")) o.simplify = r.number(*n, where + ".simplify", 0, 1e4);
  if (const Yaml* n = d.find("rooms")) o.rooms = f.resolve(r.text(*n, where + ".rooms"));
  if (const Yaml* n = d.find("min_room_area")) o.min_room_area = r.number(*n, where + ".min_room_area", 0, 1e8);
  if (const Yaml* n = d.find("transform")) o.transform = parseTransform(r.text(*n, where + ".transform"), f.path + ":" + std::to_string(n->line), where + ".transform");
  if (const Yaml* n = d.find("obstacle_layers")) {
    if (n->isScalar()) o.dxf_obstacle_layers = {n->scalar};
    else if (n->isList()) for (const Yaml& item : n->items) o.dxf_obstacle_layers.push_back(r.text(item, where + ".obstacle_layers"));
    else r.fail(*n, where + ".obstacle_layers", "must be a layer name or a list of them");
  }
  // Imported now, so a bad source stops the config here, before any run. A bad option is
  // named as the config's key ("--source-crs" is `source_crs` here).
  try {
    auto walls = std::make_shared<std::vector<Wall>>();
    for (ImportedWall& w : importWalls({spec.folder}, o).walls) walls->push_back(std::move(w.wall));
    spec.count = walls->size();
    spec.imported = std::move(walls);  // loadWalls uses these: the sources are read once
  } catch (const InputError& e) {
    if (e.source().rfind("--", 0) != 0) throw;
    std::string key = e.source().substr(2);
    std::replace(key.begin(), key.end(), '-', '_');
    const Yaml* at = d.find(key);
    r.fail(at ? *at : d, where + "." + key, e.problem());
  }
}

/// A `family:` dataset (a generator family, with count and seed) or a `suite:` one (a fixed set).
void readGeneratedDataset(Reader& r, const Yaml& d, const std::string& where, DatasetSpec& spec) {
  const Yaml* family = d.find("family");
  const Yaml* suite = d.find("suite");
  const Yaml* count = d.find("count");
  const Yaml* seed = d.find("seed");
  if (family) {
    spec.kind = DatasetSpec::Kind::Family;
    spec.family = r.text(*family, where + ".family");
    try {
      if (findFamily(spec.family, "", "").fixed_suite) r.fail(*family, where + ".family", "'" + shownBytes(spec.family) + "' is a suite: write suite: " + spec.family);
    } catch (const InputError& e) {
      if (e.source().empty()) r.fail(*family, where + ".family", e.problem());
      throw;
    }
    if (!count) r.fail(d, where + ".count", "missing (how many walls to generate)");
    spec.count = static_cast<std::size_t>(r.integer(*count, where + ".count", 1, 1000000));
    spec.seed = seed ? static_cast<std::uint64_t>(r.integer(*seed, where + ".seed", 0, 1LL << 53)) : 0;
  } else {
    spec.kind = DatasetSpec::Kind::Suite;
    spec.family = r.text(*suite, where + ".suite");
    try {
      if (!findFamily(spec.family, "", "").fixed_suite) r.fail(*suite, where + ".suite", "'" + shownBytes(spec.family) + "' is a generator family: write family, count and seed");
    } catch (const InputError& e) {
      if (e.source().empty()) r.fail(*suite, where + ".suite", e.problem());
      throw;
    }
    if (count || seed) r.fail(d, where, "a suite has a fixed set of walls: no count or seed");
    spec.count = suiteSize(spec.family);
  }
}

/// A `folder:` dataset: the wall files of a folder (its manifest.json aside).
void readFolderDataset(const ConfigFile& f, const Yaml& d, const std::string& where, const Yaml& folder, DatasetSpec& spec) {
  Reader& r = f.r;
  spec.kind = DatasetSpec::Kind::Folder;
  spec.folder = f.resolve(r.text(folder, where + ".folder"));
  if (d.find("count") || d.find("seed")) r.fail(d, where, "a folder has a fixed set of walls: no count or seed");
  if (!fs::is_directory(spec.folder)) r.fail(folder, where + ".folder", "'" + shownBytes(spec.folder) + "' is not a folder");
  for (const auto& entry : fs::directory_iterator(spec.folder))
    spec.count += entry.path().extension() == ".json" && entry.path().filename() != "manifest.json";
}

/// What every kind of dataset may add: where its paths begin and end, and its label.
void readDatasetEnds(Reader& r, const Yaml& d, const std::string& where, DatasetSpec& spec) {
  auto point = [&](const Yaml& n, const std::string& field) {
    if (!n.isList() || n.items.size() != 2) r.fail(n, field, "must be [x, y]");
    return Point{r.number(n.items[0], field + "[0]", -kMaxExtent, kMaxExtent),
                 r.number(n.items[1], field + "[1]", -kMaxExtent, kMaxExtent)};
  };
  if (const Yaml* n = d.find("start")) spec.start = point(*n, where + ".start");
  if (const Yaml* n = d.find("end")) {
    if (n->isScalar() && n->scalar == "start") spec.end_at_start = true;
    else spec.end = point(*n, where + ".end");
  }
  const Yaml* label = d.find("label");
  spec.label = label ? r.text(*label, where + ".label")
               : spec.kind == DatasetSpec::Kind::Folder || spec.kind == DatasetSpec::Kind::Import
                   ? (fs::path(spec.folder) / "").lexically_normal().parent_path().filename().string()  // "a/fields/" as "a/fields"
                   : spec.family;
  if (spec.label.empty()) r.fail(label ? *label : d, where + ".label", "must not be empty");
}

/// One entry of `datasets:`: exactly one of family, suite, folder or import, with its options.
DatasetSpec readDataset(const ConfigFile& f, const Yaml& d, const std::string& where) {
  Reader& r = f.r;
  r.onlyKeys(d, where, {"family", "count", "seed", "suite", "folder", "label", "start", "end", "import", "format", "crs", "source_crs",
                        "name_field", "split_multipolygons", "boundary_layer", "obstacle_layers", "all_components",
                        "min_hole_area", "simplify", "transform", "origin", "rooms", "min_room_area"});
  DatasetSpec spec;
  spec.line = d.line;
  const Yaml* family = d.find("family");
  const Yaml* suite = d.find("suite");
  const Yaml* folder = d.find("folder");
  const Yaml* import = d.find("import");
  const int kinds = (family ? 1 : 0) + (suite ? 1 : 0) + (folder ? 1 : 0) + (import ? 1 : 0);
  if (kinds != 1) r.fail(d, where, "needs exactly one of family (with count and seed), suite, folder, or import");
  if (!import)
    for (const YamlEntry& e : d.entries)
      if (e.key != "family" && e.key != "count" && e.key != "seed" && e.key != "suite" && e.key != "folder" && e.key != "label" &&
          e.key != "start" && e.key != "end")
        r.fail(e.key_line, where + "." + e.key, "is an import option: it needs import: FILE_OR_FOLDER");
  if (import) readImportDataset(f, d, where, *import, spec);
  else if (family || suite) readGeneratedDataset(r, d, where, spec);
  else readFolderDataset(f, d, where, *folder, spec);
  readDatasetEnds(r, d, where, spec);
  return spec;
}

/// The `datasets:` section: a non-empty list.
void readDatasets(const ConfigFile& f, const Yaml& datasets, ExperimentConfig& c) {
  if (!datasets.isList() || datasets.items.empty()) f.r.fail(datasets, "datasets", "must be a non-empty list");
  for (std::size_t i = 0; i < datasets.items.size(); ++i)
    c.datasets.push_back(readDataset(f, datasets.items[i], "datasets[" + std::to_string(i) + "]"));
}

/// The planner configurations listed so far, each label and each set of resolved parameters once.
struct PlannerList {
  std::map<std::string, std::string> where_label;  // label -> where it was listed
  std::map<std::string, std::string> label_of_id;  // configuration id -> its first label

  void add(Reader& r, ExperimentConfig& c, PlannerConfig pc, const Yaml& at, const std::string& where) {
    if (where_label.count(pc.label))
      r.fail(at, where, "configuration '" + pc.label + "' is listed twice (also at " + where_label[pc.label] + ")");
    if (label_of_id.count(pc.id))
      r.fail(at, where,
             "configuration '" + pc.label + "' has the same resolved parameters as '" + label_of_id[pc.id] +
                 "' (defaults included): list it once");
    where_label[pc.label] = where;
    label_of_id[pc.id] = pc.label;
    c.planners.push_back(std::move(pc));
  }
};

/// A planner entry's `params:` as every combination of their values (lists give the product of
/// their values, in key order).
std::vector<ParamSettings> paramCombos(Reader& r, const PlannerInfo& info, const Yaml* params, const std::string& where) {
  std::vector<ParamSettings> combos{{}};
  if (!params) return combos;
  std::vector<std::string> declared;
  for (const ParamSpec& s : info.params) declared.push_back(s.name);
  r.onlyKeys(*params, where + ".params", declared);
  // Key order, so a configuration's label does not depend on how the file orders its keys.
  std::vector<const YamlEntry*> sorted;
  for (const YamlEntry& e : params->entries) sorted.push_back(&e);
  std::sort(sorted.begin(), sorted.end(), [](const YamlEntry* a, const YamlEntry* b) { return a->key < b->key; });
  for (const YamlEntry* entry : sorted) {
    const std::string field = where + ".params." + entry->key;
    std::vector<ParamSettings> next;
    const ParamSpec& spec = paramSpec(info, entry->key, field);
    for (const Yaml* v : r.values(entry->value, field)) {
      ParamValue value;
      try {
        value = parseParam(spec, r.text(*v, field), "");
      } catch (const InputError& e) {
        r.fail(*v, field, e.problem());
      }
      for (auto combo : combos) {
        combo.push_back({entry->key, value});
        next.push_back(std::move(combo));
      }
    }
    combos = std::move(next);
  }
  return combos;
}

/// An entry's `label:`: a name for its configurations in every table, plot and the explorer. One
/// line of at most 80 printable characters, and not another planner's name (it would read as that
/// planner). Empty when the entry has none.
std::string readLabel(Reader& r, const Yaml& p, const std::string& where, const std::string& planner) {
  const Yaml* node = p.isScalar() ? nullptr : p.find("label");
  if (!node) return "";
  const std::string field = where + ".label";
  const std::string label = r.text(*node, field);
  if (label.empty() || label.size() > 80) r.fail(*node, field, "must be 1 to 80 characters");
  if (!isPrintableLine(label)) r.fail(*node, field, "must be one line of printable characters (no control or bidirectional marks)");
  if (label.front() == ' ' || label.back() == ' ') r.fail(*node, field, "must not begin or end with a space");
  if (label != planner && lookupPlanner(label))
    r.fail(*node, field, "'" + label + "' is the name of another planner; a label must not read as one");
  return label;
}

/// The entry's configurations' labels: each its own (configLabel) without `label:`; with it, the
/// label alone when the entry makes one configuration, else the label and the settings its lists
/// sweep, in brackets: "fine(sweep_angle=45)".
void applyLabel(std::vector<PlannerConfig>& configs, const std::string& label, const Yaml* params) {
  if (label.empty()) return;
  if (configs.size() == 1) {
    configs.front().label = label;
    return;
  }
  for (PlannerConfig& pc : configs) {
    ParamSettings swept;
    for (const auto& [name, value] : pc.settings) {
      const Yaml* given = params ? params->find(name) : nullptr;
      if (given && given->isList() && given->items.size() > 1) swept.push_back({name, value});
    }
    pc.label = configLabel(label, swept);
  }
}

/// One entry of `planners:`: "all", a name, {name, params, label} or {external: MANIFEST, params,
/// label}.
void readPlanner(const ConfigFile& f, const Yaml& p, const std::string& where, PlannerList& list, ExperimentConfig& c) {
  Reader& r = f.r;
  if (p.isScalar() && p.scalar == "all") {  // every registered planner, default parameters
    for (const PlannerInfo& info : registeredPlanners()) list.add(r, c, makeConfig(info, {}), p, where);
    return;
  }
  // "- zigzag" is short for "- name: zigzag"; "- external: FILE" names a planner outside the
  // tree by its manifest (docs/external_planners.md), relative to the config's folder.
  const Yaml* name_node = &p;
  const Yaml* params = nullptr;
  const PlannerInfo* info = nullptr;
  if (!p.isScalar()) {
    if (const Yaml* ext = p.find("external")) {
      r.onlyKeys(p, where, {"external", "params", "label"});
      const std::string file = r.text(*ext, where + ".external");
      const fs::path manifest = fs::path(file).is_absolute() ? fs::path(file) : fs::path(f.path).parent_path() / file;
      if (!fs::is_regular_file(manifest)) r.fail(*ext, where + ".external", "no manifest at " + manifest.string());
      info = &external::addFromManifest(manifest.lexically_normal().string());
      name_node = ext;
    } else {
      r.onlyKeys(p, where, {"name", "params", "label"});
      name_node = p.find("name");
      if (!name_node) r.fail(p, where + ".name", "missing");
    }
    params = p.find("params");
  }
  const std::string name = info ? info->name : r.text(*name_node, where + ".name");
  if (!info) info = lookupPlanner(name);
  if (!info) {
    std::string known;
    for (const PlannerInfo& candidate : registeredPlanners()) known += (known.empty() ? "" : ", ") + candidate.name;
    r.fail(*name_node, where + ".name", "unknown planner '" + shownBytes(name) + "' (registered: " + known + ")");
  }
  const std::string label = readLabel(r, p, where, info->name);
  std::vector<PlannerConfig> configs;
  for (auto& settings : paramCombos(r, *info, params, where)) configs.push_back(makeConfig(*info, std::move(settings)));
  applyLabel(configs, label, params);
  for (PlannerConfig& pc : configs) list.add(r, c, std::move(pc), p, where);
}

/// The `planners:` section, with sweeps expanded; the labels listed, by where they were.
PlannerList readPlanners(const ConfigFile& f, const Yaml& planners, ExperimentConfig& c) {
  if (!planners.isList() || planners.items.empty()) f.r.fail(planners, "planners", "must be a non-empty list");
  PlannerList list;
  for (std::size_t i = 0; i < planners.items.size(); ++i)
    readPlanner(f, planners.items[i], "planners[" + std::to_string(i) + "]", list, c);
  return list;
}

/// The `vehicle:` section: one model per experiment (docs/vehicles.md).
void readVehicle(Reader& r, const Yaml& v, VehicleModel& vehicle) {
  r.onlyKeys(v, "vehicle", {"model", "lift_s", "lower_s", "turn_radius", "reverse"});
  const Yaml* model = v.find("model");
  if (!model) r.fail(v, "vehicle.model", "missing (holonomic, gantry or car)");
  const std::string name = r.text(*model, "vehicle.model");
  if (!parseVehicleKind(name, vehicle.kind))
    r.fail(*model, "vehicle.model", "must be holonomic, gantry or car, not '" + shownBytes(name) + "'");
  if (const Yaml* t = v.find("lift_s")) vehicle.lift_s = r.number(*t, "vehicle.lift_s", 0.0, kMaxLiftTime);
  if (const Yaml* t = v.find("lower_s")) vehicle.lower_s = r.number(*t, "vehicle.lower_s", 0.0, kMaxLiftTime);
  if (const Yaml* t = v.find("turn_radius"))
    vehicle.turn_radius = r.number(*t, "vehicle.turn_radius", kMinTurnRadius, kMaxTurnRadius);  // validateVehicle's range
  if (const Yaml* t = v.find("reverse")) vehicle.reverse = r.boolean(*t, "vehicle.reverse");
  if (!vehicle.liftsTool() && (v.find("lift_s") || v.find("lower_s")))
    r.fail(v, "vehicle", "lift_s and lower_s belong to a gantry; a " + name + " never lifts its tool");
  if (!vehicle.isCar() && (v.find("turn_radius") || v.find("reverse")))
    r.fail(v, "vehicle", "turn_radius and reverse belong to a car; a " + name + " turns on the spot");
}

/// The `transit:` section: a planner name or a list of names, each its own runs (docs/transits.md).
void readTransits(Reader& r, const Yaml& t, std::vector<TransitSpec>& transits) {
  r.onlyKeys(t, "transit", {"planner", "iterations", "time_cap_s"});
  const Yaml* planner = t.find("planner");
  if (!planner) r.fail(t, "transit.planner", "missing (visibility, rrtstar, prmstar, bitstar or informed-rrtstar)");
  TransitSpec common;
  if (const Yaml* n = t.find("iterations")) common.iterations = r.integer(*n, "transit.iterations", 1, kMaxTransitIterations);
  if (const Yaml* n = t.find("time_cap_s"))
    common.time_cap_s = r.number(*n, "transit.time_cap_s", 0.0, kMaxTimeLimitSeconds, true);
  transits.clear();
  bool sampling = false;
  for (const Yaml* v : r.values(*planner, "transit.planner")) {
    TransitSpec spec = common;
    spec.planner = r.text(*v, "transit.planner");
    const TransitPlannerInfo* info = findTransitPlanner(spec.planner);
    if (!info) {
      std::string known;
      for (const TransitPlannerInfo& p : transitPlanners()) known += (known.empty() ? "" : ", ") + p.name;
      r.fail(*v, "transit.planner", "'" + shownBytes(spec.planner) + "' is not a transit planner (" + known + ")");
    }
    for (const TransitSpec& before : transits)
      if (before.planner == spec.planner) r.fail(*v, "transit.planner", "lists " + spec.planner + " twice");
    sampling = sampling || info->sampling;
    transits.push_back(spec);
  }
  if (!sampling && (t.find("iterations") || t.find("time_cap_s")))
    r.fail(t, "transit", "iterations and time_cap_s belong to a sampling planner; visibility has neither");
  if (sampling) loadSamplingTransits();  // before the workers are forked: they share it
}

/// The `replanning:` section: obstacles appear at fractions of every path; each repair is
/// measured (docs/replanning.md).
void readReplanning(Reader& r, const Yaml& p, ReplanningSpec& replanning) {
  r.onlyKeys(p, "replanning", {"at", "obstacles", "kinds", "repairs"});
  const Yaml* at = p.find("at");
  if (!at) r.fail(p, "replanning.at", "missing (fractions of the path's length, e.g. [0.3, 0.7])");
  for (const Yaml* v : r.values(*at, "replanning.at")) {
    // At 0 nothing was driven yet, at 1 nothing is left to repair.
    const double f = r.number(*v, "replanning.at", 0.0, 1.0, true, true);
    if (std::find(replanning.at.begin(), replanning.at.end(), f) != replanning.at.end())
      r.fail(*v, "replanning.at", "lists " + v->scalar + " twice");
    replanning.at.push_back(f);
  }
  if (const Yaml* n = p.find("obstacles"))
    replanning.obstacles = static_cast<int>(r.integer(*n, "replanning.obstacles", 1, kMaxSurpriseObstacles));
  // A name or a list of distinct names, each parsed by `parse`.
  auto names = [&](const char* key, auto parse, const std::string& known, auto& into) {
    const Yaml* k = p.find(key);
    if (!k) return;
    const std::string field = std::string("replanning.") + key;
    into.clear();
    for (const Yaml* v : r.values(*k, field)) {
      typename std::decay_t<decltype(into)>::value_type value;
      const std::string name = r.text(*v, field);
      if (!parse(name, value)) r.fail(*v, field, "must be " + known + ", not '" + shownBytes(name) + "'");
      if (std::find(into.begin(), into.end(), value) != into.end()) r.fail(*v, field, "lists " + name + " twice");
      into.push_back(value);
    }
  };
  names("kinds", [](const std::string& n, SurpriseKind& k) { return parseSurpriseKind(n, k); },
        "scaffolding, ladder or duct", replanning.kinds);
  names("repairs", [](const std::string& n, RepairMethod& m) { return parseRepairMethod(n, m); }, "replan or detour",
        replanning.repairs);
}

/// The settings of how runs are run: repetitions, limits, threads, seed, allow_large and judge.
void readRunSettings(Reader& r, const Yaml& doc, ExperimentConfig& c) {
  if (const Yaml* n = doc.find("repetitions")) c.repetitions = static_cast<int>(r.integer(*n, "repetitions", 1, 1000));
  if (const Yaml* l = doc.find("limits")) {
    r.onlyKeys(*l, "limits", {"time_s", "memory_mb"});
    if (const Yaml* v = l->find("time_s")) c.time_limit_s = r.number(*v, "limits.time_s", 0.0, kMaxTimeLimitSeconds, true);
    if (const Yaml* v = l->find("memory_mb")) c.memory_limit_mb = r.number(*v, "limits.memory_mb", 0.0, 1048576.0, true);
  }
  if (const Yaml* n = doc.find("threads")) c.threads = static_cast<unsigned>(r.integer(*n, "threads", 0, 1024));
  if (const Yaml* n = doc.find("seed")) c.seed = static_cast<std::uint64_t>(r.integer(*n, "seed", 0, 1LL << 53));
  if (const Yaml* n = doc.find("allow_large")) c.allow_large = r.boolean(*n, "allow_large");
  if (const Yaml* n = doc.find("judge")) {
    const std::string judge = r.text(*n, "judge");
    if (judge != "fast" && judge != "exact") r.fail(*n, "judge", "must be fast or exact, not '" + shownBytes(judge) + "'");
    c.exact_judge = judge == "exact";
  }
}

/// The `baseline:` key: one of the planner configurations' labels (default: the first).
void readBaseline(Reader& r, const Yaml& doc, const PlannerList& list, ExperimentConfig& c) {
  c.baseline = c.planners.front().label;
  if (const Yaml* b = doc.find("baseline")) {
    c.baseline = r.text(*b, "baseline");
    if (!list.where_label.count(c.baseline)) {
      std::string known;
      for (const PlannerConfig& pc : c.planners) known += (known.empty() ? "" : ", ") + pc.label;
      r.fail(*b, "baseline", "'" + shownBytes(c.baseline) + "' is not one of the planner configurations (" + known + ")");
    }
  }
}

/// A published table's clock: `unknown`, or a time model with the keys of `motion:` (`{}` is the
/// default one).
std::optional<MotionLimits> readClock(Reader& r, const Yaml& n, const std::string& field) {
  if (n.isScalar() && n.scalar == "unknown") return std::nullopt;
  if (!n.isMap()) r.fail(n, field, "must be unknown or a time model with the keys of motion: ({} is the default one)");
  return readMotion(r, n, field);
}

/// The `published:` section: a table of published values (`table:`, a CSV, docs/report.md) and
/// the clock its times were measured with (`clock:`), both required. The table is read and
/// checked here, so a bad one stops the config before any run.
PublishedTable readPublished(Reader& r, const Yaml& p, const fs::path& base) {
  r.onlyKeys(p, "published", {"table", "clock"});
  for (const char* required : {"table", "clock"})
    if (!p.find(required)) r.fail(p, std::string("published.") + required, "missing");
  const Yaml& t = *p.find("table");
  std::string table = r.text(t, "published.table");
  if (table.empty()) r.fail(t, "published.table", "must not be empty");
  table = fs::path(table).is_absolute() ? table : (base / table).lexically_normal().string();
  std::error_code ec;
  if (!fs::exists(table, ec)) r.fail(t, "published.table", "no such file: " + table);
  const std::optional<MotionLimits> clock = readClock(r, *p.find("clock"), "published.clock");
  return readPublishedTable(table, clock);
}

}  // namespace

std::optional<PublishedTable> configPublished(const std::string& config_text, const std::string& source) {
  Reader r(source);
  try {
    const Yaml doc = r.copy(YAML::Load(config_text), "", 0);
    if (const Yaml* p = doc.isMap() ? doc.find("published") : nullptr)
      return readPublished(r, *p, fs::path(source).parent_path());
  } catch (const YAML::Exception& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1), "(document)", "YAML syntax: " + e.msg);
  }
  return std::nullopt;
}

PublishedTable publishedTable(const std::string& table, const std::string& clock) {
  Reader r("--published-clock");
  Yaml n;
  try {
    n = r.copy(YAML::Load(clock), "", 0);
  } catch (const YAML::Exception& e) {
    throw InputError("--published-clock", "published_clock", "YAML syntax: " + e.msg);
  }
  if (n.kind == Yaml::Kind::Null) r.fail(n, "published_clock", "missing: unknown, or a time model such as '{speed: 0.3}'");
  return readPublishedTable(table, readClock(r, n, "published_clock"));
}

MotionLimits configMotion(const std::string& config_text, const std::string& source) {
  Reader r(source);
  try {
    const Yaml doc = r.copy(YAML::Load(config_text), "", 0);
    if (const Yaml* m = doc.isMap() ? doc.find("motion") : nullptr) return readMotion(r, *m);
  } catch (const YAML::Exception& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1), "(document)", "YAML syntax: " + e.msg);
  }
  return {};
}

FluxProfile configProfile(const std::string& config_text, const std::string& source, double tool_width) {
  Reader r(source);
  try {
    const Yaml doc = r.copy(YAML::Load(config_text), "", 0);
    const Yaml* tool = doc.isMap() ? doc.find("tool") : nullptr;
    if (const Yaml* p = tool && tool->isMap() ? tool->find("profile") : nullptr) return readProfile(r, *p, {tool_width});
  } catch (const YAML::Exception& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1), "(document)", "YAML syntax: " + e.msg);
  }
  return {};
}

ExperimentConfig loadExperimentConfig(const std::string& path) {
  ExperimentConfig c;
  c.path = path;
  c.text = readFile(path);
  c.hash = sha256Hex(c.text);
  Reader r(path);
  // A byte that is not UTF-8 is named by its own line (yaml-cpp would read past it).
  for (std::size_t start = 0, line = 1; start < c.text.size(); ++line) {
    const std::size_t end = std::min(c.text.find('\n', start), c.text.size());
    if (!isValidUtf8(c.text.substr(start, end - start))) r.fail(static_cast<int>(line), "(document)", "is not valid UTF-8 text");
    start = end + 1;
  }
  requireText(c.text, path + ":1");
  Yaml doc;
  try {
    doc = r.copy(YAML::Load(c.text), "", 0);
  } catch (const YAML::Exception& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1), "(document)", "YAML syntax: " + e.msg);
  }
  if (!doc.isMap()) r.fail(doc, "(document)", "must be a mapping (name, datasets, planners, ...)");
  r.onlyKeys(doc, "", {"name", "output", "datasets", "planners", "tool", "repetitions", "limits", "baseline", "threads",
                       "seed", "allow_large", "judge", "vehicle", "transit", "replanning", "motion", "published"});
  const ConfigFile file{r, path, fs::path(path).parent_path()};

  for (const char* required : {"name", "output", "datasets", "planners"})
    if (!doc.find(required)) r.fail(1, required, "missing");
  c.name = r.text(*doc.find("name"), "name");
  if (c.name.empty()) r.fail(*doc.find("name"), "name", "must not be empty");
  c.output = r.text(*doc.find("output"), "output");
  if (c.output.empty()) r.fail(*doc.find("output"), "output", "must not be empty");
  c.output = file.resolve(c.output);

  readDatasets(file, *doc.find("datasets"), c);
  const PlannerList planners = readPlanners(file, *doc.find("planners"), c);
  readTools(r, doc.find("tool"), c);
  // The time model of duration_s: one per experiment, like the vehicle.
  if (const Yaml* m = doc.find("motion")) c.motion = readMotion(r, *m);
  if (const Yaml* v = doc.find("vehicle")) readVehicle(r, *v, c.vehicle);
  if (const Yaml* t = doc.find("transit")) readTransits(r, *t, c.transits);
  if (const Yaml* p = doc.find("replanning")) readReplanning(r, *p, c.replanning);
  if (c.replanning.enabled() && c.vehicle.isCar())
    r.fail(*doc.find("replanning"), "replanning",
           "is not built for a car yet: its repairs are straight moves a car cannot drive (docs/replanning.md)");
  const auto turning = std::find_if(c.tools.begin(), c.tools.end(), [](const ToolParams& x) { return x.turnsWithHeading(); });
  if (turning != c.tools.end() && (c.vehicle.isCar() || c.replanning.enabled()))
    r.fail(*doc.find("tool")->find("shape"), "tool.shape", "a " + toString(turning->shape) + " tool is not built for " +
           (c.vehicle.isCar() ? "a car yet: the arcs it drives" : "replanning yet: its repairs' paint") + " (docs/metrics.md#tool-shapes); use a disk");
  readRunSettings(r, doc, c);
  readBaseline(r, doc, planners, c);
  if (const Yaml* p = doc.find("published")) c.published = readPublished(r, *p, file.base);
  return c;
}

std::size_t plannedRuns(const ExperimentConfig& config) {
  std::size_t walls = 0;
  for (const DatasetSpec& d : config.datasets) walls += d.count;
  return walls * runsPerWall(config);
}

}  // namespace coverbench
