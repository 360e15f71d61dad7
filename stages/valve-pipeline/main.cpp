// valve-pipeline run P.json --out DIR [--jobs N] [--run ID ...] [--force] [--dry-run] [--stage-dir D ...] [--quiet]
// valve-pipeline list P.json [--out DIR] [--stage-dir D ...]
// `run` runs a pipeline JSON (format in libvalve/valve/pipeline/pipeline_spec.hpp): every run
// in DIR/runs/<run_id>/ with one <step>.log per step, up to N runs at a time, then writes
// the gather CSVs and gnuplot plots into DIR and DIR/pipeline.summary.json.
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
// Exit 0 ok, 2 bad pipeline (one line naming file and key, nothing written), 3 some run or
// plot failed (the summary says which; the tables still hold what the other runs made).
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/pipeline_spec.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/pipeline/runner.hpp"
#include "stage_usage.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {

int parse_jobs(const CommandLine& cl) {
  const auto v = cl.get("jobs");
  if (!v) return 1;
  char* end = nullptr;
  const long n = std::strtol(v->c_str(), &end, 10);
  if (end == v->c_str() || *end != '\0' || n < 1 || n > 1024)
    throw InputError("valve-pipeline: --jobs: expected an integer in [1, 1024], found \"" + *v + "\"");
  return static_cast<int>(n);
}

std::vector<fs::path> stage_dirs(const CommandLine& cl) {
  std::vector<fs::path> dirs;
  for (const auto& d : cl.get_all("stage-dir")) dirs.push_back(fs::absolute(d));
  return default_stage_dirs(dirs);
}

// Without --out the dry run shows paths under a stand-in folder, printed as $OUT.
int list_runs(const PipelineSpec& spec, const CommandLine& cl) {
  const auto exes = resolve_stages(spec, stage_dirs(cl));
  resolve_required_stages(spec, stage_dirs(cl));
  const std::string marker = "/__valve_pipeline_out__";
  const fs::path out = cl.get("out") ? fs::path(*cl.get("out")) : fs::path(marker);
  const auto runs = expand_runs(spec, out);
  auto show = [&](std::string text) {
    if (cl.get("out")) return text;
    for (size_t at; (at = text.find(marker)) != std::string::npos;) text.replace(at, marker.size(), "$OUT");
    return text;
  };
  std::string vars;
  for (const auto& v : spec.variables)
    vars += (vars.empty() ? "" : spec.sweep == SweepKind::grid ? " x " : ", ") + v.name + " (" +
            std::to_string(v.values.size()) + ")";
  std::printf("pipeline %s (%s): %zu run(s)%s, %zu step(s) each\n", spec.name.c_str(), spec.file.c_str(), runs.size(),
              vars.empty() ? "" : ((spec.sweep == SweepKind::grid ? ", grid over " : ", zip of ") + vars).c_str(),
              spec.steps.size());
  if (!cl.get("out")) std::printf("# OUT stands for the --out folder\n");
  for (const auto& r : spec.required)
    std::printf("requires %s (%zu run(s)), run first into %s\n", r.spec->file.c_str(),
                expand_runs(*r.spec, out / r.out).size(), show((normalized_dir(out) / r.out).string()).c_str());
  for (const auto& run : runs) {
    std::printf("run %s\n", run.run_id.c_str());
    for (size_t s = 0; s < run.steps.size(); ++s) {
      std::vector<std::string> words{exes[s].string()};
      words.insert(words.end(), run.steps[s].args.begin(), run.steps[s].args.end());
      std::printf("  [%s] %s\n", run.steps[s].name.c_str(), show(shell_quote(words)).c_str());
    }
  }
  for (const auto& g : spec.gather)
    std::printf("gather %s from runs/*/%s\n", show((normalized_dir(out) / g.csv).string()).c_str(), g.summary.c_str());
  for (const auto& p : spec.plots)
    std::printf("plot %s from %s\n", show((normalized_dir(out) / p.png).string()).c_str(), p.csv.c_str());
  return 0;
}

// What `run` would do, step by step, without writing anything: the required pipelines
// first, as `run` runs them. Adds to the step counts.
void dry_run_steps(const PipelineSpec& spec, const RunnerOptions& options, size_t& to_run, size_t& cached) {
  for (const auto& r : spec.required) {
    RunnerOptions upstream = options;
    upstream.out_dir = normalized_dir(options.out_dir) / r.out;
    upstream.only_runs.clear();
    std::printf("required pipeline %s into %s\n", r.spec->file.c_str(), upstream.out_dir.string().c_str());
    dry_run_steps(*r.spec, upstream, to_run, cached);
  }
  const auto exes = resolve_stages(spec, default_stage_dirs(options.stage_dirs));
  const auto runs = select_runs(expand_runs(spec, options.out_dir), options.only_runs, "--run");
  const auto plans = plan_runs(runs, stage_hashes(exes), options.force);
  for (size_t r = 0; r < runs.size(); ++r) {
    std::printf("run %s\n", runs[r].run_id.c_str());
    for (size_t s = 0; s < runs[r].steps.size(); ++s) {
      const auto& why = plans[r][s];
      (why ? to_run : cached) += 1;
      std::printf("  [%s] %s\n", runs[r].steps[s].name.c_str(), why ? ("run: " + *why).c_str() : "cached");
    }
  }
}

int dry_run(const PipelineSpec& spec, const RunnerOptions& options) {
  select_runs(expand_runs(spec, options.out_dir), options.only_runs, "--run");  // an unknown --run fails first
  size_t to_run = 0, cached = 0;
  dry_run_steps(spec, options, to_run, cached);
  std::printf("dry run: %zu step(s) would run, %zu cached\n", to_run, cached);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  keep_written_files_on_failure();
  return run_stage("valve-pipeline", kStageUsage, [&] {
    CommandLine cl(argc, argv, {"out", "jobs", "stage-dir", "run"}, {"quiet", "force", "dry-run"});
    const auto& pos = cl.positional();
    if (pos.size() != 2 || (pos[0] != "run" && pos[0] != "list"))
      throw InputError("valve-pipeline: command: expected \"run P.json\" or \"list P.json\", found " +
                       std::to_string(pos.size()) + " positional argument(s)" +
                       (pos.empty() ? "" : " starting with \"" + pos[0] + "\""));
    RunnerOptions options;
    if (pos[0] == "run") options.out_dir = cl.require("out");
    options.jobs = parse_jobs(cl);
    const PipelineSpec spec = load_pipeline(pos[1]);
    if (pos[0] == "list") return list_runs(spec, cl);

    options.quiet = cl.has("quiet");
    options.force = cl.has("force");
    options.only_runs = cl.get_all("run");
    for (const auto& d : cl.get_all("stage-dir")) {
      std::error_code ec;
      if (!fs::is_directory(d, ec)) throw_input_error(d, "--stage-dir", "a folder of stage executables", "no such folder");
      options.stage_dirs.push_back(fs::absolute(d));
    }
    if (cl.has("dry-run")) return dry_run(spec, options);
    const PipelineOutcome result = run_pipeline(spec, options);

    if (!options.quiet) {
      size_t ok = 0;
      size_t cached = 0;
      for (const auto& r : result.runs) {
        ok += r.ok ? 1 : 0;
        for (const auto& st : r.steps) cached += st.status == "cached" ? 1 : 0;
      }
      std::string made;
      for (const auto& t : result.tables)
        made += "; wrote " + t.path.filename().string() + " (" + std::to_string(t.rows) + " rows)";
      for (const auto& p : result.plots) made += "; plot " + p.png + " " + p.status;
      std::printf("valve-pipeline: %zu/%zu runs ok, %zu step(s) cached%s\n", ok, result.runs.size(), cached, made.c_str());
    }
    if (result.exit_code != 0) std::fprintf(stderr, "valve-pipeline: failed: %s\n", result.reason.c_str());
    return result.exit_code;
  });
}
