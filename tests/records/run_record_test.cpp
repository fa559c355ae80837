// The run record's field table (records/run_record.hpp) drives every place a run's values travel:
// every field, set to a value of its own, crosses the worker pipe, SQLite, a merge of shards and
// both exports unchanged, and the report data declares it for the Python reader. A field added to
// the table is covered here without an edit.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "../experiments/src/isolation.hpp"
#include "coverbench/param_codec.hpp"
#include "coverbench/records.hpp"
#include "coverbench/report_data.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/run_record.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

/// Every field but the key set to a value of its own, unlike its default: text "v:NAME" with a
/// comma, a quote and a newline (as a reason or a planner's stderr may have), status partial,
/// true, 7 + i, 0.5 + i (exact in binary).
RunFields distinctFields(const std::string& key) {
  RunFields r;
  std::size_t i = 0;
  auto set = [&](const RunField& f, auto& value) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, std::string>) value = std::string("v:") + f.name + ", \"quoted\"\nnext line";
    else if constexpr (std::is_same_v<T, RunStatus>) value = RunStatus::Partial;
    else if constexpr (std::is_same_v<T, bool>) value = true;
    else if constexpr (std::is_same_v<T, long long>) value = static_cast<long long>(7 + i);
    else value = 0.5 + static_cast<double>(i);
    ++i;
  };
  forEachRunField(r, set);
  r.key = key;
  return r;
}

/// The records of CSV text (RFC 4180: a quoted cell may hold commas, doubled quotes, newlines).
std::vector<std::vector<std::string>> csvRecords(const std::string& text) {
  std::vector<std::vector<std::string>> out(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') out.back().back() += '"', ++i;
      else if (c == '"') quoted = false;
      else out.back().back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.back().emplace_back();
    } else if (c == '\n') {
      out.emplace_back(1);
    } else {
      out.back().back() += c;
    }
  }
  if (out.back().size() == 1 && out.back()[0].empty()) out.pop_back();
  return out;
}

/// Each field of `a` and `b` (same type) compared, with its name on failure.
void expectSameFields(const RunFields& a, const RunFields& b, const std::string& where) {
  std::vector<std::string> as, bs;
  auto text = [](std::vector<std::string>& out) {
    return [&out](const RunField& f, const auto& value) {
      std::ostringstream s;
      s.precision(17);
      s << f.name << "=" << value;
      out.push_back(s.str());
    };
  };
  forEachRunField(a, text(as));
  forEachRunField(b, text(bs));
  ASSERT_EQ(as.size(), kRunFieldCount);
  EXPECT_EQ(as, bs) << where;
}

TEST(RunFields, TheTableNamesEachFieldOnceWithATypeAndTheVisitorFollowsIt) {
  std::set<std::string> names;
  for (const RunField& f : kRunFields) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    EXPECT_GT(std::string(f.description).size(), 10u) << f.name;
  }
  EXPECT_EQ(std::string(kRunFields[0].name), "key");
  std::size_t i = 0;
  RunFields r;
  forEachRunField(r, [&](const RunField& f, auto&) { EXPECT_EQ(&f, &kRunFields[i++]); });
  EXPECT_EQ(i, kRunFieldCount);
  for (RunStatus s : kRunStatuses) EXPECT_EQ(parseRunStatus(toString(s)), s);
  EXPECT_FALSE(parseRunStatus("fine"));
}

TEST(RunFields, EveryFieldCrossesTheWorkerPipe) {
  RunRecord rec;
  static_cast<RunFields&>(rec) = distinctFields("k");
  rec.metrics = {{"coverage_reachable", 0.25}, {"length_total", 3.0}};
  rec.plan_times_ms = {1.0, 2.0};
  const RunRecord back = deserializeRecord(serializeRecord(rec));
  expectSameFields(rec, back, "through the pipe");
  EXPECT_EQ(back.metrics, rec.metrics);
  EXPECT_EQ(back.plan_times_ms, rec.plan_times_ms);
}

class RunRecordStorage : public test::CommandTest {};

// Runs stored by the results database (every field set by hand), in two shards, merged by the
// command, loaded, and exported as CSV and JSON: every field arrives as it left.
TEST_F(RunRecordStorage, EveryFieldCrossesSqliteTheMergeAndBothExports) {
  const std::string cfg = write("c.yaml", R"(name: fields
output: out
datasets:
  - suite: seed-cases
planners: [zigzag]
tool:
  width: 0.1
  clearance: 0.02
)");
  std::string shards;
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(run("run " + cfg + " --shard " + std::to_string(i) + "/2").exit_code, 0);
    shards += " " + (dir_ / ("out/shards/shard-" + std::to_string(i) + "-of-2.sqlite")).string();
  }
  // Each shard's runs stored again with every field set by hand.
  const ExperimentConfig config = loadExperimentConfig(cfg);
  const std::vector<WallEntry> walls = loadWalls(config);
  const std::vector<RunSpec> specs = expandRuns(config, walls);
  std::size_t restored = 0;
  for (int i = 0; i < 2; ++i) {
    const std::string shard = (dir_ / ("out/shards/shard-" + std::to_string(i) + "-of-2.sqlite")).string();
    std::set<std::string> keys;
    for (const ResultsDb::StoredKey& k : ResultsDb(shard, ResultsDb::Mode::ReadOnly).storedKeys()) keys.insert(k.key);
    ResultsDb db(shard);
    for (const RunSpec& spec : specs)
      if (keys.count(spec.key)) {
        RunRecord rec;
        static_cast<RunFields&>(rec) = distinctFields(spec.key);
        db.storeRun(spec, deserializeRecord(serializeRecord(rec)));
        ++restored;
      }
  }
  ASSERT_EQ(restored, specs.size());
  const std::string merged = (dir_ / "merged.sqlite").string();
  const test::CommandRun m = run("merge " + merged + shards);
  ASSERT_EQ(m.exit_code, 0) << m.err;

  const ResultSet rs = ResultsDb(merged, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), specs.size());
  for (const ResultRow& r : rs.runs) expectSameFields(distinctFields(r.key), r, "stored, merged and loaded: " + r.key);

  // The exports: one column per exported field, each value as it was.
  const nlohmann::json json = nlohmann::json::parse(renderRuns(rs, true));
  const std::string csv = renderRuns(rs, false);
  const std::vector<std::vector<std::string>> records = csvRecords(csv);
  ASSERT_EQ(records.size(), rs.runs.size() + 1) << csv;
  const std::vector<std::string>& columns = records[0];
  const std::vector<std::string>& cells = records[1];
  ASSERT_EQ(cells.size(), columns.size());
  const std::string header = csv.substr(0, csv.find('\n'));
  std::size_t exported = 0;
  forEachRunField(rs.runs[0], [&](const RunField& f, const auto& value) {
    if (f.exported == RunExport::No) return;
    ++exported;
    ASSERT_TRUE(json[0].contains(f.name)) << f.name;
    const auto at = std::find(columns.begin(), columns.end(), f.name);
    ASSERT_NE(at, columns.end()) << f.name << " is not a CSV column: " << header;
    const std::string cell = cells.at(static_cast<std::size_t>(at - columns.begin()));
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, RunStatus>) {
      EXPECT_EQ(json[0][f.name], toString(value));
      EXPECT_EQ(cell, toString(value));
    } else if constexpr (std::is_same_v<T, bool>) {
      EXPECT_EQ(json[0][f.name], value);
      EXPECT_EQ(cell, value ? "true" : "false");
    } else if constexpr (std::is_same_v<T, double>) {
      EXPECT_EQ(json[0][f.name].template get<double>(), value) << f.name;
      EXPECT_EQ(std::stod(cell), value) << f.name;
    } else {
      EXPECT_EQ(json[0][f.name], value) << f.name;
      if constexpr (std::is_same_v<T, std::string>) { EXPECT_EQ(cell, value) << f.name; }
    }
  });
  EXPECT_GE(exported, 6u);
}

// A database made before a field existed (its column dropped here) is read with the field
// empty, and gets the column when opened to be written.
TEST_F(RunRecordStorage, ADatabaseWithoutAFieldsColumnIsReadAndUpgraded) {
  const std::string cfg = write("c.yaml", "name: old\noutput: out\ndatasets:\n  - suite: seed-cases\nplanners: [zigzag]\n"
                                          "tool:\n  width: 0.1\n  clearance: 0.02\n");
  ASSERT_EQ(run("run " + cfg + " --no-report").exit_code, 0);
  const std::string file = (dir_ / "out/results.sqlite").string();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "ALTER TABLE runs DROP COLUMN start_rss_bytes", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  const ResultSet old = ResultsDb(file, ResultsDb::Mode::ReadOnly).load();
  ASSERT_FALSE(old.runs.empty());
  for (const ResultRow& r : old.runs) {
    EXPECT_TRUE(std::isnan(r.start_rss_bytes));
    EXPECT_TRUE(std::isfinite(r.peak_rss_bytes));
  }
  { ResultsDb upgraded(file); }
  EXPECT_NE(test::sqlRows(file, "SELECT name FROM pragma_table_info('runs')").find("start_rss_bytes"), std::string::npos);
  // A run stored from now on has the field.
  ASSERT_EQ(run("run " + cfg + " --no-report --retry-failed").exit_code, 0);
}

// A configuration's parameters are stored as a JSON object with full precision (two overlaps that
// differ in the fifteenth digit stay two), and text stored by older builds still reads.
TEST_F(RunRecordStorage, ParametersAreStoredAsAJsonObjectWithFullPrecision) {
  const std::string cfg = write("c.yaml", "name: p\noutput: out\ndatasets:\n  - suite: seed-cases\nplanners:\n"
                                          "  - name: zigzag\n    params: {overlap: [0.123456789012345, 0.123456789012346]}\n"
                                          "tool:\n  width: 0.1\n  clearance: 0.02\n");
  ASSERT_EQ(run("run " + cfg + " --no-report").exit_code, 0);
  const ExperimentRecord record = ResultsDb((dir_ / "out/results.sqlite").string(), ResultsDb::Mode::ReadOnly).record();
  ASSERT_EQ(record.planners.size(), 2u);
  const nlohmann::json a = storedParamsJson(record.planners[0].params);
  const nlohmann::json b = storedParamsJson(record.planners[1].params);
  EXPECT_EQ(a["overlap"].get<double>(), 0.123456789012345);
  EXPECT_EQ(b["overlap"].get<double>(), 0.123456789012346);
  EXPECT_EQ(a["boundary_passes"], 1);
  EXPECT_EQ(a["direction_search"], false);
  EXPECT_NE(record.planners[0].label, record.planners[1].label);
  EXPECT_NE(storedParamsLine(record.planners[0].params).find("overlap=0.123456789012345"), std::string::npos);
}

TEST(RunFields, ParametersStoredAsTextByOlderBuildsReadAsTypedValues) {
  EXPECT_EQ(storedParamsJson("boundary_passes=1, direction_search=false, order=tsp, overlap=0.2"),
            nlohmann::ordered_json::parse(R"({"boundary_passes":1,"direction_search":false,"order":"tsp","overlap":0.2})"));
  EXPECT_EQ(storedParamsLine(R"({"order":"tsp","overlap":0.1,"loop":true})"), "order=tsp, overlap=0.1, loop=true");
  EXPECT_EQ(storedParamsJson("").dump(), "{}");
}

TEST(RunFields, TheReportDataDeclaresTheExportedFieldsForItsReader) {
  ResultSet rs;
  ResultRow row;
  static_cast<RunFields&>(row) = distinctFields("k1");
  row.planner = row.config = "zigzag";
  rs.planners = {"zigzag"};
  rs.runs = {row};
  const nlohmann::json data = nlohmann::json::parse(reportDataJson(rs, ExperimentRecord{}, {}));
  std::vector<std::string> declared;
  for (const auto& f : data["run_fields"]) declared.push_back(f["name"]);
  std::vector<std::string> exported;
  for (const RunField& f : kRunFields)
    if (f.exported == RunExport::RunsAndReport) exported.push_back(f.name);
  EXPECT_EQ(declared, exported);
  for (const std::string& name : declared) EXPECT_TRUE(data["runs"][0].contains(name)) << name;
  EXPECT_EQ(data["run_statuses"].size(), std::size(kRunStatuses));
}

}  // namespace
}  // namespace coverbench
