#pragma once
// A pipeline JSON: parsing, validation, sweep expansion and ${...} substitution.
//
// valve-pipeline runs a pipeline file: a sequence of stage invocations ("steps"), repeated
// for every combination of sweep variables ("runs"), then gathered into CSV tables and
// plotted. Everything below is checked before anything runs; a bad file is one InputError
// line "P.json: <key path>: expected ..., found ..." (exit 2) and nothing is written.
//
// {
//   "name": "seed_biaxial",              // optional, default: the file name without .json
//   "description": "...",                // optional free text
//   "requires": [                        // optional: pipelines run (whole, cached as usual)
//     {"pipeline": "image_to_mesh.json", //   before this one's runs; the file relative to
//      "out": "image_to_mesh"}           //   this one's folder, its DIR the folder "out"
//   ],                                   //   inside this DIR (see "Required pipelines")
//   "variables": {                       // optional sweep variables, in this order
//     "angle": [0, 45],                  //   a non-empty list of numbers, strings, booleans or objects
//     "ratio": [{"label": "20:60", "sx": "20 kPa"}, {"label": "60:60", "sx": "60 kPa"}],
//     "mesh": {"range": [1, 10]}         //   a..b inclusive, step 1 (or -1 when b < a);
//   },                                   //   {"range": [a, b, step]} with any nonzero step
//   "shared_steps": true,                // optional, default true; false: every step runs in
//                                        // every run (repetitions of one computation, as in a
//                                        // benchmark; see "Shared steps")
//   "sweep": "grid",                     // "grid" (default): Cartesian product, the first
//                                        // variable varies slowest; "zip": the lists (of equal
//                                        // length) are taken together, run k uses value k of each
//   "steps": [                           // required, non-empty; run in order inside a run
//     {"name": "mesh",                   // optional, default the stage name; unique; names the log
//      "stage": "valve-generate",        // required: "valve-<name>", see process.hpp for lookup
//      "args": ["square_patch", "--out", "${run_dir}/mesh"],   // required: strings (or numbers)
//      "allow_exit": [0, 3],             // optional exit codes that do not fail the run, default [0]
//      "resources": {"threads": 1, "mem_mb": 2048, "runtime": 60}}   // optional, these defaults:
//                                        // what a cluster scheduler reserves per invocation
//                                        // (snakemake threads, mem_mb, runtime in minutes;
//                                        // see "Cluster route" in docs/pipelines.md); the
//                                        // native runner runs one step per job slot
//   ],
//   "gather": [                          // optional: CSV tables in DIR
//     {"csv": "biaxial.csv",             // relative path inside DIR; entries naming the same
//                                        // csv are concatenated into it (see below)
//      "summary": "sim/simulate.summary.json",   // JSON file relative to each run folder
//      "rows": "metrics.biaxial.components",     // optional: an array in it, one row per element
//      "columns": {"angle": "${angle}",          // ordered; a string with placeholders,
//                  "error": "row:error_pct",     // "row:<path>" inside the current element,
//                  "status": "summary:status",   // "summary:<path>" inside the summary,
//                  "time": "file:sim/simulate.summary.json:metrics.solver.wall_seconds",
//                                                // "file:<json file in the run folder>:<path>"
//                  "worst": {"min": ["summary:a.height", "summary:b.height"]}}}
//                                                // {"min" or "max": [two or more summary:,
//                                                // row: or file: sources]}: the smallest or
//                                                // largest; empty when any is not a number
//   ],
//   "aggregate": [                       // optional: grouped statistics of the tables, computed
//     {"csv": "biaxial_summary.csv",     // after the gather step, in this order; unique, not a
//                                        // gather csv
//      "from": "biaxial.csv",            // a gather csv or an earlier aggregate csv
//      "where": {"component": ["E11", "E22"], "fiber_angle_deg": [45]},  // optional (see below)
//      "group_by": ["model", "load_kind"],                // required, may be []
//      "stats": {"strain_error_pct": ["mean", "sd", "count"]}}   // required, non-empty
//   ],
//   "select": [                          // optional: per group, the row that meets every
//     {"csv": "choice.csv",              // threshold and comes first by "minimize" (after the
//      "from": "graft_sizing.csv",       // aggregates); unique csv; from: a gather or aggregate csv
//      "where": {"status": ["ok"]},      // optional, as in an aggregate
//      "group_by": ["stiffness"],        // required, may be []
//      "at_least": {"native_min_height_mm": 1},   // column: number; at_least, at_most or
//      "at_most": {"orifice_area_mm2": 0.05},      // both, together non-empty
//      "minimize": ["graft_rest_area_mm2"],       // required, non-empty list of columns
//      "agree_on": ["width_pct", "height_pct"]}   // optional: compared across the groups
//   ],
//   "plots": [                           // optional: rendered with gnuplot when it is on PATH
//     {"png": "error.png", "csv": "biaxial.csv",   // csv: a gather, aggregate or select table
//      "gnuplot": "plot '${csv}' using 2:5 with points"}   // a string or a list of lines
//                                       // columns named in it (column('x'), strcol('x'))
//                                       // must be the table's; with "set datafile
//                                       // columnheaders" they survive added columns
//   ]
// }
// Comments (// and /* */) are allowed in pipeline files.
//
// Shared gather CSVs: several gather entries may name the same csv (say one per summary
// file); the file then holds all rows of the first such entry (every run), then all rows of
// the next, and so on. Their columns must have the same names in the same order, so that
// the file has one header.
//
// Aggregates: each aggregate reads the table "from" (as written, cell texts), keeps the rows
// that pass every "where" filter (a column name: a non-empty list of strings, numbers or
// booleans; a row passes when its cell text equals one of them, numbers compared as their
// shortest text, so 45 and 45.0 both match the cell "45"), and groups them by the
// "group_by" columns, one output row per distinct combination in order of first appearance;
// "group_by": [] makes one row for the whole table (also when no row passes). The output
// columns are the group_by columns, then "<column>_<stat>" for every column of "stats" and
// every stat of its list, in file order. Stats: mean, sd (sample standard deviation, n - 1),
// min, max, median (the mean of the two middle values for even n), count and true_count
// (the cells that read true, as booleans are written). The others use only
// the numeric cells of the group (decimal numbers; empty and other text cells are skipped):
// count is the number of numeric cells, the others are empty when there are none (sd when
// there are fewer than 2), never nan. Values are written like gather cells: integral values
// exactly, others with %.10g. Every column named in where, group_by and stats must be a
// column of the "from" table (known before running: the gather columns, or the output
// columns of the earlier aggregate), and the output column names must be distinct.
//
// Selections: each select entry reads its "from" table, keeps the rows that pass "where"
// whose "at_least" cells are all numbers at or above their bounds and whose "at_most" cells
// are all numbers at or below theirs, and in each group
// (one per distinct group_by combination among all rows that pass "where", in order of
// first appearance) picks the row with the smallest "minimize" cells (numbers compared in
// list order; a row with a non-numeric one is not a candidate; ties go to the earlier row).
// The output has one row per group: the group_by columns, "found" (true/false), then the
// chosen row's other columns (empty when none qualifies). One line of text, also in
// <csv stem>.txt and printed by valve-pipeline, names each group's choice by its agree_on
// columns (else its minimize columns) and says whether the agree_on values are the same in
// every group. Why: a study's decision (the smallest graft that seals) stays a rule in the
// file, checked before any run, rather than a reading of a plot.
//
// Required pipelines: each entry of "requires" is parsed and checked with this file (a
// pipeline that requires itself, directly or through others, is an InputError), and
// valve-pipeline runs it into DIR/<out> before any run of this one, with the same --jobs and
// --force (--run selects runs of this pipeline only). Its step cache makes a rerun cheap. If
// it fails, none of this pipeline's runs start (exit 3). Steps read its outputs by path,
// "${out_dir}/<out>/runs/<its run id>/...". Why: two pipelines that need the same upstream
// chain share one copy of it, and running the upstream one alone gives the same files.
//
// Placeholders: ${name} is a variable's value; ${name.field} (a dot path, array indices as
// numbers) a field of an object-valued one. A whole object substitutes as its "label" field
// when it has one, else as compact JSON. Numbers substitute in shortest round-trip form
// (45, 0.1, 1e-05), booleans as true/false. Built-ins: ${run_dir} (absolute run folder
// DIR/runs/<run_id>), ${run_id}, ${out_dir} (absolute DIR), ${pipeline_dir} (absolute folder
// of P.json); in plots only ${csv} and ${png} (absolute paths in DIR), ${out_dir} and
// ${pipeline_dir}. "$${" writes a literal "${". An unknown name, a field missing from any
// value, or an unterminated placeholder is an InputError naming the key path.
//
// Outputs in DIR: runs/<run_id>/ (one folder per run, emptied when the run starts; the steps
// run there as working directory and log stdout+stderr to <step>.log), shared/ (the shared
// steps, see below, run there the same way), the gather CSVs, the
// aggregate CSVs, the plots with their gnuplot scripts (<png>.gp) and logs (<png>.log),
// pipeline.summary.json.
//
// Shared steps: in a pipeline with variables, the leading steps that use no sweep variable
// (nor ${run_id}) and write into "--out ${run_dir}/<folder>" run once, into DIR/shared/<folder>,
// before the runs (their stamps in DIR/shared/.valve-cache). Later steps and gathers that name
// "${run_dir}/<folder>" (or gather "<folder>/...") read DIR/shared/<folder> instead. The leading
// run of such steps stops at the first step that uses a variable, has no such --out, or whose
// folder a later step names as a relative path (that would be looked for in the run folder).
// Why: a study of N runs repeats none of its common preparation N times. "shared_steps":
// false turns this off, for runs that are repetitions on purpose.
//
// Runs: run_id is a slug of the variable values, "angle-45_ratio-20-60_mesh-3" (characters
// other than letters, digits, '.', '+' and '-' become '-'; an object value uses its "label");
// a collision gets a "-2", "-3", ... suffix; no variables gives the single run "single".
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "valve/core/error.hpp"  // format_number

namespace valve {

/// Pipeline files keep their key order (variables, columns): ordered JSON throughout.
using ojson = nlohmann::ordered_json;

enum class SweepKind { grid, zip };

struct SweepVariable {
  std::string name;
  std::vector<ojson> values;  ///< non-empty; numbers, strings, booleans or objects
};

/// What a cluster scheduler reserves for one invocation of a step.
struct StepResources {
  int threads = 1;
  int mem_mb = 2048;
  int runtime_min = 60;
};

struct StepSpec {
  std::string name;               ///< unique inside the pipeline; the log is <name>.log
  std::string stage;              ///< "valve-<name>"
  std::vector<std::string> args;  ///< with placeholders
  std::vector<int> allow_exit{0};
  StepResources resources;
  std::string key;                ///< "steps[i]", for messages
};

/// One CSV column: a literal (with placeholders), a path into the summary or the row, or the
/// smallest or largest number among several such paths.
struct ColumnSpec {
  enum class Source { literal, summary, row, file, min, max };
  std::string header;
  Source source = Source::literal;
  std::string text;  ///< the literal, or the dot path after "summary:" / "row:" / "file:<file>:"
  std::string file;  ///< Source::file: the JSON file, relative to the run folder
  std::vector<ColumnSpec> parts;  ///< Source::min / max: the summary, row or file columns compared
};

struct GatherSpec {
  std::string csv;      ///< relative to DIR
  std::string summary;  ///< relative to the run folder, with placeholders
  std::string rows;     ///< dot path of an array in the summary; empty: one row per run
  std::vector<ColumnSpec> columns;
  std::string key;      ///< "gather[i]"
};

/// A "where" filter: keep rows whose cell in `column` is one of `values` (cell texts).
struct AggregateFilter {
  std::string column;
  std::vector<std::string> values;
};

/// The statistics of one value column, in file order.
struct AggregateStats {
  std::string column;
  std::vector<std::string> stats;  ///< each one of aggregate_stat_names()
};

struct AggregateSpec {
  std::string csv;                       ///< output, relative to DIR
  std::string from;                      ///< a gather CSV or an earlier aggregate CSV
  std::vector<AggregateFilter> where;
  std::vector<std::string> group_by;     ///< may be empty: one row for the whole table
  std::vector<AggregateStats> stats;     ///< non-empty
  std::vector<std::string> header;       ///< the output columns, known at parse time
  std::string key;                       ///< "aggregate[i]"
};

/// A "select" threshold: keep rows whose cell in `column` is a number >= `bound` (or <= `bound`
/// when `at_most`).
struct SelectThreshold {
  std::string column;
  double bound = 0;
  bool at_most = false;
};

struct SelectSpec {
  std::string csv;                        ///< output, relative to DIR; the line goes to <stem>.txt
  std::string from;                       ///< a gather or an aggregate CSV
  std::vector<AggregateFilter> where;
  std::vector<std::string> group_by;      ///< may be empty: one choice for the whole table
  std::vector<SelectThreshold> thresholds;  ///< the at_least bounds, then the at_most ones; non-empty
  std::vector<std::string> minimize;      ///< non-empty; compared in order, ties by table order
  std::vector<std::string> agree_on;      ///< columns the line compares across groups
  std::vector<std::string> header;        ///< group_by, "found", then the other columns of from
  std::string key;                        ///< "select[i]"
};

struct PlotSpec {
  std::string png;      ///< relative to DIR
  std::string csv;      ///< one of the gather or aggregate CSVs
  std::string gnuplot;  ///< script text with placeholders
  std::string key;      ///< "plots[i]"
};

struct PipelineSpec;

/// An entry of "requires".
struct RequiredPipeline {
  std::string out;                           ///< folder relative to DIR
  std::shared_ptr<const PipelineSpec> spec;  ///< parsed and checked
  std::string key;                           ///< "requires[i]"
};

struct PipelineSpec {
  std::string file;                    ///< as given, for messages
  std::filesystem::path pipeline_dir;  ///< absolute folder of the file
  std::string name, description;
  std::vector<RequiredPipeline> required;  ///< run before this pipeline's runs, in order
  std::vector<SweepVariable> variables;
  SweepKind sweep = SweepKind::grid;
  std::vector<StepSpec> steps;
  size_t shared_steps = 0;               ///< leading steps run once in DIR/shared
  std::vector<std::string> shared_outs;  ///< their --out folders, relative to a run folder
  std::vector<GatherSpec> gather;       ///< entries may share a csv (same columns)
  std::vector<AggregateSpec> aggregates;
  std::vector<SelectSpec> selects;
  std::vector<PlotSpec> plots;
  ojson source;                        ///< the document as read
};

/// One step of one run with every placeholder substituted.
struct ResolvedStep {
  std::string name, stage;
  std::vector<std::string> args;
  std::vector<int> allow_exit;
};

struct RunPlan {
  std::string run_id;
  ojson variables = ojson::object();  ///< name -> value, in declaration order
  std::filesystem::path run_dir;      ///< absolute
  std::vector<ResolvedStep> steps;
};

/// Placeholder name -> value.
using Bindings = std::map<std::string, ojson>;

/// Reads a pipeline file (comments allowed); malformed JSON is an InputError naming the line.
ojson load_pipeline_json(const std::filesystem::path& path);

/// Validates `doc` completely (keys, types, sweep shapes, every placeholder) and returns the
/// spec. `file` names the source in messages; `pipeline_dir` is made absolute.
PipelineSpec parse_pipeline(const ojson& doc, const std::string& file,
                            const std::filesystem::path& pipeline_dir);
/// The same, with the chain of files that led here ("requires"; canonical paths), to reject cycles.
PipelineSpec parse_pipeline(const ojson& doc, const std::string& file, const std::filesystem::path& pipeline_dir,
                            const std::vector<std::filesystem::path>& required_by);

/// load_pipeline_json + parse_pipeline.
PipelineSpec load_pipeline(const std::filesystem::path& path);

/// The distinct gather CSVs in order of first appearance (entries may share one).
std::vector<std::string> gather_csvs(const PipelineSpec& spec);

/// The stat names an aggregate accepts: mean, sd, min, max, median, count, true_count.
const std::vector<std::string>& aggregate_stat_names();

/// The variable assignments of every run, in run order (grid: first variable slowest).
/// No variables gives one empty assignment.
std::vector<ojson> expand_sweep(const std::vector<SweepVariable>& variables, SweepKind sweep);

/// Readable unique run ids for the assignments, in the same order (see the header comment).
std::vector<std::string> make_run_ids(const std::vector<ojson>& assignments);

/// The runs of the pipeline with their folders under out_dir/runs and substituted steps
/// (the steps after the shared ones, reading the shared outputs in out_dir/shared).
std::vector<RunPlan> expand_runs(const PipelineSpec& spec, const std::filesystem::path& out_dir);

/// The shared steps as one run "shared" in out_dir/shared, or nothing without shared steps.
std::optional<RunPlan> shared_run(const PipelineSpec& spec, const std::filesystem::path& out_dir);

/// A file named relative to a run folder: in out_dir/shared when it lies in a shared step's
/// --out folder, else in the run folder.
std::filesystem::path run_file(const PipelineSpec& spec, const RunPlan& run, const std::filesystem::path& out_dir,
                               const std::string& relative);

/// The runs whose ids are listed, in pipeline order; all of them when `ids` is empty. An id
/// that is not a run of the pipeline is an InputError naming `option`.
std::vector<RunPlan> select_runs(std::vector<RunPlan> runs, const std::vector<std::string>& ids,
                                 const std::string& option);

/// The placeholders of one run: its variables plus run_dir, run_id, out_dir, pipeline_dir.
Bindings run_bindings(const PipelineSpec& spec, const RunPlan& run, const std::filesystem::path& out_dir);

/// Replaces every ${...} in `text`. Errors name `file` and `key`:
/// "P.json: steps[1].args[3]: expected a known variable, found ${rato}".
std::string substitute(const std::string& text, const Bindings& bindings, const std::string& file,
                       const std::string& key);

/// A value as substituted text (numbers shortest round-trip, objects by label or JSON).
std::string value_text(const ojson& value);

/// `dir` absolute and normalized, without a trailing separator: what ${out_dir} gives.
std::filesystem::path normalized_dir(const std::filesystem::path& dir);


/// The value at a dot path ("metrics.leaflets.0.free_edge_mm"; empty path: `root` itself),
/// or nullptr when any part is missing.
const ojson* find_path(const ojson& root, const std::string& dot_path);

}  // namespace valve
