#pragma once
// Which steps of a pipeline run can be skipped: a step that already succeeded with the same
// command and the same stage executable, and whose input files are unchanged, is not run
// again. Rerunning a pipeline therefore resumes after a failure (the steps that succeeded
// are kept) and redoes only what a changed parameter or input affects.
//
// The stamp of a step, <run_dir>/.valve-cache/<step>.json, is written after it succeeded:
//   key     sha256 of the stage executable's hash, the stage name and the arguments after
//           substitution (a changed parameter or tool build changes the key);
//   inputs  path and sha256 of every file the step read: arguments naming existing files
//           when it started, plus the inputs its own summary lists (<out>/<stage>.summary.json,
//           <out> the --out argument), which covers files named inside a scene or pipeline
//           file (the mesh of a scene, the chordae file).
// A step is up to date when its stamp exists, the key matches and every input still has
// its hash. Once one step of a run runs, every later step of that run runs too: it may read
// what the rerun step rewrote.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "valve/pipeline/pipeline_spec.hpp"

namespace valve {

struct StepInput {
  std::string path;  ///< absolute, or relative to the run folder
  std::string sha256;
};

/// The cache key of a step (see above).
std::string step_cache_key(const std::string& executable_sha256, const ResolvedStep& step);

/// <run_dir>/.valve-cache/<step>.json
std::filesystem::path step_stamp_path(const std::filesystem::path& run_dir, const std::string& step);

/// The folder given to the step's --out argument (absolute, resolved against run_dir), if any.
std::optional<std::filesystem::path> step_out_dir(const ResolvedStep& step, const std::filesystem::path& run_dir);

/// Why the step must run ("never ran", "command or stage changed", "input <path> changed"),
/// or nothing when its stamp shows it up to date.
std::optional<std::string> step_rerun_reason(const std::filesystem::path& run_dir, const ResolvedStep& step,
                                             const std::string& key);

/// The files the step read (see above); call after it succeeded.
std::vector<StepInput> step_inputs(const std::filesystem::path& run_dir, const ResolvedStep& step);

/// Writes the stamp of a step that succeeded; returns the inputs it recorded.
std::vector<StepInput> write_step_stamp(const std::filesystem::path& run_dir, const ResolvedStep& step,
                                        const std::string& key);

/// The inputs recorded in a step's stamp (empty without one).
std::vector<StepInput> read_step_stamp_inputs(const std::filesystem::path& run_dir, const std::string& step);

/// Removes the step's stamp and its --out folder when that lies inside the run folder, so
/// that a failing rerun leaves neither a stamp nor stale outputs for a gather to read.
void clear_step_outputs(const std::filesystem::path& run_dir, const ResolvedStep& step);

}  // namespace valve
