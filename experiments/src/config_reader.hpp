#pragma once
// The experiment config's reading (config.cpp, config_tool.cpp): a YAML document copied into a
// plain value tree, and the Reader whose every error names FILE:LINE and the key path.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "coverbench/experiment.hpp"
#include "coverbench/input_error.hpp"

namespace coverbench::config_yaml {

inline std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// A YAML value copied out of yaml-cpp once, at load. yaml-cpp's nodes are handles whose
/// assignment writes through to the shared node (so sorting or reassigning them rewrites the
/// document); every later step reads this plain value tree instead, which cannot alias.
struct Yaml;
struct YamlEntry;
struct Yaml {
  enum class Kind { Null, Scalar, List, Map } kind = Kind::Null;
  std::string scalar;
  std::vector<Yaml> items;          ///< a list's items
  std::vector<YamlEntry> entries;   ///< a map's entries, in file order, keys unique
  int line = 1;                     ///< 1-based
  bool isScalar() const { return kind == Kind::Scalar; }
  bool isMap() const { return kind == Kind::Map; }
  bool isList() const { return kind == Kind::List; }
  const Yaml* find(const std::string& key) const;
};
struct YamlEntry {
  std::string key;
  int key_line = 1;
  Yaml value;
};
inline const Yaml* Yaml::find(const std::string& key) const {
  for (const YamlEntry& e : entries)
    if (e.key == key) return &e.value;
  return nullptr;
}

/// Reads one config file; every error names FILE:LINE and the key path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(int line, const std::string& field, const std::string& problem) const {
    throw InputError(file_ + ":" + std::to_string(line), field, problem);
  }
  [[noreturn]] void fail(const Yaml& at, const std::string& field, const std::string& problem) const {
    fail(at.line, field, problem);
  }

  /// The document as a value tree: keys must be plain scalars and appear once per mapping.
  Yaml copy(const YAML::Node& n, const std::string& where, int depth) {
    if (depth > 32) fail(line(n), where.empty() ? "(document)" : where, "nested more than 32 levels deep");
    if (++nodes_ > 1000000) fail(line(n), where.empty() ? "(document)" : where, "more than 10^6 values (aliases expanding?)");
    Yaml y;
    y.line = line(n);
    if (n.IsScalar()) {
      y.kind = Yaml::Kind::Scalar;
      y.scalar = n.Scalar();
    } else if (n.IsSequence()) {
      y.kind = Yaml::Kind::List;
      std::size_t i = 0;
      for (const YAML::Node& item : n) y.items.push_back(copy(item, where + "[" + std::to_string(i++) + "]", depth + 1));
    } else if (n.IsMap()) {
      y.kind = Yaml::Kind::Map;
      for (auto it = n.begin(); it != n.end(); ++it) {
        if (!it->first.IsScalar())
          fail(line(it->first), where.empty() ? "(document)" : where, "a key must be a plain name, not a list or mapping");
        const std::string key = it->first.Scalar();
        const std::string field = where.empty() ? key : where + "." + key;
        for (const YamlEntry& e : y.entries)
          if (e.key == key) fail(line(it->first), field, "duplicate key (first on line " + std::to_string(e.key_line) + ")");
        y.entries.push_back(YamlEntry{key, line(it->first), copy(it->second, field, depth + 1)});
      }
    }
    return y;
  }

  void onlyKeys(const Yaml& map, const std::string& where, const std::vector<std::string>& allowed) const {
    if (!map.isMap()) fail(map, where.empty() ? "(document)" : where, "must be a mapping of keys to values");
    for (const YamlEntry& e : map.entries) {
      if (std::find(allowed.begin(), allowed.end(), e.key) != allowed.end()) continue;
      std::string hint;
      std::size_t best = 3;
      for (const std::string& a : allowed)
        if (editDistance(e.key, a) < best) best = editDistance(e.key, a), hint = a;
      std::string known;
      for (const std::string& a : allowed) known += (known.empty() ? "" : ", ") + a;
      fail(e.key_line, where.empty() ? shownBytes(e.key) : where + "." + shownBytes(e.key),
           "unknown key" + (hint.empty() ? " (allowed: " + known + ")" : " (did you mean '" + hint + "'?)"));
    }
  }

  std::string text(const Yaml& n, const std::string& field) const {
    if (!n.isScalar()) fail(n, field, "must be a single value");
    return n.scalar;
  }
  double number(const Yaml& n, const std::string& field, double lo, double hi, bool open_lo = false, bool open_hi = false) const {
    const std::string t = text(n, field);
    double v = 0.0;
    std::size_t used = 0;
    try {
      v = std::stod(t, &used);
    } catch (...) {
      used = 0;
    }
    if (used != t.size() || t.empty() || !std::isfinite(v)) fail(n, field, "must be a number, got '" + shownBytes(t) + "'");
    // std::stod also reads hexadecimal ("0x10" as 16), which a config does not mean.
    if (t.find_first_of("xX") != std::string::npos) fail(n, field, "must be a decimal number, got '" + shownBytes(t) + "'");
    if (v < lo || v > hi || (open_lo && v == lo) || (open_hi && v == hi))
      fail(n, field, "must be in " + std::string(open_lo ? "(" : "[") + shortNumber(lo) + ", " + shortNumber(hi) + (open_hi ? ")" : "]") +
                         ", got " + shownBytes(t));
    return v;
  }
  long long integer(const Yaml& n, const std::string& field, long long lo, long long hi) const {
    const double v = number(n, field, static_cast<double>(lo), static_cast<double>(hi));
    if (v != std::floor(v)) fail(n, field, "must be a whole number, got " + shownBytes(text(n, field)));
    return static_cast<long long>(v);
  }
  bool boolean(const Yaml& n, const std::string& field) const {
    const std::string t = text(n, field);
    if (t == "true") return true;
    if (t == "false") return false;
    fail(n, field, "must be true or false, got '" + shownBytes(t) + "'");
  }
  /// A scalar or a list of scalars, as a list.
  std::vector<const Yaml*> values(const Yaml& n, const std::string& field) const {
    std::vector<const Yaml*> out;
    if (n.isList()) {
      if (n.items.empty()) fail(n, field, "must not be an empty list");
      for (const Yaml& item : n.items) out.push_back(&item);
    } else {
      out.push_back(&n);
    }
    return out;
  }
  const std::string& file() const { return file_; }

 private:
  static int line(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 1; }
  std::string file_;
  std::size_t nodes_ = 0;
};

/// `tool.profile` (config_tool.cpp): the flux profile of every tool of the config
/// (flux_profile.hpp), checked against each tool's width.
FluxProfile readProfile(Reader& r, const Yaml& p, const std::vector<double>& widths);
/// The `tool:` section (config_tool.cpp): width, clearance, shape and a rectangle's depth, each a
/// value or a list naming nothing twice (the tools are their product), and one flux profile.
void readTools(Reader& r, const Yaml* t, ExperimentConfig& c);

}  // namespace coverbench::config_yaml
