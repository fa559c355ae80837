#pragma once
/// The sub-commands of `coverbench`, kept apart from argument parsing (which only main.cpp does).

#include <cstddef>
#include <exception>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "coverbench/planner.hpp"
#include "coverbench/wall_import.hpp"

namespace coverbench::cli {

void listPlanners(std::ostream& out);

/// A vehicle as the command line gives it (--vehicle, --lift-s, --lower-s); unset: the default's
/// (or, for `metrics`, the plan file's).
struct VehicleOptions {
  std::optional<std::string> model;
  std::optional<double> lift_s, lower_s;
  std::optional<double> turn_radius;  ///< car
  bool reverse = false;               ///< car: --reverse
};

struct PlanOptions {
  std::string wall, planner, out, svg;
  ToolParams tool;
  VehicleOptions vehicle;
  TransitSpec transit;        ///< --transit, --transit-iterations, --transit-time-cap
  bool transit_options_given = false;  ///< --transit-iterations or --transit-time-cap was given
  unsigned long long seed = 0;  ///< --seed: what planners and sampling transit planners draw from
  std::vector<std::string> params;  ///< key=value
  double time_limit_s = 60.0;
  std::string start, end;  ///< --start X,Y and --end X,Y (or --end start): over the wall file's own
  ProfileOptions coat;     ///< the tool's flux profile (planners that space rows for an even coat read it)
  std::string tool_shape = "disk";  ///< --tool-shape: disk, line or rectangle (docs/metrics.md#tool-shapes)
};
/// Returns 0 when the plan is ok and valid, 3 when the planner reported a failure or its path is
/// invalid (the plan file is still written and says which). Bad input throws InputError.
int planCommand(const PlanOptions& options);

/// `key=value` items (--param) as pairs; InputError ("--param") for an item without a key or `=`.
std::vector<std::pair<std::string, std::string>> splitSettings(const std::vector<std::string>& items);

struct ConformanceOptions {
  std::string planner;               ///< a registered planner's name or an external planner's manifest
  std::vector<std::string> params;   ///< key=value
  std::vector<std::string> walls;    ///< folders of wall files; default: datasets/canonical and datasets/conformance
  std::string format = "md";         ///< md or json
  std::string out;                   ///< file to write; default: stdout
  double time_limit_s = 60.0;
  std::string source_dir;            ///< where datasets/ is
};
/// The conformance checks for one planner on every conformance wall at two tools, as a report
/// card (Markdown or JSON). Returns 0 when every row passes, 1 otherwise.
int conformanceCommand(const ConformanceOptions& options);

struct MetricsOptions {
  std::string wall, plan, svg;
  std::optional<double> tool_width, clearance;  ///< default: the plan file's, else 0.1 / 0.02
  std::optional<std::string> tool_shape;        ///< default: the plan file's, else disk
  std::optional<double> tool_depth;             ///< a rectangle's; default: the plan file's
  VehicleOptions vehicle;  ///< default: the plan file's, else holonomic
  double speed = 0.3, acceleration = 0.5;
  std::string stops = "turns";  ///< the time model's stops: turns or waypoints
  double stop_angle = 30.0, turn_cost = 0.0, rotation_speed = 0.0;
  double time_limit_s = 600.0;  ///< scoring (and picture) past it: a one-line error, exit 2
  std::string judge = "fast";   ///< "fast", or "exact": also the exact judge, side by side
  int arc_vertices = 128;       ///< the exact judge's disk polygons
  ProfileOptions coat;  ///< the tool's flux profile: "none" gives no deposition metrics
  std::string coat_svg;  ///< the coat's thickness map (SVG); needs a profile
};
/// Prints every metric of a plan file (from any source) as JSON. Returns 0 when the path is
/// valid, 3 when it is not (with --judge exact: when either judge finds it invalid).
int metricsCommand(const MetricsOptions& options);

struct CarCeilingCommandOptions {
  std::string wall;
  ToolParams tool;
  double turn_radius = 0.5, resolution = 0.02;
  std::size_t headings = 72;
};
/// Prints what a forward-only car could paint at best on the wall (car_ceiling.hpp) as JSON.
int carCeilingCommand(const CarCeilingCommandOptions& options);

struct ShowcaseOptions {
  std::string walls, out;
  ToolParams tool;
};
/// Returns 0 when every plan is ok and valid, 3 otherwise.
int showcaseCommand(const ShowcaseOptions& options);

}  // namespace coverbench::cli

namespace coverbench::cli {

struct DatasetGenerateOptions {
  std::string family, out;
  long long count = 0;  ///< signed, so a negative count is refused rather than wrapped around
  long long seed = 0;
};
/// Writes the walls and manifest.json; prints where and a summary.
int datasetGenerateCommand(const DatasetGenerateOptions& options);
struct DatasetImportOptions {
  std::vector<std::string> sources;
  std::string out;
  std::string transform;  ///< as typed; parsed into options.transform
  bool refuse_multipolygons = false;
  ImportOptions options;
};
/// Imports maps and polygons into a dataset folder (walls plus a manifest with the sources' hashes
/// and the options); prints where and a summary.
int datasetImportCommand(DatasetImportOptions options);
/// Prints a summary of a dataset folder (checking the manifest's hashes).
int datasetShowCommand(const std::string& dir);
/// Prints the generator families and suites.
int datasetFamiliesCommand();

struct RunOptions {
  std::string config;
  unsigned threads = 0;  ///< 0: the config's, else every core
  bool yes = false;      ///< confirms an experiment of more than kLargeExperimentRuns runs
  bool timing = false, retry_failed = false, reuse_across_builds = false;  ///< RunnerOptions
  bool no_report = false;  ///< skip the report (results are stored either way)
  std::string shard;       ///< "I/N": only that shard's runs, into OUTPUT/shards/ (no report)
  std::string command_line;
};
/// Runs an experiment config and writes its report (OUTPUT/report/index.html with tables and
/// figures) next to the results database.
int runCommand(const RunOptions& options);

struct MergeCommandOptions {
  std::string out;
  std::vector<std::string> shards;
  std::string command_line;
};
/// Merges shard databases (`run --shard`) into one; prints what it did. Refusals are InputErrors.
int mergeCommand(const MergeCommandOptions& options);

struct SlurmCommandOptions {
  std::string config;
  unsigned shards = 8, cpus_per_task = 1, throttle = 0;
  std::string partition, time = "04:00:00", mem, account;
  bool no_report = false, submit = false, yes = false;
};
/// Writes OUTPUT/slurm/run.sbatch (the array) and merge.sbatch; with --submit, submits both
/// (the merge after the array) with sbatch.
int slurmCommand(const SlurmCommandOptions& options);

struct ExportOmplOptions {
  std::string database, out;
  std::optional<long long> experiment;
};
/// Writes one OMPL benchmark log per dataset of an experiment into the folder `out`.
int exportOmplCommand(const ExportOmplOptions& options);

struct ReportOptions {
  std::string database, format = "md", out, baseline;
  /// A published table (CSV) and its clock, instead of the one the config names (docs/report.md).
  std::string published, published_clock;
  bool no_published = false;  ///< leave out the table the stored config names
  std::optional<long long> experiment;
};

struct RunsOptions {
  std::string database, format = "csv";
  std::optional<long long> experiment;
  bool list = false;
};
/// Prints every run of an experiment (default: the latest) as CSV or JSON, or a list of keys.
int runsCommand(const RunsOptions& options);

struct RedrawOptions {
  std::string database, run, svg;
  std::string coat_svg;  ///< also the coat's picture (the run's tool must have a flux profile); empty: none
  std::optional<std::size_t> replan;  ///< draw this repair of the run instead (replans table, 0-based)
};
/// Redraws a stored run (its wall, path and coverage layer) as an SVG picture, and with
/// `coat_svg` the coat it lays (its experiment's flux profile and time model).
int redrawCommand(const RedrawOptions& options);
/// html: writes the report folder (--out); md, csv, latex: prints (or writes) its tables.
int reportCommand(const ReportOptions& options);
/// Writes the HTML report of `options` into the folder options.out (all or nothing; an earlier
/// report there is replaced, any other folder refused). Returns the page's path.
std::string writeReport(const ReportOptions& options);
/// Gallery pictures are shown about 400 pixels wide: 350 overlap strips over a wall's height are
/// about one per pixel there, and keep a stress wall's picture near 2 MB instead of 18 MB.
inline constexpr double kGalleryOverlapStrips = 350.0;
/// The coverage layer of a path costs about 20 s at 80 000 waypoints (a stress wall's spiral);
/// gallery pictures of longer paths than this leave it out and say so (`redraw` draws it).
inline constexpr std::size_t kGalleryCoverageWaypoints = 20000;
/// How a stored run is pictured: `scorable` when it has a path the metrics engine could score,
/// `layer` when its picture also gets the coverage layer (scorable, at most
/// kGalleryCoverageWaypoints waypoints). The report's gallery and the explorer both use it.
struct PictureLayers {
  bool scorable = false, layer = false;
};
PictureLayers pictureLayers(const Path& path, const std::string& status);

struct ServeOptions {
  std::vector<std::string> databases;
  std::vector<std::string> wall_folders;  ///< --walls: folders whose wall files the workbench opens
  std::string walls_db;                   ///< --walls-db: where the workbench saves walls (created if absent)
  double plan_time_limit_s = 60.0;        ///< --plan-time-limit: the most a workbench plan may ask for
  std::string host = "127.0.0.1";
  int port = 8080;
};
/// Serves the explorer (docs/explorer.md) over the named databases until stopped: serveHere in
/// the plug-in libcoverbench_serve.so (serve_plugin.hpp), opened here. Throws InputError naming
/// the plug-in when it cannot be opened.
int serveCommand(const ServeOptions& options);
/// serveCommand in this process (the plug-in's own code; cli/serve_command.cpp).
int serveHere(const ServeOptions& options);

/// An error whose one-line message has already been printed (by the analysis, which names the
/// file it could not write): the command exits with 2 and prints nothing more.
struct AlreadyReported : std::exception {
  const char* what() const noexcept override { return "already reported"; }
};
/// Runs the analysis (python3 -m coverbench_report, reports/python) on a report data or
/// showcase file, writing `formats` (comma-separated: html, md, csv, latex) into `folder`.
/// Throws AlreadyReported when it could not write a file (its message is on stderr).
void runAnalysis(const std::string& data, const std::string& folder, const std::string& formats);
/// The showcase page (the report machinery's layout) for showcase data (format
/// "coverbench-showcase"), as text; nothing is written.
std::string renderShowcasePage(const std::string& data_json);

}  // namespace coverbench::cli
