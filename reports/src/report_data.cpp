#include "coverbench/report_data.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "coverbench/metric_spec.hpp"
#include "coverbench/param_codec.hpp"

namespace coverbench {
namespace {

using Json = nlohmann::ordered_json;

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// A run field's value (NaN and infinities as null).
Json fieldValue(const std::string& v) { return v; }
Json fieldValue(RunStatus v) { return toString(v); }
Json fieldValue(bool v) { return v; }
Json fieldValue(long long v) { return v; }
Json fieldValue(double v) { return number(v); }

const char* typeName(RunFieldType t) {
  switch (t) {
    case RunFieldType::Text: return "text";
    case RunFieldType::Status: return "status";
    case RunFieldType::Bool: return "bool";
    case RunFieldType::Integer: return "integer";
    case RunFieldType::Real: return "real";
  }
  return "";
}

double metricOr(const ResultRow& r, const std::string& name, double fallback) {
  const auto it = r.metrics.find(name);
  return it == r.metrics.end() || !std::isfinite(it->second) ? fallback : it->second;
}

/// Larger is worse: runs without a valid path first, then partial, then low coverage, then overlap.
std::tuple<int, double, double> badness(const ResultRow& r) {
  const int outcome = r.status == RunStatus::Ok && r.valid ? 0 : r.status == RunStatus::Partial && r.valid ? 1 : 2;
  return {outcome, -metricOr(r, "coverage_reachable", 0.0), metricOr(r, "overlap", 0.0)};
}

}  // namespace

std::vector<GallerySection> selectGallery(const ResultSet& rs, const std::vector<std::string>& dataset_order) {
  std::vector<GallerySection> out;
  for (const std::string& dataset : dataset_order) {
    std::vector<const ResultRow*> runs;
    for (const ResultRow& r : rs.runs)
      if (r.dataset == dataset) runs.push_back(&r);
    if (runs.empty()) continue;
    // Walls in a stable order (name, then hash) so every choice below is deterministic.
    std::sort(runs.begin(), runs.end(), [](const ResultRow* a, const ResultRow* b) {
      return std::tie(a->wall_name, a->wall, a->planner) < std::tie(b->wall_name, b->wall, b->planner);
    });
    std::vector<std::pair<std::string, std::string>> chosen;  // (wall hash, why)
    auto choose = [&](const std::string& wall, const std::string& why) {
      for (auto& [w, reasons] : chosen)
        if (w == wall) {
          reasons += "; " + why;
          return;
        }
      chosen.push_back({wall, why});
    };
    // The median wall by the baseline's length ratio (its first column, with several tools).
    std::string baseline_column;
    for (const ResultRow* r : runs)
      if (r->config == rs.baseline) {
        baseline_column = r->planner;
        break;
      }
    std::vector<std::pair<double, const ResultRow*>> ratios;
    for (const ResultRow* r : runs)
      if (r->planner == baseline_column && r->valid && hasPath(r->status))
        if (const double v = metricOr(*r, "length_ratio", NAN); std::isfinite(v)) ratios.push_back({v, r});
    std::stable_sort(ratios.begin(), ratios.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    if (!ratios.empty())
      choose(ratios[(ratios.size() - 1) / 2].second->wall, "median wall (" + baseline_column + "'s length ratio)");
    else
      choose(runs.front()->wall, "first wall (the baseline has no valid path here)");
    for (const std::string& column : rs.planners) {
      const ResultRow* worst = nullptr;
      for (const ResultRow* r : runs)
        if (r->planner == column && (!worst || badness(*r) > badness(*worst))) worst = r;
      if (worst) choose(worst->wall, "worst for " + column);
    }
    GallerySection section;
    section.title = dataset;
    for (const auto& [wall, why] : chosen) {
      GalleryWall g;
      g.wall = wall;
      g.why = why;
      for (const std::string& column : rs.planners)
        for (const ResultRow* r : runs)
          if (r->wall == wall && r->planner == column) {
            g.wall_name = r->wall_name;
            GalleryPicture picture;
            picture.column = column;
            picture.key = r->key;
            picture.status = toString(r->status);
            g.pictures.push_back(std::move(picture));
          }
      section.walls.push_back(std::move(g));
    }
    out.push_back(std::move(section));
  }
  return out;
}

std::string reportDataJson(const ResultSet& rs, const ExperimentRecord& record, const std::vector<GallerySection>& gallery,
                           const PublishedTable* published) {
  Json j;
  j["format"] = "coverbench-report-data";
  j["version"] = 1;
  Json e;
  e["id"] = record.id;
  e["name"] = record.name;
  e["config_path"] = record.config_path;
  e["config_hash"] = record.config_hash;
  e["config_text"] = record.config_text;
  e["baseline"] = rs.baseline;
  e["motion"] = record.motion;
  e["facts"] = Json::array();
  for (const auto& [k, v] : record.facts) e["facts"].push_back({k, v});
  e["datasets"] = Json::array();
  for (const auto& d : record.datasets)
    e["datasets"].push_back({{"label", d.label}, {"source", d.source}, {"walls", d.walls}, {"sha256", d.sha256}});
  e["planners"] = Json::array();
  for (const auto& p : record.planners)
    e["planners"].push_back({{"label", p.label}, {"planner", p.planner}, {"params", storedParamsJson(p.params)}});
  e["columns"] = rs.planners;
  j["experiment"] = e;

  // The run fields each run object carries (kRunFields' exported ones): the Python reader takes
  // their names and types from here.
  j["run_fields"] = Json::array();
  for (const RunField& f : kRunFields)
    if (f.exported == RunExport::RunsAndReport)
      j["run_fields"].push_back(
          {{"name", f.name}, {"type", typeName(f.type)}, {"unit", f.unit}, {"description", f.description}});
  j["run_statuses"] = Json::array();
  for (RunStatus s : kRunStatuses) j["run_statuses"].push_back(toString(s));

  j["metrics"] = Json::array();
  for (const MetricSpec& s : metricSpecs())
    j["metrics"].push_back({{"name", s.name},
                            {"unit", s.unit},
                            {"better", s.better},
                            {"kind", toString(s.kind)},
                            {"headline", s.headline},
                            {"tie_absolute", s.tie_absolute},
                            {"tie_relative", s.tie_relative},
                            {"description", s.description}});
  Json walls = Json::object();
  for (const auto& w : record.walls)
    walls[w.hash] = {{"name", w.name}, {"obstacles", w.obstacles}, {"area", number(w.area)}};
  j["walls"] = walls;

  std::vector<const ResultRow*> runs;
  for (const ResultRow& r : rs.runs) runs.push_back(&r);
  std::sort(runs.begin(), runs.end(), [](const ResultRow* a, const ResultRow* b) { return a->key < b->key; });
  j["runs"] = Json::array();
  for (const ResultRow* r : runs) {
    Json m = Json::object();
    for (const MetricSpec& s : metricSpecs()) {
      const auto it = r->metrics.find(s.name);
      m[s.name] = it == r->metrics.end() ? Json(nullptr) : number(it->second);
    }
    Json run = {{"key", r->key},
                {"column", r->planner},
                {"config", r->config},
                {"dataset", r->dataset},
                {"wall", r->wall},
                {"wall_name", r->wall_name},
                {"tool_width", r->tool.tool_width},
                {"clearance", r->tool.clearance},
                {"pairing", r->pairing}};
    forEachRunField(*r, [&](const RunField& f, const auto& value) {
      if (f.exported == RunExport::RunsAndReport) run[f.name] = fieldValue(value);
    });
    run["metrics"] = std::move(m);
    // Only a tool other than a disk names its shape, so disk reports stay as they were.
    if (r->tool.turnsWithHeading()) run["tool_shape"] = toString(r->tool.shape);
    if (r->tool.isRectangle()) run["tool_depth"] = r->tool.depth;
    // Only a tool with a flux profile names it (FluxProfile::label; the target in um, or null), so
    // other reports stay as they were.
    if (r->tool.profile.set())
      run["profile"] = {{"label", r->tool.profile.label()},
                        {"target_um", r->tool.profile.target > 0.0 ? Json(r->tool.profile.target) : Json(nullptr)}};
    // Only a vehicle other than holonomic is named, so holonomic reports stay as they were.
    if (r->vehicle.isCar())
      run["vehicle"] = {{"model", "car"}, {"turn_radius", r->vehicle.turn_radius}, {"reverse", r->vehicle.reverse}};
    else if (!r->vehicle.isDefault())
      run["vehicle"] = {{"model", toString(r->vehicle.kind)}, {"lift_s", r->vehicle.lift_s}, {"lower_s", r->vehicle.lower_s}};
    if (!r->transit.isDefault()) {
      Json figures = Json::object();
      for (const auto& [name, value] : r->transit_figures) figures[name] = number(value);
      run["transit"] = {{"planner", r->transit.planner}, {"iterations", r->transit.iterations}, {"figures", figures}};
    }
    if (!r->replans.empty()) {  // only with replanning, so other reports stay as they were
      Json replans = Json::array();
      for (const ReplanRow& p : r->replans) {
        Json figures = Json::object();
        for (const auto& [name, value] : p.figures) figures[name] = number(value);
        replans.push_back({{"fraction", p.fraction}, {"repair", p.repair}, {"obstacles", p.obstacles},
                           {"requested", p.requested}, {"status", p.status}, {"valid", p.valid},
                           {"repair_ms", number(p.repair_ms)}, {"figures", figures}});
      }
      run["replans"] = std::move(replans);
    }
    j["runs"].push_back(std::move(run));
  }
  j["gallery"] = Json::array();
  for (const GallerySection& s : gallery) {
    Json section = {{"title", s.title}, {"walls", Json::array()}};
    for (const GalleryWall& w : s.walls) {
      Json pictures = Json::array();
      for (const GalleryPicture& p : w.pictures) {
        pictures.push_back({{"column", p.column}, {"key", p.key}, {"status", p.status}, {"file", p.file}, {"note", p.note},
                            {"playback", p.playback}, {"width", p.width}, {"height", p.height}});
        if (!p.coat.empty())  // only for a tool with a flux profile, so other reports stay as they were
          pictures.back().update({{"coat", p.coat}, {"coat_width", p.coat_width}, {"coat_height", p.coat_height}});
      }
      section["walls"].push_back({{"wall", w.wall}, {"wall_name", w.wall_name}, {"why", w.why}, {"pictures", pictures}});
    }
    j["gallery"].push_back(section);
  }
  if (published) {  // only when given, so other reports stay as they were
    Json rows = Json::array();
    for (const PublishedValue& v : published->values)
      rows.push_back({v.instance, v.method, v.metric, v.value ? Json(*v.value) : Json(nullptr), v.line});
    j["published"] = {{"file", published->file},
                      {"sha256", published->sha256},
                      {"clock", published->clock ? Json(published->clock->describe()) : Json(nullptr)},
                      {"clock_matches", published->clock_matches},
                      {"columns", {"instance", "method", "metric", "value", "line"}},
                      {"rows", std::move(rows)}};
  }
  return j.dump() + "\n";  // compact: it is most of a report folder's text
}

}  // namespace coverbench
