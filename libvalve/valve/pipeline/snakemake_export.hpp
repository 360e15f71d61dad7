#pragma once
// A pipeline as a Snakefile, for running its runs on a cluster with snakemake (the "Cluster
// route" in docs/pipelines.md). The Snakefile writes into the same folders as the native
// runner (DIR/shared, DIR/runs/<run_id>, DIR/<required out>, the tables in DIR), so that both
// routes give comparable outputs and each sees the other's work as done:
//   - one rule per step of each run (one per shared step), whose shell command runs the
//     resolved stage executable (absolute path) with the native runner's arguments, in the
//     run folder, with stdout+stderr in <step>.log, after removing the step's --out folder;
//     then `valve-pipeline stamp` checks the exit code against allow_exit and writes the
//     step's cache stamp (step_cache.hpp), the same file the native runner writes;
//   - the rule's output is that stamp (it stands for the step's --out folder: it is written
//     only after the step succeeded); its inputs are the stamps of the earlier steps whose
//     --out folder an argument names (as a path or inside KEY=PATH), the existing files the
//     arguments name outside DIR, and the final targets of the required pipelines. A file
//     reached only through another file (a scene's mesh) is not a rule input: name it in an
//     argument too when its producer must run first;
//   - params: stage_sha256, the sha256 of the stage executable, computed when snakemake reads
//     the Snakefile, so a rebuilt stage reruns its rules (snakemake's params trigger);
//   - threads and resources (mem_mb, runtime in minutes) from the step's "resources";
//   - a rule "tables" runs `valve-pipeline tables` (the gather, aggregate and plot files the
//     native runner writes, and provenance.json) after every step; "all" asks for the tables
//     (or every stamp when there are none).
#include <filesystem>
#include <string>
#include <vector>

#include "valve/pipeline/pipeline_spec.hpp"

namespace valve {

struct SnakemakeExport {
  std::filesystem::path snakefile;  ///< DIR/Snakefile
  size_t step_rules = 0;            ///< rules that run a stage (required pipelines included)
};

/// The Snakefile text for `spec` writing into out_dir. Stages are resolved in `stage_dirs`
/// (an InputError naming steps[i].stage when one is missing); `pipeline_exe` is the
/// valve-pipeline that the rules call for stamps and tables.
std::string snakefile_text(const PipelineSpec& spec, const std::filesystem::path& out_dir,
                           const std::vector<std::filesystem::path>& stage_dirs,
                           const std::filesystem::path& pipeline_exe, size_t* step_rules = nullptr);

/// Writes out_dir/Snakefile (nothing when the text cannot be made).
SnakemakeExport export_snakemake(const PipelineSpec& spec, const std::filesystem::path& out_dir,
                                 const std::vector<std::filesystem::path>& stage_dirs,
                                 const std::filesystem::path& pipeline_exe);

}  // namespace valve
