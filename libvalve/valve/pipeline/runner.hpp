#pragma once
// Runs a validated pipeline: every run in its own folder DIR/runs/<run_id>/, the steps of a
// run in order with the run folder as working directory and their stdout+stderr in
// <step>.log there, up to `jobs` runs at a time. A step whose exit code is not in its
// allow_exit (or that cannot start, or is killed by a signal) fails the run and skips the
// run's later steps; other runs go on. Then the gather tables (one file per csv, shared
// entries concatenated), the aggregate tables and the select tables with their lines (in file
// order) and the plots are written and DIR/pipeline.summary.json (status ok only when every
// run and every attempted plot succeeded; a plot skipped because gnuplot is absent is not a
// failure; metrics.csv lists the gather, then the aggregate, then the select tables, each
// with its "kind" and row count, a select's also with its line).
//
// Required pipelines ("requires", pipeline_spec.hpp) run first, each by run_pipeline into
// DIR/<out> with the same jobs and force and all of its runs; if one fails, no run of this
// pipeline starts and the summary says which (metrics.required lists each with its status).
//
// Shared steps (pipeline_spec.hpp) run first as the run "shared" in DIR/shared; if one fails,
// no run starts; if one ran (was not cached), every step of every run runs, as a later step
// of the same run would.
//
// Incremental runs (step_cache.hpp): the leading steps of a run that are up to date are not
// run again ("cached"); from the first step that is not, every step runs. A run with no
// cached step starts from an emptied folder (so a gather never picks up a stale summary
// from an earlier invocation); otherwise each step that runs first loses its stamp and its
// --out folder. Rerunning after a failure thus resumes at the failed step. `force` runs
// everything from emptied folders. Every invocation appends to DIR/pipeline.log (one line
// per step: time, run, step, cached / ok / failed, exit code, wall time, why it ran) and
// writes DIR/provenance.json: tool version, pipeline file hash, each stage executable and
// its hash, and per step the arguments, cache key and the hashes of the files it read.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "valve/pipeline/aggregate.hpp"
#include "valve/pipeline/selection.hpp"
#include "valve/pipeline/gather.hpp"
#include "valve/pipeline/pipeline_spec.hpp"

namespace valve {

struct RunnerOptions {
  std::filesystem::path out_dir;
  int jobs = 1;
  bool quiet = true;
  /// Searched for stages before the default directories and PATH (see process.hpp).
  std::vector<std::filesystem::path> stage_dirs;
  bool force = false;  ///< ignore the step cache: rerun every step from emptied run folders
  std::vector<std::string> only_runs;  ///< run ids to run (the tables hold only them); empty: all
};

struct StepOutcome {
  std::string name;
  std::string status = "skipped";  ///< "ok", "cached" (up to date, not run), "failed" or
                                   ///< "skipped" (an earlier step failed)
  std::string run_reason;          ///< why it ran (step_cache.hpp), empty when cached
  int exit_code = -1;              ///< -1 when it did not run
  double wall_time_s = 0, cpu_time_s = 0;
  std::string error;               ///< could not start, or killed by a signal
};

struct RunOutcome {
  std::string run_id;
  ojson variables;
  bool ok = false;
  std::string reason;
  std::vector<StepOutcome> steps;
  double wall_time_s = 0;
};

/// The executable of each step's stage; an InputError naming steps[i].stage when one is
/// not found, so that nothing runs.
std::vector<std::filesystem::path> resolve_stages(const PipelineSpec& spec,
                                                  const std::vector<std::filesystem::path>& dirs);

/// The same for every pipeline `spec` requires, directly or not (nothing is returned: a
/// missing stage is the InputError).
void resolve_required_stages(const PipelineSpec& spec, const std::vector<std::filesystem::path>& dirs);

/// Called after every finished step with the fraction of work done (finished runs plus the
/// finished steps of running ones, over all runs) and a one-line description.
using RunProgress = std::function<void(double fraction, const std::string& detail)>;

/// sha256 of each executable (one hash per distinct file).
std::vector<std::string> stage_hashes(const std::vector<std::filesystem::path>& executables);

/// Per step of a run: nothing if it is cached, else why it runs.
using StepPlan = std::vector<std::optional<std::string>>;

/// What an invocation would do: the leading up-to-date steps of each run are cached, the
/// rest run. `executable_sha256[i]` is the hash of step i's program.
/// `rerun_all`, when not empty, makes every step run for that reason (an upstream step ran).
std::vector<StepPlan> plan_runs(const std::vector<RunPlan>& runs, const std::vector<std::string>& executable_sha256,
                                bool force, const std::string& rerun_all = "");

struct ExecutionOptions {
  int jobs = 1;
  bool quiet = true;
  bool force = false;
  std::vector<std::string> executable_sha256;  ///< per step, for the cache keys
  std::filesystem::path log;                    ///< appended run log; empty: none
  std::string rerun_all;                        ///< see plan_runs
};

/// Runs every run, at most `jobs` at a time, each a sequence of child processes. Results
/// are in run order. `executables[i]` is the program of step i.
std::vector<RunOutcome> execute_runs(const std::vector<RunPlan>& runs,
                                     const std::vector<std::filesystem::path>& executables,
                                     const ExecutionOptions& options, const RunProgress& progress = {});

struct PipelineOutcome {
  std::optional<RunOutcome> shared;         ///< the shared steps (pipeline_spec.hpp), run first
  std::vector<RunOutcome> runs;
  std::vector<GatherResult> tables;         ///< one per gather csv, in order of first appearance
  std::vector<AggregateResult> aggregates;  ///< one per aggregate entry
  std::vector<SelectResult> selects;        ///< one per select entry
  std::vector<PlotResult> plots;
  std::string status;  ///< "ok" or "failed"
  std::string reason;
  int exit_code = 0;   ///< 0 ok, 3 some run or plot failed
};

/// Resolves the stages (throws InputError before writing anything), then runs, gathers,
/// aggregates, plots and writes DIR/pipeline.summary.json.
PipelineOutcome run_pipeline(const PipelineSpec& spec, const RunnerOptions& options);

/// The gather tables, aggregates and plots of `runs` in out_dir, as run_pipeline writes them.
void write_tables(const PipelineSpec& spec, const std::vector<RunPlan>& runs, const std::filesystem::path& out_dir,
                  PipelineOutcome& result);

/// Writes DIR/provenance.json for the shared run (if any) and the runs with their outcomes.
/// `hashes` has one entry per step of the spec.
void write_provenance(const PipelineSpec& spec, const std::optional<RunPlan>& shared,
                      const std::optional<RunOutcome>& shared_outcome, const std::vector<RunPlan>& runs,
                      const std::vector<RunOutcome>& outcomes, const std::vector<std::filesystem::path>& executables,
                      const std::vector<std::string>& hashes, const std::filesystem::path& out);

}  // namespace valve
