#pragma once
// The commands of valve-pipeline (its usage text says what each does): reading the command
// line's shape, `list`, `run --dry-run`, `stamp`, `tables` and the one-line report of `run`.
// What they print goes to the stream given (the stage passes std::cout), so that a test can
// read it; a failing check throws InputError (exit 2) before anything is printed or written.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "valve/core/cli.hpp"
#include "valve/pipeline/pipeline_spec.hpp"
#include "valve/pipeline/runner.hpp"

namespace valve {

/// The command (run, list, export, stamp or tables) of a command line holding it and the
/// pipeline file as its two positional arguments; export also needs --snakemake and refuses
/// --run, --force and --dry-run, since snakemake selects and forces its jobs itself.
std::string pipeline_command(const CommandLine& cl);

/// --jobs: an integer in [1, 1024]; 1 when absent.
int pipeline_jobs(const CommandLine& cl);

/// --stage-dir (repeatable), each an existing folder, made absolute.
std::vector<std::filesystem::path> pipeline_stage_dirs(const CommandLine& cl);

/// `list`: checks every stage can be found (also those of the required pipelines), then
/// prints each run's id and resolved commands, the gather tables and plots. Without --out
/// the paths are shown under "$OUT". Returns the exit code (0).
int list_pipeline(const PipelineSpec& spec, const CommandLine& cl, std::ostream& out);

/// `run --dry-run`: per step of the required pipelines, the shared steps and the selected
/// runs, whether it would run (and why) or is cached, then the counts. Writes nothing.
int dry_run_pipeline(const PipelineSpec& spec, const RunnerOptions& options, std::ostream& out);

/// `stamp`: the end of a step another engine ran (the exported Snakefile's rules). Reads
/// --out, --run, --step, --stage-sha256 and --exit-code; an exit code the step does not
/// allow is reported on stderr and returns 3, else the step's cache stamp is written and 0
/// returned.
int stamp_pipeline_step(const PipelineSpec& spec, const CommandLine& cl);

/// `tables`: the gather, aggregate and plot files and provenance.json `run` writes after its
/// steps, from the run folders as they are. A step counts as done ("ok") when it has its
/// stamp. Returns 3 when a plot failed, else 0.
int write_pipeline_tables(const PipelineSpec& spec, const RunnerOptions& options, std::ostream& out);

/// `run`'s closing line: "valve-pipeline: <ok>/<runs> runs ok, <n> step(s) cached" and each
/// table and plot written; then one line per select entry, its choices in words.
std::string pipeline_outcome_line(const PipelineOutcome& outcome);

}  // namespace valve
