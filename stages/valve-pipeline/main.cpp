// valve-pipeline run P.json --out DIR [--jobs N] [--run ID ...] [--force] [--dry-run] [--stage-dir D ...] [--quiet]
// valve-pipeline list P.json [--out DIR] [--stage-dir D ...]
// valve-pipeline export --snakemake P.json --out DIR [--stage-dir D ...]
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
// Shared steps (the leading steps that use no sweep variable) run once, into DIR/shared.
// valve-pipeline export --snakemake P.json --out DIR [--stage-dir D ...]
// writes DIR/Snakefile: the same steps as snakemake rules writing into DIR as `run` would
// (libvalve/valve/pipeline/snakemake_export.hpp); then `snakemake -s DIR/Snakefile -j N`, or
// on a cluster `snakemake -s DIR/Snakefile --slurm --jobs N --default-resources ...`.
// The Snakefile's rules call two more commands: `stamp P.json --out DIR --run ID --step NAME
// --exit-code C --stage-sha256 H` (fails with exit 3 unless C is allowed, else writes the
// step's cache stamp) and `tables P.json --out DIR` (the gather, aggregate and plot files,
// and provenance.json, from the runs' folders as they are).
// Exit 0 ok, 2 bad pipeline (one line naming file and key, nothing written), 3 some run or
// plot failed (the summary says which; the tables still hold what the other runs made).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/pipeline_spec.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/pipeline/runner.hpp"
#include "valve/pipeline/snakemake_export.hpp"
#include "valve/pipeline/step_cache.hpp"
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
  std::printf("pipeline %s (%s): %zu run(s)%s, %zu step(s) each", spec.name.c_str(), spec.file.c_str(), runs.size(),
              vars.empty() ? "" : ((spec.sweep == SweepKind::grid ? ", grid over " : ", zip of ") + vars).c_str(),
              spec.steps.size() - spec.shared_steps);
  if (spec.shared_steps) std::printf(" after %zu shared step(s)", spec.shared_steps);
  std::printf("\n");
  if (!cl.get("out")) std::printf("# OUT stands for the --out folder\n");
  for (const auto& r : spec.required)
    std::printf("requires %s (%zu run(s)), run first into %s\n", r.spec->file.c_str(),
                expand_runs(*r.spec, out / r.out).size(), show((normalized_dir(out) / r.out).string()).c_str());
  auto print_run = [&](const RunPlan& run, size_t first_step, const std::string& title) {
    std::printf("%s\n", title.c_str());
    for (size_t s = 0; s < run.steps.size(); ++s) {
      std::vector<std::string> words{exes[first_step + s].string()};
      words.insert(words.end(), run.steps[s].args.begin(), run.steps[s].args.end());
      std::printf("  [%s] %s\n", run.steps[s].name.c_str(), show(shell_quote(words)).c_str());
    }
  };
  if (const auto shared = shared_run(spec, out)) print_run(*shared, 0, "shared steps, once, in " + show(shared->run_dir.string()));
  for (const auto& run : runs) print_run(run, spec.shared_steps, "run " + run.run_id);
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
  const auto hashes = stage_hashes(exes);
  const size_t k = spec.shared_steps;
  auto show = [&](const RunPlan& run, const StepPlan& plan, const std::string& title) {
    std::printf("%s\n", title.c_str());
    bool runs_any = false;
    for (size_t s = 0; s < run.steps.size(); ++s) {
      const auto& why = plan[s];
      (why ? to_run : cached) += 1;
      runs_any = runs_any || why.has_value();
      std::printf("  [%s] %s\n", run.steps[s].name.c_str(), why ? ("run: " + *why).c_str() : "cached");
    }
    return runs_any;
  };
  std::string rerun_all;
  if (const auto shared = shared_run(spec, options.out_dir))
    if (show(*shared, plan_runs({*shared}, {hashes.begin(), hashes.begin() + k}, options.force).front(),
             "shared steps in " + shared->run_dir.string()))
      rerun_all = "a shared step runs";
  const auto runs = select_runs(expand_runs(spec, options.out_dir), options.only_runs, "--run");
  const auto plans = plan_runs(runs, {hashes.begin() + k, hashes.end()}, options.force, rerun_all);
  for (size_t r = 0; r < runs.size(); ++r) show(runs[r], plans[r], "run " + runs[r].run_id);
}

// The run (or the shared steps, "shared") with this id.
RunPlan find_run(const PipelineSpec& spec, const fs::path& out, const std::string& id) {
  if (const auto shared = shared_run(spec, out); shared && id == shared->run_id) return *shared;
  return select_runs(expand_runs(spec, out), {id}, "--run").front();
}

// `stamp`: the end of a step run by another engine (the exported Snakefile's rules).
int stamp_step(const PipelineSpec& spec, const CommandLine& cl) {
  const fs::path out = cl.require("out");
  const RunPlan run = find_run(spec, out, cl.require("run"));
  const std::string name = cl.require("step");
  const auto step = std::find_if(run.steps.begin(), run.steps.end(), [&](const ResolvedStep& s) { return s.name == name; });
  if (step == run.steps.end())
    throw InputError("valve-pipeline: --step: expected a step of run " + run.run_id + ", found \"" + name + "\"");
  const std::string sha = cl.require("stage-sha256");
  if (sha.size() != 64 || sha.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw InputError("valve-pipeline: --stage-sha256: expected 64 lowercase hex digits, found \"" + sha + "\"");
  const std::string code_text = cl.require("exit-code");
  char* end = nullptr;
  const long code = std::strtol(code_text.c_str(), &end, 10);
  if (code_text.empty() || *end != '\0' || code < 0 || code > 255)
    throw InputError("valve-pipeline: --exit-code: expected an integer in [0, 255], found \"" + code_text + "\"");
  if (std::find(step->allow_exit.begin(), step->allow_exit.end(), static_cast<int>(code)) == step->allow_exit.end()) {
    std::fprintf(stderr, "valve-pipeline: step %s of run %s exited with %ld, see %s\n", name.c_str(), run.run_id.c_str(),
                 code, (run.run_dir / (name + ".log")).string().c_str());
    return 3;
  }
  write_step_stamp(run.run_dir, *step, step_cache_key(sha, *step));
  return 0;
}

// `tables`: what `run` writes after the steps, from the run folders as they are.
int write_tables_only(const PipelineSpec& spec, const RunnerOptions& options) {
  const auto exes = resolve_stages(spec, default_stage_dirs(options.stage_dirs));
  const fs::path out = normalized_dir(options.out_dir);
  const auto shared = shared_run(spec, out);
  const auto runs = expand_runs(spec, out);
  // Steps with a stamp count as done ("ok"), as far as provenance can tell.
  auto outcome = [](const RunPlan& run) {
    RunOutcome o;
    o.run_id = run.run_id;
    o.variables = run.variables;
    o.ok = true;
    for (const auto& s : run.steps) {
      StepOutcome so;
      so.name = s.name;
      std::error_code ec;
      so.status = fs::is_regular_file(step_stamp_path(run.run_dir, s.name), ec) ? "ok" : "skipped";
      o.ok = o.ok && so.status == "ok";
      o.steps.push_back(so);
    }
    return o;
  };
  std::optional<RunOutcome> shared_outcome;
  if (shared) shared_outcome = outcome(*shared);
  std::vector<RunOutcome> outcomes;
  for (const auto& r : runs) outcomes.push_back(outcome(r));
  fs::create_directories(out);
  write_provenance(spec, shared, shared_outcome, runs, outcomes, exes, stage_hashes(exes), out);
  PipelineOutcome result;
  write_tables(spec, runs, out, result);
  size_t failed = 0;
  for (const auto& p : result.plots) failed += p.status == "failed" ? 1 : 0;
  if (!options.quiet)
    for (const auto& t : result.tables) std::printf("valve-pipeline: wrote %s (%zu rows)\n", t.path.string().c_str(), t.rows);
  return failed ? 3 : 0;
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
    CommandLine cl(argc, argv, {"out", "jobs", "stage-dir", "run", "step", "exit-code", "stage-sha256"},
                   {"quiet", "force", "dry-run", "snakemake"});
    const auto& pos = cl.positional();
    const std::vector<std::string> commands{"run", "list", "export", "stamp", "tables"};
    if (pos.size() != 2 || std::find(commands.begin(), commands.end(), pos[0]) == commands.end())
      throw InputError("valve-pipeline: command: expected \"run P.json\", \"list P.json\" or \"export --snakemake "
                       "P.json\", found " + std::to_string(pos.size()) + " positional argument(s)" +
                       (pos.empty() ? "" : " starting with \"" + pos[0] + "\""));
    if (pos[0] == "export" && !cl.has("snakemake"))
      throw InputError("valve-pipeline: export: expected the format --snakemake, found none");
    // The Snakefile holds every run; snakemake picks targets and forces reruns itself.
    for (const char* option : {"run", "force", "dry-run"})
      if (pos[0] == "export" && (std::string(option) == "run" ? cl.get("run").has_value() : cl.has(option)))
        throw InputError(std::string("valve-pipeline: export: expected no --") + option +
                         " (snakemake selects and forces jobs itself), found --" + option);
    RunnerOptions options;
    if (pos[0] != "list") options.out_dir = cl.require("out");
    options.jobs = parse_jobs(cl);
    const PipelineSpec spec = load_pipeline(pos[1]);
    if (pos[0] == "list") return list_runs(spec, cl);
    if (pos[0] == "stamp") return stamp_step(spec, cl);

    options.quiet = cl.has("quiet");
    options.force = cl.has("force");
    options.only_runs = cl.get_all("run");
    for (const auto& d : cl.get_all("stage-dir")) {
      std::error_code ec;
      if (!fs::is_directory(d, ec)) throw_input_error(d, "--stage-dir", "a folder of stage executables", "no such folder");
      options.stage_dirs.push_back(fs::absolute(d));
    }
    if (cl.has("dry-run")) return dry_run(spec, options);
    if (pos[0] == "tables") return write_tables_only(spec, options);
    if (pos[0] == "export") {
      const SnakemakeExport done =
          export_snakemake(spec, options.out_dir, options.stage_dirs, fs::canonical("/proc/self/exe"));
      if (!options.quiet)
        std::printf("valve-pipeline: wrote %s (%zu step rules); run it with snakemake -s %s -j N\n",
                    done.snakefile.string().c_str(), done.step_rules, done.snakefile.string().c_str());
      return 0;
    }
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
