// Published results: the table of values from elsewhere, read strictly (docs/report.md).
#include "coverbench/published.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>

#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/input_error.hpp"
#include "coverbench/metric_spec.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

constexpr const char* kHeader = "instance,method,metric,value";
constexpr const char* kFields[] = {"instance", "method", "metric", "value"};

/// The fields of one line: plain fields end at a comma; a field that begins with a quote ends at
/// the next lone quote ("" stands for one). Returns false with `problem` set otherwise.
bool splitFields(const std::string& line, std::vector<std::string>& fields, std::string& problem) {
  fields.clear();
  std::size_t i = 0;
  while (true) {
    std::string field;
    if (i < line.size() && line[i] == '"') {
      for (++i;; ++i) {
        if (i >= line.size()) {
          problem = "a quoted field has no closing quote (a field cannot hold a line break)";
          return false;
        }
        if (line[i] != '"') {
          field += line[i];
        } else if (i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          ++i;
          break;
        }
      }
      if (i < line.size() && line[i] != ',') {
        problem = "text after a quoted field's closing quote";
        return false;
      }
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      field = line.substr(i, end - i);
      if (field.find('"') != std::string::npos) {
        problem = "a quote inside an unquoted field (quote the whole field, \"\" for a quote)";
        return false;
      }
      i = end;
    }
    fields.push_back(std::move(field));
    if (i >= line.size()) return true;
    ++i;  // the comma
  }
}

/// A field as an error message shows it: its first 40 bytes (cut between UTF-8 characters), "..."
/// when there is more.
std::string shortened(const std::string& text) {
  if (text.size() <= 40) return text;
  std::size_t n = 40;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // not inside a character
  return text.substr(0, n) + "...";
}

/// A field without control characters (a tab, an escape sequence), which no name, metric or
/// number holds and which an error message must not echo to a terminal.
void checkPrintable(const std::string& text, const std::string& source, const char* field) {
  for (unsigned char c : text)
    if (c < 0x20 || c == 0x7f) throw InputError(source, field, "holds a control character");
}

/// A name field: not empty, at most kMaxPublishedName bytes, printable (no control characters).
void checkName(const std::string& text, const std::string& source, const char* field) {
  if (text.empty()) throw InputError(source, field, "must not be empty");
  if (text.size() > kMaxPublishedName)
    throw InputError(source, field, "longer than " + std::to_string(kMaxPublishedName) + " bytes");
  checkPrintable(text, source, field);
}

std::optional<double> parseValue(const std::string& text, const std::string& source) {
  if (text.empty()) return std::nullopt;  // the method did not solve the instance
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const std::string shown = shortened(text);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(source, "value", "must be a finite number (or empty: not solved), got '" + shown + "'");
  if (v < 0.0) throw InputError(source, "value", "must be >= 0 (every compared metric is), got " + shown);
  return v;
}

void checkMetric(const std::string& name, const std::string& source) {
  const MetricSpec* spec = findMetricSpec(name);
  if (!spec) {
    throw InputError(source, "metric", "unknown metric '" + shortened(name) + "' (docs/metrics.md lists them)");
  }
  if (spec->kind == MetricKind::Measured)
    throw InputError(source, "metric", "'" + shownBytes(name) + "' is measured on a machine: a value from another machine is not comparable");
  if (spec->kind != MetricKind::Quality || spec->better == 0)
    throw InputError(source, "metric", "'" + shownBytes(name) + "' is not a compared quality metric (docs/metrics.md)");
}

}  // namespace

bool sameClock(const MotionLimits& a, const MotionLimits& b) {
  return a.speed == b.speed && a.acceleration == b.acceleration && a.stops == b.stops &&
         (a.stops == MotionLimits::Stops::Waypoints || a.stop_angle_deg == b.stop_angle_deg) &&
         a.turn_cost_s == b.turn_cost_s && a.rotation_speed == b.rotation_speed;
}

PublishedTable readPublishedTable(const std::string& path, std::optional<MotionLimits> clock) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!ec && fs::exists(st) && !fs::is_directory(st)) {
    if (!fs::is_regular_file(st)) throw InputError(path, "(file)", "is not a regular file");
    const auto size = fs::file_size(path, ec);
    if (!ec && size > kMaxPublishedBytes)
      throw InputError(path, "(file)", "is " + std::to_string(size) + " bytes, over the limit of " +
                                           std::to_string(kMaxPublishedBytes) + " for a published table");
  }
  std::string text = readFile(path);  // names a missing file or a folder
  if (text.size() > kMaxPublishedBytes)  // grew since it was measured
    throw InputError(path, "(file)", "over the limit of " + std::to_string(kMaxPublishedBytes) + " bytes for a published table");
  PublishedTable table;
  table.file = path;
  table.sha256 = sha256Hex(text);
  table.clock = clock;
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // a spreadsheet's byte order mark

  std::map<std::tuple<std::string, std::string, std::string>, int> seen;
  std::vector<std::string> fields;
  std::size_t at = 0;
  int line_no = 0;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string source = path + ":" + std::to_string(line_no);
    if (line.find('\0') != std::string::npos) throw InputError(source, "(row)", "holds a NUL byte (not a text file)");
    if (!isValidUtf8(line)) throw InputError(source, "(row)", "is not valid UTF-8 text");
    if (line.find('\r') != std::string::npos)
      throw InputError(source, "(row)", "holds a carriage return inside the line (lines end with \\n or \\r\\n)");
    if (line.find("\xEF\xBB\xBF") != std::string::npos)
      throw InputError(source, "(row)", "holds a byte order mark (U+FEFF): only the file's first bytes may");
    if (line_no == 1) {
      if (line != kHeader)
        throw InputError(source, "(header)", std::string("must be exactly '") + kHeader + "'");
      continue;
    }
    if (line.empty()) throw InputError(source, "(row)", "an empty line (every row has four fields)");
    std::string problem;
    if (!splitFields(line, fields, problem)) throw InputError(source, "(row)", problem);
    if (fields.size() != 4)
      throw InputError(source, "(row)", "has " + std::to_string(fields.size()) + " fields, not 4 (" + kHeader + ")");
    if (table.values.size() >= kMaxPublishedRows)
      throw InputError(source, "(row)", "more than " + std::to_string(kMaxPublishedRows) + " rows");
    PublishedValue v;
    v.instance = fields[0];
    v.method = fields[1];
    v.metric = fields[2];
    v.line = line_no;
    checkName(v.instance, source, kFields[0]);
    checkName(v.method, source, kFields[1]);
    for (int k : {2, 3}) checkPrintable(fields[static_cast<std::size_t>(k)], source, kFields[k]);
    checkMetric(v.metric, source);
    v.value = parseValue(fields[3], source);
    const auto [it, fresh] = seen.emplace(std::make_tuple(v.instance, v.method, v.metric), line_no);
    if (!fresh)
      throw InputError(source, "(row)", "instance '" + v.instance + "', method '" + v.method + "', metric '" + v.metric +
                                            "' again (first on line " + std::to_string(it->second) + ")");
    table.values.push_back(std::move(v));
  }
  if (line_no == 0) throw InputError(path + ":1", "(header)", std::string("missing: the file is empty (") + kHeader + ")");
  if (table.values.empty()) throw InputError(path + ":2", "(row)", "no rows after the header");
  return table;
}

}  // namespace coverbench
