// The explorer's runs table (serve_parts.hpp): a runs query read and checked, the runs it selects
// in its order, a page of them as JSON, or all of them as CSV; and the metric registry as the page
// formats it.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <set>
#include <string>

#include "coverbench/escape.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/param_codec.hpp"
#include "serve_parts.hpp"

namespace coverbench::cli::serve_internal {
namespace {

using nlohmann::json;

/// The most a run's position in the table may be (`offset`).
constexpr std::size_t kMaxOffset = std::size_t{1} << 30;

/// A request's text as an error message quotes it: at most 60 bytes, control bytes as \xHH, so
/// the message stays one line whatever the request held.
std::string shown(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < 60; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    } else {
      out += text[i];
    }
  }
  return text.size() > 60 ? out + "..." : out;
}

/// A query parameter's whole number from 0 to `most`.
std::size_t wholeNumber(const std::string& name, const std::string& text, std::size_t most) {
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || text[0] == '-' || text[0] == '+' || text[0] == ' ' || v > most)
    throw HttpError(400, name + ": must be a whole number from 0 to " + std::to_string(most) + ", got '" + shown(text) + "'");
  return static_cast<std::size_t>(v);
}

/// A query parameter's finite number.
double realNumber(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double v = text.empty() || std::isspace(static_cast<unsigned char>(text[0])) ? NAN : std::strtod(text.c_str(), &end);
  if (!std::isfinite(v) || end != text.c_str() + text.size())
    throw HttpError(400, shown(name) + ": must be a finite number, got '" + shown(text) + "'");
  return v;
}

/// A parameter's text as a number, or NaN when it is none.
double asNumber(const std::string& text) {
  char* end = nullptr;
  const double v = text.empty() ? NAN : std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(v) ? v : NAN;
}

/// Shortest text that reads back as the same double; empty for NaN and infinities (as
/// `coverbench export` writes its CSV).
std::string csvNumber(double v) { return std::isfinite(v) ? json(v).dump() : std::string(); }

const char* const kQueryNames = "planner, dataset, status, tool, wall, key, param.NAME, min.METRIC, max.METRIC, sort, order, offset, limit";

}  // namespace

Explorer::Query Explorer::readQuery(Index& x, const Params& query, bool paged) {
  Query q;
  q.facet.fill(-1);
  std::set<std::string> seen;
  const auto hasMetric = [&](const std::string& m) { return std::find(x.metric_names.begin(), x.metric_names.end(), m) != x.metric_names.end(); };
  for (const auto& [name, value] : query) {
    if (!seen.insert(name).second) throw HttpError(400, shown(name) + ": given twice (each parameter is given once)");
    const std::string& key = name;  // a lambda may not capture a structured binding (C++17; clang refuses it)
    const auto facet = std::find_if(std::begin(kFacetNames), std::end(kFacetNames), [&](const char* n) { return key == n; });
    if (facet != std::end(kFacetNames)) {
      const std::size_t f = static_cast<std::size_t>(facet - std::begin(kFacetNames));
      const auto& values = x.facet_values[f];
      const auto it = std::find(values.begin(), values.end(), value);
      q.facet[f] = value.empty() ? -1 : it == values.end() ? -2 : static_cast<long long>(it - values.begin());
    } else if (name == "wall") {
      q.wall = value;
    } else if (name == "key") {
      q.key = value;
    } else if (name.rfind("param.", 0) == 0) {
      if (!x.param_values.count(name.substr(6)))
        throw HttpError(400, shown(name) + ": no planner of this experiment has a parameter '" + shown(name.substr(6)) + "'");
      if (!value.empty()) q.params.emplace_back(name.substr(6), value);
    } else if (name.rfind("min.", 0) == 0 || name.rfind("max.", 0) == 0) {
      const std::string metric = name.substr(4);
      if (!hasMetric(metric)) throw HttpError(400, shown(name) + ": this experiment has no metric '" + shown(metric) + "'");
      const double v = realNumber(name, value);
      const bool low = name[1] == 'i';
      q.ranges.push_back({metric, low ? v : -INFINITY, low ? INFINITY : v});
    } else if (name == "sort") {
      q.sort = value;
    } else if (name == "order") {
      if (value != "asc" && value != "desc") throw HttpError(400, "order: must be asc or desc, got '" + shown(value) + "'");
      q.desc = value == "desc";
    } else if ((name == "offset" || name == "limit") && !paged) {
      throw HttpError(400, name + ": runs.csv holds every run the filters pass (no paging)");
    } else if (name == "offset") {
      q.offset = wholeNumber(name, value, kMaxOffset);
    } else if (name == "limit") {
      q.limit = wholeNumber(name, value, kMaxRunsPerPage);
    } else {
      throw HttpError(400, shown(name) + ": not a parameter of the runs (they take " + kQueryNames + ")");
    }
  }
  return q;
}

std::vector<std::uint32_t> Explorer::matching(Index& x, std::size_t db, long long id, const Query& q) {
  std::vector<const std::vector<double>*> ranges;
  for (const Query::Range& r : q.ranges) ranges.push_back(&column(x, db, id, r.metric));
  std::vector<std::uint32_t> out;
  for (const std::uint32_t i : sorted(x, db, id, q.sort, q.desc)) {
    bool match = true;
    for (std::size_t f = 0; f < kFacets && match; ++f) match = q.facet[f] == -1 || q.facet[f] == static_cast<long long>(x.facet_of[f][i]);
    match = match && (q.wall.empty() || x.runs[i].wall_name == q.wall) && (q.key.empty() || x.runs[i].key == q.key);
    const auto& params = x.params_of_planner[x.facet_of[0][i]];
    for (std::size_t p = 0; p < q.params.size() && match; ++p) {
      const auto it = params.find(q.params[p].first);
      match = it != params.end() && it->second == q.params[p].second;
    }
    for (std::size_t r = 0; r < ranges.size() && match; ++r) {
      const double v = (*ranges[r])[i];
      match = std::isfinite(v) && v >= q.ranges[r].low && v <= q.ranges[r].high;
    }
    if (match) out.push_back(i);
  }
  return out;
}

json Explorer::runs(std::size_t db, long long id, const Params& query) {
  std::lock_guard<std::mutex> lock(mutex_);
  Index& x = index(db, id);
  const Query q = readQuery(x, query, true);
  const std::vector<std::uint32_t> selected = matching(x, db, id, q);
  std::vector<std::uint32_t> page;
  for (std::size_t k = q.offset; k < selected.size() && page.size() < q.limit; ++k) page.push_back(selected[k]);
  std::vector<std::string> keys;
  for (const std::uint32_t i : page) keys.push_back(x.runs[i].key);
  const auto metrics = dbs_[db].db->metricsOf(keys);
  json out = json::array();
  for (const std::uint32_t i : page) {
    const ResultsDb::RunSummary& r = x.runs[i];
    json m = json::object();
    for (const auto& [k, v] : metrics.at(r.key))
      if (std::isfinite(v)) m[k] = v;
    out.push_back({{"key", r.key}, {"planner", r.planner}, {"dataset", r.dataset}, {"wall", r.wall}, {"wall_name", r.wall_name},
                   {"status", toString(r.status)}, {"tool", x.facet_values[3][x.facet_of[3][i]]}, {"tool_width", r.tool.tool_width},
                   {"clearance", r.tool.clearance}, {"params", x.params_of_planner[x.facet_of[0][i]]}, {"metrics", m}});
  }
  json facets = json::object();
  for (std::size_t f = 0; f < kFacets; ++f) facets[kFacetNames[f]] = x.facet_values[f];
  return {{"total", selected.size()}, {"offset", q.offset},        {"limit", q.limit},        {"metrics", x.metric_names},
          {"facets", facets},         {"params", x.param_values}, {"runs", out}};
}

Explorer::Selection Explorer::select(std::size_t db, long long id, const Params& query) {
  std::lock_guard<std::mutex> lock(mutex_);
  Index& x = index(db, id);
  return {db, id, matching(x, db, id, readQuery(x, query, false))};
}

std::string Explorer::csvHeader(const Selection& s) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string text = "key,dataset,wall,wall_hash,planner,params,status,tool_width,clearance,tool";
  for (const std::string& m : index(s.db, s.id).metric_names) {
    text += ',';
    text += escapeCsv(m);
  }
  return text + "\n";
}

std::string Explorer::csvRows(const Selection& s, std::size_t from, std::size_t n) {
  std::lock_guard<std::mutex> lock(mutex_);
  Index& x = index(s.db, s.id);
  std::vector<std::string> keys;
  for (std::size_t k = from; k < s.runs.size() && k < from + n; ++k) keys.push_back(x.runs[s.runs[k]].key);
  const auto metrics = dbs_[s.db].db->metricsOf(keys);
  std::string text;
  for (std::size_t k = from; k < s.runs.size() && k < from + n; ++k) {
    const std::uint32_t i = s.runs[k];
    const ResultsDb::RunSummary& r = x.runs[i];
    text += r.key + "," + escapeCsv(r.dataset) + "," + escapeCsv(r.wall_name) + "," + r.wall + "," + escapeCsv(r.planner) + "," +
            escapeCsv(x.params_json_of_planner[x.facet_of[0][i]]) + "," + toString(r.status) + "," + csvNumber(r.tool.tool_width) +
            "," + csvNumber(r.tool.clearance) + "," + escapeCsv(x.facet_values[3][x.facet_of[3][i]]);
    const auto& m = metrics.at(r.key);
    for (const std::string& name : x.metric_names) {
      const auto it = m.find(name);
      text += ',';
      if (it != m.end()) text += csvNumber(it->second);
    }
    text += "\n";
  }
  return text;
}

json Explorer::values(std::size_t db, long long id, const Params& query) {
  std::lock_guard<std::mutex> lock(mutex_);
  Index& x = index(db, id);
  Params filters;
  std::string names[2];  // metric, versus
  for (const auto& [name, value] : query) {
    const int which = name == "metric" ? 0 : name == "versus" ? 1 : -1;
    if (which < 0) {
      if (name == "offset" || name == "limit") throw HttpError(400, name + ": plots take every run the filters pass (no paging)");
      filters.emplace(name, value);
      continue;
    }
    if (!names[which].empty() || query.count(name) > 1) throw HttpError(400, name + ": given twice (each parameter is given once)");
    if (std::find(x.metric_names.begin(), x.metric_names.end(), value) == x.metric_names.end())
      throw HttpError(400, name + ": this experiment has no metric '" + shown(value) + "'");
    names[which] = value;
  }
  if (names[0].empty()) throw HttpError(400, "metric: missing (the metric to plot)");
  const Query q = readQuery(x, filters, false);
  const std::vector<std::uint32_t> selected = matching(x, db, id, q);
  if (selected.size() > kMaxPlotRuns)
    throw HttpError(400, "metric: the filters select " + std::to_string(selected.size()) + " runs; plots take at most " +
                             std::to_string(kMaxPlotRuns) + " (narrow the filters)");
  const std::vector<double>& value = column(x, db, id, names[0]);
  const std::vector<double>* versus = names[1].empty() ? nullptr : &column(x, db, id, names[1]);
  const bool has_valid = std::find(x.metric_names.begin(), x.metric_names.end(), "valid") != x.metric_names.end();
  const std::vector<double>* valid = has_valid ? &column(x, db, id, "valid") : nullptr;
  // Walls by their position in `walls` (a hash is 64 bytes; a run names its wall by a number).
  std::map<std::string, std::size_t> wall_of;
  json walls = json::array(), wall_names = json::array();
  json wall = json::array(), dataset = json::array(), config = json::array(), tool = json::array(), status = json::array(),
       usable = json::array(), v = json::array(), w = json::array();
  const auto number = [](double d) { return std::isfinite(d) ? json(d) : json(nullptr); };
  for (const std::uint32_t i : selected) {
    const ResultsDb::RunSummary& r = x.runs[i];
    const auto [it, added] = wall_of.emplace(r.wall, wall_of.size());
    if (added) {
      walls.push_back(r.wall);
      wall_names.push_back(r.wall_name);
    }
    wall.push_back(it->second);
    dataset.push_back(x.facet_of[1][i]);
    config.push_back(x.facet_of[0][i]);
    tool.push_back(x.facet_of[3][i]);
    status.push_back(toString(r.status));
    usable.push_back((r.status == RunStatus::Ok || r.status == RunStatus::Partial) && (!valid || (*valid)[i] == 1.0));
    v.push_back(number(value[i]));
    if (versus) w.push_back(number((*versus)[i]));
  }
  json out = {{"metric", names[0]}, {"versus", names[1].empty() ? json(nullptr) : json(names[1])},
              {"total", selected.size()}, {"configurations", x.facet_values[0]}, {"families", x.family_of_planner},
              {"params", x.params_of_planner}, {"datasets", x.facet_values[1]}, {"tools", x.facet_values[3]},
              {"walls", walls}, {"wall_names", wall_names}};
  out["runs"] = {{"wall", wall}, {"dataset", dataset}, {"configuration", config}, {"tool", tool}, {"status", status},
                 {"usable", usable}, {"value", v}};
  if (versus) out["runs"]["versus"] = w;
  return out;
}

json Explorer::metricSpecsJson() {
  json out = json::array();
  for (const MetricSpec& s : metricSpecs())
    out.push_back({{"name", s.name}, {"unit", s.unit}, {"better", s.better}, {"kind", toString(s.kind)}, {"headline", s.headline},
                   {"tie_absolute", s.tie_absolute}, {"tie_relative", s.tie_relative}, {"description", s.description},
                   {"format", displayFormat(s)}});
  return {{"metrics", out}};
}

const std::vector<double>& Explorer::column(Index& x, std::size_t db, long long id, const std::string& metric) {
  if (const auto it = x.columns.find(metric); it != x.columns.end()) return it->second;
  std::vector<double> v;
  if (metric == "plan_time_ms" || metric == "peak_memory_bytes")
    for (const auto& r : x.runs) v.push_back(metric == "plan_time_ms" ? r.plan_time_ms : r.peak_memory_bytes);
  else
    v = dbs_[db].db->metricColumn(id, metric);
  if (v.size() != x.runs.size()) throw HttpError(500, "the runs of experiment " + std::to_string(id) + " changed while served");
  return x.columns.emplace(metric, std::move(v)).first->second;
}

const std::vector<std::uint32_t>& Explorer::sorted(Index& x, std::size_t db, long long id, const std::string& name, bool desc) {
  const auto k = std::make_pair(name, desc);
  if (const auto it = x.orders.find(k); it != x.orders.end()) return it->second;
  std::vector<std::uint32_t> order(x.runs.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  // By number (runs without one last in either order), or by text.
  const auto byNumber = [&](const std::vector<double>& v) {
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const bool ha = std::isfinite(v[a]), hb = std::isfinite(v[b]);
      if (ha != hb) return ha;
      return ha && (desc ? v[b] < v[a] : v[a] < v[b]);
    });
  };
  const auto byText = [&](auto text) {
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return desc ? text(b) < text(a) : text(a) < text(b); });
  };
  const auto& names = x.metric_names;
  const auto facet = std::find_if(std::begin(kFacetNames), std::end(kFacetNames), [&](const char* n) { return name == n; });
  if (std::find(names.begin(), names.end(), name) != names.end()) {
    byNumber(column(x, db, id, name));
  } else if (name.rfind("param.", 0) == 0 && x.param_values.count(name.substr(6))) {
    // A planner parameter: by number when every value is one, else by text; runs of planners
    // without it last.
    const std::string p = name.substr(6);
    std::vector<std::string> text(x.runs.size());
    std::vector<double> v(x.runs.size(), NAN);
    bool numbers = true;
    for (std::size_t i = 0; i < x.runs.size(); ++i) {
      const auto& params = x.params_of_planner[x.facet_of[0][i]];
      if (const auto it = params.find(p); it != params.end()) {
        text[i] = it->second;
        v[i] = asNumber(it->second);
        numbers = numbers && std::isfinite(v[i]);
      }
    }
    if (numbers)
      byNumber(v);
    else
      std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (text[a].empty() != text[b].empty()) return text[b].empty();
        return desc ? text[b] < text[a] : text[a] < text[b];
      });
  } else if (name == "wall_name") {
    byText([&](std::uint32_t i) -> const std::string& { return x.runs[i].wall_name; });
  } else if (facet != std::end(kFacetNames)) {
    const std::size_t f = static_cast<std::size_t>(facet - std::begin(kFacetNames));
    byText([&](std::uint32_t i) -> const std::string& { return x.facet_values[f][x.facet_of[f][i]]; });
  } else if (!name.empty()) {
    throw HttpError(400, "sort: unknown column '" + shown(name) + "' (a metric, param.NAME, wall_name, planner, dataset, status or tool)");
  }
  return x.orders.emplace(k, std::move(order)).first->second;
}

}  // namespace coverbench::cli::serve_internal
