// valve-pipeline run P.json --out DIR [--jobs N] [--run ID ...] [--force] [--dry-run] [--stage-dir D ...] [--quiet]
// valve-pipeline list P.json [--out DIR] [--stage-dir D ...]
// valve-pipeline export --snakemake P.json --out DIR [--stage-dir D ...]
// `run` runs a pipeline JSON (format in libvalve/valve/pipeline/pipeline_spec.hpp): every run
// in DIR/runs/<run_id>/ with one <step>.log per step, up to N runs at a time, then writes
// the gather, aggregate and select CSVs (a select's one-line decision also in <csv stem>.txt
// and printed) and the gnuplot plots into DIR, and DIR/pipeline.summary.json.
// Steps already done with the same command, stage build and input files are skipped
// (libvalve/valve/pipeline/step_cache.hpp), so running again resumes after a failure;
// --run ID (repeatable) runs only those runs (ids as `list` prints them), and the tables
// and plots then hold only them. --force reruns everything. --dry-run prints which steps would run and why, and writes
// nothing. Each run appends to DIR/pipeline.log and writes DIR/provenance.json.
// Pipelines named in "requires" run first, whole, into DIR/<out> (--run selects runs of
// the named pipeline only); `list` names them, --dry-run shows their steps too (a step
// reading a required pipeline's files shows "cached" when those files are up to date now,
// although the required steps listed to run before it may change them).
// `list` validates the pipeline and prints each run's id and commands without running them.
// Shared steps (the leading steps that use no sweep variable) run once, into DIR/shared.
// valve-pipeline export --snakemake P.json --out DIR [--stage-dir D ...]
// writes DIR/Snakefile: the same steps as snakemake rules writing into DIR as `run` would
// (libvalve/valve/pipeline/snakemake_export.hpp); then `snakemake -s DIR/Snakefile -j N`, or
// on a cluster `snakemake -s DIR/Snakefile --slurm --jobs N --default-resources ...`.
// The Snakefile's rules call two more commands: `stamp P.json --out DIR --run ID --step NAME
// --exit-code C --stage-sha256 H` (fails with exit 3 unless C is allowed, else writes the
// step's cache stamp) and `tables P.json --out DIR` (the gather, aggregate, select and plot files,
// and provenance.json, from the runs' folders as they are).
// Exit 0 ok, 2 bad pipeline (one line naming file and key, nothing written), 3 some run or
// plot failed (the summary says which; the tables still hold what the other runs made).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/parallel.hpp"
#include "valve/pipeline/pipeline_commands.hpp"
#include "valve/pipeline/pipeline_spec.hpp"
#include "valve/pipeline/runner.hpp"
#include "valve/pipeline/snakemake_export.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  keep_written_files_on_failure();
  return run_stage("valve-pipeline", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"out", "jobs", "stage-dir", "run", "step", "exit-code", "stage-sha256"},
                   {"quiet", "force", "dry-run", "snakemake"});
    const std::string command = pipeline_command(cl);
    RunnerOptions options;
    if (command != "list") options.out_dir = cl.require("out");
    options.jobs = pipeline_jobs(cl);
    // Runs side by side share the cores: each stage's split loops (core/parallel.hpp) get its
    // share, unless the user chose.
    if (!std::getenv("VALVE_THREADS"))
      setenv("VALVE_THREADS", std::to_string(std::max(1, worker_threads() / std::max(options.jobs, 1))).c_str(), 1);
    const PipelineSpec spec = load_pipeline(cl.positional()[1]);
    if (command == "list") return list_pipeline(spec, cl, std::cout);
    if (command == "stamp") return stamp_pipeline_step(spec, cl);

    options.quiet = cl.has("quiet");
    options.force = cl.has("force");
    options.only_runs = cl.get_all("run");
    options.stage_dirs = pipeline_stage_dirs(cl);
    if (cl.has("dry-run")) return dry_run_pipeline(spec, options, std::cout);
    if (command == "tables") return write_pipeline_tables(spec, options, std::cout);
    if (command == "export") {
      const SnakemakeExport done =
          export_snakemake(spec, options.out_dir, options.stage_dirs, fs::canonical("/proc/self/exe"));
      if (!options.quiet)
        std::printf("valve-pipeline: wrote %s (%zu step rules); run it with snakemake -s %s -j N\n",
                    done.snakefile.string().c_str(), done.step_rules, done.snakefile.string().c_str());
      return 0;
    }
    const PipelineOutcome result = run_pipeline(spec, options);
    if (!options.quiet) std::printf("%s\n", pipeline_outcome_line(result).c_str());
    if (result.exit_code != 0) std::fprintf(stderr, "valve-pipeline: failed: %s\n", result.reason.c_str());
    return result.exit_code;
  });
}
