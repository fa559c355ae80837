// The `coverbench` command. Every user error surfaces here as one line on stderr and exit code 2.
#include <cctype>
#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "serve.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/wall.hpp"

namespace {

/// Every option's value, read one way before CLI11 converts it: an empty value is refused (CLI11
/// keeps the default for `--turn-radius ""`), and a number must be one its option's type holds
/// (CLI11 saturates `--experiment 99999999999999999999` to the largest long long) and finite,
/// except `inf` where `infinity` names what it means (`--acceleration inf`: no ramp).
CLI::Validator valueReader(const std::string& type, const std::string& infinity = "") {
  return CLI::Validator(
      [type, infinity](std::string& value) -> std::string {
        if (!infinity.empty() && value == "inf") return std::string();
        if (value.empty()) return "must not be empty";
        if (type == "INT" || type == "UINT") {
          const char* first = value.data();
          const char* last = value.data() + value.size();
          if (type == "UINT" && *first == '-') return "must be a whole number of at least 0, got '" + coverbench::shownBytes(value) + "'";
          long long s = 0;
          unsigned long long u = 0;
          const auto [end, ec] = type == "INT" ? std::from_chars(first, last, s) : std::from_chars(first, last, u);
          if (ec == std::errc::result_out_of_range)
            return "must be a whole number of at most " +
                   (type == "INT" ? std::to_string(std::numeric_limits<long long>::max())
                                  : std::to_string(std::numeric_limits<unsigned long long>::max())) +
                   ", got '" + coverbench::shownBytes(value) + "'";
          if (ec != std::errc() || end != last) return "must be a whole number, got '" + coverbench::shownBytes(value) + "'";
        } else if (type == "FLOAT") {
          // As a config reads numbers: decimal only (strtod also reads "0x10" as 16 and skips
          // leading white space).
          if (value.find_first_of("xX") != std::string::npos || (!value.empty() && std::isspace(static_cast<unsigned char>(value[0]))))
            return "must be a decimal number, got '" + coverbench::shownBytes(value) + "'";
          char* end = nullptr;
          const double v = std::strtod(value.c_str(), &end);
          if (end != value.c_str() + value.size() || !std::isfinite(v))
            return "must be a finite number" + (infinity.empty() ? std::string() : " or inf (" + infinity + ")") + ", got '" +
                   coverbench::shownBytes(value) + "'";
        }
        return std::string();
      },
      "", "value");
}

/// One of `names`, or a one-line error quoting the value as every other message does (CLI11's
/// IsMember echoes it whole).
CLI::Validator oneOf(std::vector<std::string> names) {
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return CLI::Validator(
      [names, list](std::string& value) {
        for (const std::string& n : names)
          if (value == n) return std::string();
        return "must be " + list + ", got '" + coverbench::shownBytes(value) + "'";
      },
      list, "one of");
}

void readValuesOneWay(CLI::App& app) {
  for (CLI::Option* option : app.get_options())
    if (option->get_type_size_max() > 0)
      option->check(valueReader(option->get_type_name(), option->get_name() == "--acceleration" ? "no ramp" : ""));
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) readValuesOneWay(*sub);
}

namespace cli = coverbench::cli;

/// Every command's options, filled in by CLI11 as it parses the command line, and the exit code
/// of the command that ran. The commands' callbacks hold references into it.
struct Commands {
  int exit_code = 0;
  cli::PlanOptions plan;
  cli::ConformanceOptions conformance;
  cli::MetricsOptions metrics;
  cli::CarCeilingCommandOptions ceiling;
  cli::ShowcaseOptions showcase;
  cli::DatasetGenerateOptions dataset_generate;
  cli::DatasetImportOptions dataset_import;
  std::string show_dir;
  cli::RunOptions run;
  cli::MergeCommandOptions merge;
  cli::SlurmCommandOptions slurm;
  cli::ReportOptions report;
  cli::RunsOptions runs;
  cli::ExportOmplOptions export_ompl;
  cli::RedrawOptions redraw;
  cli::ServeOptions serve;
};

/// --profile, --sigma, --beta, --rate, --fan-depth, --target and --flow: the tool's flux profile (docs/deposition.md).
void addProfileOptions(CLI::App* command, coverbench::ProfileOptions& coat, const std::string& what) {
  command->add_option("--profile", coat.profile,
                      "the tool's flux profile across its width, " + what + " (docs/deposition.md): "
                      "none, uniform, gaussian (--sigma) or beta (--beta)")
      ->capture_default_str()
      ->each([&coat](const std::string&) { coat.named = true; });
  command->add_option("--sigma", coat.sigma, "gaussian profile: standard deviation, m (at least s/50)");
  command->add_option("--beta", coat.beta, "beta profile: f proportional to (1 - u^2)^(beta - 1), u = x / r; beta in [1, 100]");
  command->add_option("--rate", coat.rate, "what the tool sprays, m^3/s (default 1e-6)");
  command->add_option("--fan-depth", coat.fan_depth, "the spray fan's depth along the motion, m (default and 0: s / 10)");
  command->add_option("--target", coat.target,
                      "the coat aimed at, micrometres: even/thin/thick shares of it, not of the mean (default: none)");
  command->add_option("--flow", coat.flow,
                      "the gun's flow: constant (default; the coat builds up where the tool slows down) or speed "
                      "(it follows the tool's speed: the same coat per metre at any speed)");
}

/// `planners`, `metric-specs` and `plan`: what can plan, what is measured, and one plan.
void addPlanCommands(CLI::App& app, Commands& o) {
  app.add_subcommand("planners", "List the registered planners and their parameters")
      ->callback([] { cli::listPlanners(std::cout); });

  app.add_subcommand("metric-specs", "The metric registry as a Markdown table (unit, direction, tie band, ...)")
      ->callback([] { std::cout << coverbench::metricSpecsMarkdown(); });

  cli::PlanOptions& plan = o.plan;
  CLI::App* plan_cmd = app.add_subcommand("plan", "Plan one wall with one planner and write a plan file");
  plan_cmd->add_option("--wall", plan.wall, "wall file (JSON)")->required();
  plan_cmd->add_option("--start", plan.start, "X,Y where the path begins (over the wall file's start)");
  plan_cmd->add_option("--end", plan.end, "X,Y where the path ends, or 'start' (over the wall file's end)");
  plan_cmd->add_option("--planner", plan.planner, "planner name (see `coverbench planners`), or an external planner's manifest (FILE.json)")->required();
  plan_cmd->add_option("--tool-width", plan.tool.tool_width, "tool diameter s in metres")->capture_default_str();
  plan_cmd->add_option("--tool-shape", plan.tool_shape,
                       "disk; line: a segment of length s square to the heading; rectangle: s across it and "
                       "--tool-depth along it (docs/metrics.md#tool-shapes)")
      ->capture_default_str();
  plan_cmd->add_option("--tool-depth", plan.tool.depth, "a rectangle tool's depth d along the heading, metres");
  plan_cmd->add_option("--clearance", plan.tool.clearance, "gap c between tool and obstacles, metres")
      ->capture_default_str();
  plan_cmd->add_option("--vehicle", plan.vehicle.model,
                       "holonomic (default): every move stays in F; gantry: tool-off moves are lifted; car: turns of --turn-radius");
  plan_cmd->add_option("--lift-s", plan.vehicle.lift_s, "gantry: seconds to lift the tool (default 1)");
  plan_cmd->add_option("--lower-s", plan.vehicle.lower_s, "gantry: seconds to lower the tool (default 1)");
  plan_cmd->add_option("--turn-radius", plan.vehicle.turn_radius, "car: its smallest turn radius, m (default 0.5)");
  plan_cmd->add_flag("--reverse", plan.vehicle.reverse, "car: it may reverse (Reeds-Shepp); default forward only (Dubins)");
  plan_cmd->add_option("--transit", plan.transit.planner,
                       "transit planner for detours: visibility (default: shortest on its visibility graph), rrtstar, prmstar, bitstar, informed-rrtstar")
      ->capture_default_str();
  CLI::Option* transit_iterations = plan_cmd->add_option("--transit-iterations", plan.transit.iterations,
                                                         "sampling transit planners: iterations per query")->capture_default_str();
  CLI::Option* transit_cap = plan_cmd->add_option("--transit-time-cap", plan.transit.time_cap_s,
                                                  "sampling transit planners: seconds a query may take at most")->capture_default_str();
  plan_cmd->add_option("--seed", plan.seed, "seed of the planner and a sampling transit planner")->capture_default_str();
  plan_cmd->add_option("--param", plan.params, "planner parameter key=value (repeatable)");
  plan_cmd->add_option("--time-limit", plan.time_limit_s, "seconds before the planner must stop")
      ->capture_default_str();
  plan_cmd->add_option("--out", plan.out, "plan file to write (JSON)")->required();
  plan_cmd->add_option("--svg", plan.svg, "picture to write (SVG)");
  addProfileOptions(plan_cmd, plan.coat, "for the thickness metrics and the planners that space rows for an even coat (coat_ripple)");
  plan_cmd->callback([&o, transit_iterations, transit_cap] {
    o.plan.transit_options_given = transit_iterations->count() > 0 || transit_cap->count() > 0;
    o.exit_code = cli::planCommand(o.plan);
  });
}

/// `conformance`, `metrics`, `car-ceiling` and `showcase`: planners and plans checked and scored.
void addCheckCommands(CLI::App& app, Commands& o) {
  cli::ConformanceOptions& conformance = o.conformance;
  conformance.source_dir = COVERBENCH_SOURCE_DIR;
  CLI::App* conformance_cmd = app.add_subcommand(
      "conformance", "The conformance checks for one planner (in-tree or external) on every conformance wall, as a report card");
  conformance_cmd->add_option("planner", conformance.planner, "planner name, or an external planner's manifest (FILE.json)")
      ->required();
  conformance_cmd->add_option("--param", conformance.params, "planner parameter key=value (repeatable)");
  conformance_cmd->add_option("--walls", conformance.walls,
                              "folder of wall files (repeatable; default: datasets/canonical and datasets/conformance)");
  conformance_cmd->add_option("--format", conformance.format, "md or json")->capture_default_str()->check(oneOf({"md", "json"}));
  conformance_cmd->add_option("--out", conformance.out, "file to write (default: standard output)");
  conformance_cmd->add_option("--time-limit", conformance.time_limit_s, "seconds per plan")->capture_default_str();
  conformance_cmd->callback([&o] { o.exit_code = cli::conformanceCommand(o.conformance); });

  cli::MetricsOptions& metrics = o.metrics;
  CLI::App* metrics_cmd =
      app.add_subcommand("metrics", "Score a plan file from any source against a wall; prints JSON");
  metrics_cmd->add_option("--wall", metrics.wall, "wall file (JSON)")->required();
  metrics_cmd->add_option("--plan", metrics.plan, "plan file: needs only waypoints and tool_on")->required();
  metrics_cmd->add_option("--tool-width", metrics.tool_width, "tool diameter s in metres (default: the plan's, else 0.1)");
  metrics_cmd->add_option("--tool-shape", metrics.tool_shape, "disk, line or rectangle (default: the plan's, else disk; docs/metrics.md#tool-shapes)");
  metrics_cmd->add_option("--tool-depth", metrics.tool_depth, "a rectangle tool's depth d in metres (default: the plan's)");
  metrics_cmd->add_option("--clearance", metrics.clearance, "gap c in metres (default: the plan's, else 0.02)");
  metrics_cmd->add_option("--vehicle", metrics.vehicle.model, "holonomic, gantry or car (default: the plan's, else holonomic)");
  metrics_cmd->add_option("--turn-radius", metrics.vehicle.turn_radius, "car: its smallest turn radius, m (default: the plan's, else 0.5)");
  metrics_cmd->add_flag("--reverse", metrics.vehicle.reverse, "car: it may reverse (Reeds-Shepp; default: the plan's, else forward only)");
  metrics_cmd->add_option("--lift-s", metrics.vehicle.lift_s, "gantry: seconds to lift the tool (default: the plan's, else 1)");
  metrics_cmd->add_option("--lower-s", metrics.vehicle.lower_s, "gantry: seconds to lower the tool (default: the plan's, else 1)");
  metrics_cmd->add_option("--speed", metrics.speed, "tool speed v for duration_s, m/s")->capture_default_str();
  metrics_cmd->add_option("--acceleration", metrics.acceleration, "acceleration a for duration_s, m/s^2 (inf: no ramp)")
      ->capture_default_str();
  metrics_cmd->add_option("--stops", metrics.stops, "where duration_s stops: turns (over --stop-angle) or waypoints (every one)")
      ->capture_default_str();
  metrics_cmd->add_option("--stop-angle", metrics.stop_angle, "with --stops turns: stop at heading changes over this, degrees")
      ->capture_default_str();
  metrics_cmd->add_option("--turn-cost", metrics.turn_cost, "seconds per turn over 1 degree, reported as turn_cost_s (0: none)")
      ->capture_default_str();
  metrics_cmd->add_option("--rotation-speed", metrics.rotation_speed,
                          "rad/s: stop and rotate in place at every heading change, angle / this (0: none)")
      ->capture_default_str();
  addProfileOptions(metrics_cmd, metrics.coat, "for the coat's thickness metrics");
  metrics_cmd->add_option("--coat-svg", metrics.coat_svg, "picture of the coat's thickness over R, with its scale in micrometres (SVG; needs --profile)");
  metrics_cmd->add_option("--svg", metrics.svg, "picture with the coverage layer (SVG)");
  metrics_cmd->add_option("--time-limit", metrics.time_limit_s, "seconds scoring may take before it is abandoned")
      ->capture_default_str();
  metrics_cmd->add_option("--judge", metrics.judge,
                          "fast: the metrics engine; exact: also CGAL's exact judge, with the difference (docs/metrics.md)")
      ->check(oneOf({"fast", "exact"}))
      ->capture_default_str();
  metrics_cmd->add_option("--arc-vertices", metrics.arc_vertices,
                          "vertices of the exact judge's inscribed and circumscribed disk polygons (multiple of 8)")
      ->capture_default_str();
  metrics_cmd->callback([&o] { o.exit_code = cli::metricsCommand(o.metrics); });

  cli::CarCeilingCommandOptions& ceiling = o.ceiling;
  CLI::App* ceiling_cmd = app.add_subcommand(
      "car-ceiling", "What a forward-only car could paint at best on a wall: an estimate on a lattice of poses (docs/metrics.md); prints JSON");
  ceiling_cmd->add_option("--wall", ceiling.wall, "wall file (JSON)")->required();
  ceiling_cmd->add_option("--tool-width", ceiling.tool.tool_width, "tool diameter s in metres")->capture_default_str();
  ceiling_cmd->add_option("--clearance", ceiling.tool.clearance, "gap c between tool and obstacles, metres")->capture_default_str();
  ceiling_cmd->add_option("--turn-radius", ceiling.turn_radius, "the car's smallest turn radius, m")->capture_default_str();
  ceiling_cmd->add_option("--resolution", ceiling.resolution, "the lattice's cell, m (raised for walls that would need too many poses)")
      ->capture_default_str();
  ceiling_cmd->add_option("--headings", ceiling.headings, "headings per cell")->capture_default_str();
  ceiling_cmd->callback([&o] { o.exit_code = cli::carCeilingCommand(o.ceiling); });

  cli::ShowcaseOptions& showcase = o.showcase;
  CLI::App* show_cmd = app.add_subcommand(
      "showcase", "Plan every wall of a folder with every planner: plan files, pictures and a summary table");
  show_cmd->add_option("--walls", showcase.walls, "folder of wall files")->required();
  show_cmd->add_option("--out", showcase.out, "output folder")->required();
  show_cmd->add_option("--tool-width", showcase.tool.tool_width, "tool diameter s in metres")->capture_default_str();
  show_cmd->add_option("--clearance", showcase.tool.clearance, "gap c in metres")->capture_default_str();
  show_cmd->callback([&o] { o.exit_code = cli::showcaseCommand(o.showcase); });
}

/// `dataset generate|import|show|families`: wall datasets made, imported and inspected.
void addDatasetCommands(CLI::App& app, Commands& o) {
  CLI::App* dataset_cmd = app.add_subcommand("dataset", "Generate and inspect wall datasets");
  dataset_cmd->require_subcommand(1);
  cli::DatasetGenerateOptions& gen = o.dataset_generate;
  CLI::App* gen_cmd = dataset_cmd->add_subcommand("generate", "Write N walls of a family (or a suite) and a manifest");
  gen_cmd->add_option("--family", gen.family, "family or suite (see `coverbench dataset families`)")->required();
  gen_cmd->add_option("--count", gen.count, "number of walls (a suite: default all)");
  gen_cmd->add_option("--seed", gen.seed, "seed: same family, count and seed give the same bytes")->capture_default_str();
  gen_cmd->add_option("--out", gen.out, "output folder (new or empty)")->required();
  gen_cmd->callback([&o] { o.exit_code = cli::datasetGenerateCommand(o.dataset_generate); });
  cli::DatasetImportOptions& imp = o.dataset_import;
  CLI::App* imp_cmd = dataset_cmd->add_subcommand(
      "import", "Import maps and polygons (GeoJSON, GML, KML, Shapefile, GeoPackage, DXF, WKT, polygon text, YAML, "
                "map_server maps) into a dataset folder");
  imp_cmd->add_option("sources", imp.sources, "files or folders to import")->required();
  imp_cmd->add_option("--out", imp.out, "output folder (new or empty)")->required();
  std::string formats;
  for (const std::string& f : coverbench::importFormats()) formats += (formats.empty() ? "" : ", ") + f;
  imp_cmd->add_option("--format", imp.options.format, "one of " + formats)->capture_default_str();
  imp_cmd->add_option("--crs", imp.options.crs, "CRS in metres for geographic input (default: the local UTM zone)");
  imp_cmd->add_option("--source-crs", imp.options.source_crs, "CRS of input that names none, or metres (default: metres; degree-like coordinates are refused)");
  imp_cmd->add_option("--name-field", imp.options.name_field, "attribute that names each wall (default: name)");
  imp_cmd->add_flag("--refuse-multipolygons", imp.refuse_multipolygons, "refuse a multipolygon instead of one wall per part");
  imp_cmd->add_option("--boundary-layer", imp.options.dxf_boundary_layer, "DXF layer of the boundaries")->capture_default_str();
  imp_cmd->add_option("--obstacle-layer", imp.options.dxf_obstacle_layers, "DXF layer of obstacles (repeatable; default: every other layer)");
  imp_cmd->add_flag("--all-components", imp.options.all_components, "maps: every free component as a wall (default: the largest)");
  imp_cmd->add_option("--min-hole-area", imp.options.min_hole_area, "drop holes smaller than this (m^2), and count them")->capture_default_str();
  imp_cmd->add_option("--simplify", imp.options.simplify, "maps: simplification tolerance in metres (default: half a pixel)");
  imp_cmd->add_option("--rooms", imp.options.rooms,
                      "a map's segmentation image (each room's pixels one grey value, 0 none): one wall per room, "
                      "MAP-room-LABEL, its largest free part; what is dropped is counted");
  imp_cmd->add_option("--min-room-area", imp.options.min_room_area, "with --rooms: drop rooms whose wall has fewer free m^2 than this")
      ->capture_default_str();
  imp_cmd->add_option("--transform", imp.transform, "placement, in order: translate=X,Y rotate=DEG scale=S");
  imp_cmd->add_option("--origin", imp.options.origin, "keep, corner (each wall's lower-left at 0,0) or auto (corner beyond 10 km)")
      ->capture_default_str();
  imp_cmd->callback([&o] { o.exit_code = cli::datasetImportCommand(o.dataset_import); });
  CLI::App* dshow_cmd = dataset_cmd->add_subcommand("show", "Summarise a dataset folder (checks the manifest's hashes)");
  dshow_cmd->add_option("dir", o.show_dir, "dataset folder")->required();
  dshow_cmd->callback([&o] { o.exit_code = cli::datasetShowCommand(o.show_dir); });
  dataset_cmd->add_subcommand("families", "List the generator families and suites")
      ->callback([&o] { o.exit_code = cli::datasetFamiliesCommand(); });
}

/// `run`, `merge` and `slurm`: experiments run here, in shards, or as Slurm jobs. `command_line`
/// is what the experiment's provenance records.
void addExperimentCommands(CLI::App& app, Commands& o, const std::string& command_line) {
  cli::RunOptions& run = o.run;
  CLI::App* run_cmd = app.add_subcommand("run", "Run an experiment config; results in SQLite, the report (OUTPUT/report/index.html) next to them");
  run_cmd->add_option("config", run.config, "experiment config (YAML)")->required();
  run_cmd->add_option("--threads", run.threads, "worker threads (default: the config's, else every core)");
  run_cmd->add_flag("--yes", run.yes, "confirm an experiment of more than 100000 runs");
  run_cmd->add_flag("--timing", run.timing, "one run at a time, so plan times do not share the machine");
  run_cmd->add_flag("--retry-failed", run.retry_failed, "run stored timeouts, memory limits, crashes and errors again");
  run_cmd->add_flag("--reuse-across-builds", run.reuse_across_builds,
                    "count stored runs of another planner version or code as done (know what you do)");
  run_cmd->add_flag("--no-report", run.no_report, "store the runs only; `coverbench report` writes the report later");
  run_cmd->add_option("--shard", run.shard,
                      "I/N: run only shard I (0 to N-1) of N, into OUTPUT/shards/shard-I-of-N.sqlite; `coverbench merge` joins them");
  run.command_line = command_line;
  run_cmd->callback([&o] { o.exit_code = cli::runCommand(o.run); });

  cli::MergeCommandOptions& merge = o.merge;
  CLI::App* merge_cmd = app.add_subcommand(
      "merge", "Merge shard databases (run --shard) into one, on run key; refuses missing or mismatched shards");
  merge_cmd->add_option("out", merge.out, "the merged database (e.g. OUTPUT/results.sqlite)")->required();
  merge_cmd->add_option("shards", merge.shards, "shard databases (OUTPUT/shards/shard-I-of-N.sqlite)")->required();
  merge.command_line = command_line;
  merge_cmd->callback([&o] { o.exit_code = cli::mergeCommand(o.merge); });

  cli::SlurmCommandOptions& slurm = o.slurm;
  CLI::App* slurm_cmd = app.add_subcommand(
      "slurm", "Write Slurm job scripts for an experiment: a job array of shards and a merge-and-report job after it");
  slurm_cmd->add_option("config", slurm.config, "experiment config (YAML)")->required();
  slurm_cmd->add_option("--shards", slurm.shards, "array tasks, one shard each")->capture_default_str();
  slurm_cmd->add_option("--cpus-per-task", slurm.cpus_per_task, "worker processes per task")->capture_default_str();
  slurm_cmd->add_option("--throttle", slurm.throttle, "at most this many tasks at once (0: no limit)")->capture_default_str();
  slurm_cmd->add_option("--partition", slurm.partition, "Slurm partition (default: the cluster's)");
  slurm_cmd->add_option("--time", slurm.time, "time limit per task (Slurm format)")->capture_default_str();
  slurm_cmd->add_option("--mem", slurm.mem, "memory per task, e.g. 4G (default: the config's limit per worker + 1 GiB)");
  slurm_cmd->add_option("--account", slurm.account, "Slurm account to charge");
  slurm_cmd->add_flag("--no-report", slurm.no_report, "the merge job only merges");
  slurm_cmd->add_flag("--submit", slurm.submit, "submit both jobs with sbatch (the merge after the array)");
  slurm_cmd->add_flag("--yes", slurm.yes, "confirm an experiment of more than 100000 runs");
  slurm_cmd->callback([&o] { o.exit_code = cli::slurmCommand(o.slurm); });
}

/// `report`, `runs`, `export-ompl` and `redraw`: what an experiment's database holds, read out.
void addResultCommands(CLI::App& app, Commands& o) {
  cli::ReportOptions& report = o.report;
  CLI::App* report_cmd = app.add_subcommand("report", "An experiment's report: --format html writes a folder (page, figures, tables); md, csv, latex print its tables");
  report_cmd->add_option("database", report.database, "results.sqlite of an experiment")->required();
  report_cmd->add_option("--format", report.format, "html, md, csv or latex")->capture_default_str();
  report_cmd->add_option("--out", report.out, "html: the report folder; otherwise the file to write (default: standard output)");
  report_cmd->add_option("--experiment", report.experiment, "experiment id in the database (default: the latest)");
  report_cmd->add_option("--baseline", report.baseline, "planner label to compare against (default: the config's)");
  report_cmd->add_option("--published", report.published,
                         "a table of published values (instance,method,metric,value) to set beside the planners "
                         "(default: the config's published:)");
  report_cmd->add_option("--published-clock", report.published_clock,
                         "the time model the published times were measured with: unknown, or '{speed: 0.3, ...}' "
                         "(the keys of motion:)");
  report_cmd->add_flag("--no-published", report.no_published,
                       "leave out the published table the config names (one that has moved, say)");
  report_cmd->callback([&o] { o.exit_code = cli::reportCommand(o.report); });

  cli::RunsOptions& runs = o.runs;
  CLI::App* runs_cmd = app.add_subcommand("runs", "Every run of an experiment, one row each (CSV or JSON), or --list");
  runs_cmd->add_option("database", runs.database, "results.sqlite of an experiment")->required();
  runs_cmd->add_option("--format", runs.format, "csv or json")->capture_default_str();
  runs_cmd->add_option("--experiment", runs.experiment, "experiment id in the database (default: the latest)");
  runs_cmd->add_flag("--list", runs.list, "one line per run: key, status, planner, tool, wall");
  runs_cmd->callback([&o] { o.exit_code = cli::runsCommand(o.runs); });

  cli::ExportOmplOptions& export_ompl = o.export_ompl;
  CLI::App* export_cmd = app.add_subcommand(
      "export-ompl", "Write an experiment's runs as OMPL benchmark logs (one per dataset) for ompl_benchmark_statistics and Planner Arena");
  export_cmd->add_option("database", export_ompl.database, "results.sqlite of an experiment")->required();
  export_cmd->add_option("--out", export_ompl.out, "folder for the .log files")->required();
  export_cmd->add_option("--experiment", export_ompl.experiment, "experiment id in the database (default: the latest)");
  export_cmd->callback([&o] { o.exit_code = cli::exportOmplCommand(o.export_ompl); });

  cli::RedrawOptions& redraw = o.redraw;
  CLI::App* redraw_cmd = app.add_subcommand("redraw", "Draw a stored run of an experiment (wall, path, coverage)");
  redraw_cmd->add_option("database", redraw.database, "results.sqlite of an experiment")->required();
  redraw_cmd->add_option("--run", redraw.run, "run key, or its first 6 or more hex digits")->required();
  redraw_cmd->add_option("--svg", redraw.svg, "picture to write")->required();
  redraw_cmd->add_option("--coat-svg", redraw.coat_svg,
                         "also the coat's thickness over R, with its scale in micrometres (SVG; the run's tool needs a flux profile)");
  redraw_cmd->add_option("--replan", redraw.replan,
                         "draw the run's repair number N after surprise obstacles (0-based; docs/replanning.md)");
  redraw_cmd->callback([&o] { o.exit_code = cli::redrawCommand(o.redraw); });
}

/// `serve`: experiments explored in a browser, and the workbench.
void addServeCommand(CLI::App& app, Commands& o) {
  cli::ServeOptions& serve = o.serve;
  CLI::App* serve_cmd = app.add_subcommand("serve", "Explore experiments in a browser: runs table, path playback (docs/explorer.md)");
  serve_cmd->add_option("database", serve.databases, "results.sqlite files to serve (nothing else is served)");
  serve_cmd->add_option("--walls", serve.wall_folders, "folders of wall files the workbench can open");
  serve_cmd->add_option("--walls-db", serve.walls_db, "walls database (SQLite) the workbench saves walls to; created if absent");
  serve_cmd->add_option("--plan-time-limit", serve.plan_time_limit_s, "the longest time limit a workbench plan may ask for, s")
      ->capture_default_str();
  serve_cmd->add_option("--host", serve.host, "address to listen on")->capture_default_str();
  serve_cmd->add_option("--port", serve.port, "port (0: any free one, printed)")->capture_default_str();
  serve_cmd->callback([&o] { o.exit_code = cli::serveCommand(o.serve); });
}

}  // namespace

int main(int argc, char** argv) {
  // The workbench's plan helper, which `coverbench serve` starts as this executable.
  if (argc >= 2 && std::string(argv[1]) == cli::kPlanHelperArgument) return cli::planHelperMain(argc, argv);
  CLI::App app{"CoverBench: benchmark 2-D coverage path planners"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "coverbench 0.1.0");

  Commands commands;
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  addPlanCommands(app, commands);
  addCheckCommands(app, commands);
  addDatasetCommands(app, commands);
  addExperimentCommands(app, commands, command_line);
  addResultCommands(app, commands);
  addServeCommand(app, commands);

  readValuesOneWay(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "coverbench: " << e.what() << "\n";
    return 2;
  } catch (const coverbench::InputError& e) {
    std::cerr << "coverbench: " << e.what() << "\n";
    return 2;
  } catch (const cli::AlreadyReported&) {
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "coverbench: internal error: " << e.what() << "\n";
    return 70;
  }
  return commands.exit_code;
}
