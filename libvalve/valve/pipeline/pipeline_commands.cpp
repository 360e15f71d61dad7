#include "valve/pipeline/pipeline_commands.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "valve/core/error.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/pipeline/step_cache.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

// What `run` would do, step by step: the required pipelines first, as `run` runs them.
// Adds to the step counts.
void dry_run_steps(const PipelineSpec& spec, const RunnerOptions& options, std::ostream& out, size_t& to_run,
                   size_t& cached) {
  for (const auto& r : spec.required) {
    RunnerOptions upstream = options;
    upstream.out_dir = normalized_dir(options.out_dir) / r.out;
    upstream.only_runs.clear();
    out << "required pipeline " << r.spec->file << " into " << upstream.out_dir.string() << "\n";
    dry_run_steps(*r.spec, upstream, out, to_run, cached);
  }
  const auto exes = resolve_stages(spec, default_stage_dirs(options.stage_dirs));
  const auto hashes = stage_hashes(exes);
  const size_t k = spec.shared_steps;
  auto show = [&](const RunPlan& run, const StepPlan& plan, const std::string& title) {
    out << title << "\n";
    bool runs_any = false;
    for (size_t s = 0; s < run.steps.size(); ++s) {
      const auto& why = plan[s];
      (why ? to_run : cached) += 1;
      runs_any = runs_any || why.has_value();
      out << "  [" << run.steps[s].name << "] " << (why ? "run: " + *why : std::string("cached")) << "\n";
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

// A run as provenance sees it from its folder: a step with a stamp is done ("ok"); one
// without is "skipped", and the run is ok only when every step is done.
RunOutcome outcome_from_stamps(const RunPlan& run) {
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
}

}  // namespace

std::string pipeline_command(const CommandLine& cl) {
  const auto& pos = cl.positional();
  const std::vector<std::string> commands{"run", "list", "export", "stamp", "tables"};
  if (pos.size() != 2 || std::find(commands.begin(), commands.end(), pos[0]) == commands.end())
    throw InputError("valve-pipeline: command: expected \"run P.json\", \"list P.json\" or \"export --snakemake "
                     "P.json\", found " + std::to_string(pos.size()) + " positional argument(s)" +
                     (pos.empty() ? "" : " starting with \"" + pos[0] + "\""));
  if (pos[0] == "export" && !cl.has("snakemake"))
    throw InputError("valve-pipeline: export: expected the format --snakemake, found none");
  for (const char* option : {"run", "force", "dry-run"})
    if (pos[0] == "export" && (std::string(option) == "run" ? cl.get("run").has_value() : cl.has(option)))
      throw InputError(std::string("valve-pipeline: export: expected no --") + option +
                       " (snakemake selects and forces jobs itself), found --" + option);
  return pos[0];
}

int pipeline_jobs(const CommandLine& cl) {
  const auto v = cl.get("jobs");
  if (!v) return 1;
  char* end = nullptr;
  const long n = std::strtol(v->c_str(), &end, 10);
  if (end == v->c_str() || *end != '\0' || n < 1 || n > 1024)
    throw InputError("valve-pipeline: --jobs: expected an integer in [1, 1024], found \"" + *v + "\"");
  return static_cast<int>(n);
}

std::vector<fs::path> pipeline_stage_dirs(const CommandLine& cl) {
  std::vector<fs::path> dirs;
  for (const auto& d : cl.get_all("stage-dir")) {
    std::error_code ec;
    if (!fs::is_directory(d, ec)) throw_input_error(d, "--stage-dir", "a folder of stage executables", "no such folder");
    dirs.push_back(fs::absolute(d));
  }
  return dirs;
}

int list_pipeline(const PipelineSpec& spec, const CommandLine& cl, std::ostream& out) {
  // `list` shows the commands even when a --stage-dir is missing: only the stages must be found.
  std::vector<fs::path> given;
  for (const auto& d : cl.get_all("stage-dir")) given.push_back(fs::absolute(d));
  const auto exes = resolve_stages(spec, default_stage_dirs(given));
  resolve_required_stages(spec, default_stage_dirs(given));
  // Without --out the paths are made under a stand-in folder, then shown as $OUT.
  const std::string marker = "/__valve_pipeline_out__";
  const bool has_out = cl.get("out").has_value();
  const fs::path out_dir = has_out ? fs::path(*cl.get("out")) : fs::path(marker);
  const auto runs = expand_runs(spec, out_dir);
  auto show = [&](std::string text) {
    if (has_out) return text;
    for (size_t at; (at = text.find(marker)) != std::string::npos;) text.replace(at, marker.size(), "$OUT");
    return text;
  };
  std::string vars;
  for (const auto& v : spec.variables)
    vars += (vars.empty() ? "" : spec.sweep == SweepKind::grid ? " x " : ", ") + v.name + " (" +
            std::to_string(v.values.size()) + ")";
  out << "pipeline " << spec.name << " (" << spec.file << "): " << runs.size() << " run(s)"
      << (vars.empty() ? "" : (spec.sweep == SweepKind::grid ? ", grid over " : ", zip of ") + vars) << ", "
      << spec.steps.size() - spec.shared_steps << " step(s) each";
  if (spec.shared_steps) out << " after " << spec.shared_steps << " shared step(s)";
  out << "\n";
  if (!has_out) out << "# OUT stands for the --out folder\n";
  for (const auto& r : spec.required)
    out << "requires " << r.spec->file << " (" << expand_runs(*r.spec, out_dir / r.out).size() << " run(s)), run first into "
        << show((normalized_dir(out_dir) / r.out).string()) << "\n";
  auto print_run = [&](const RunPlan& run, size_t first_step, const std::string& title) {
    out << title << "\n";
    for (size_t s = 0; s < run.steps.size(); ++s) {
      std::vector<std::string> words{exes[first_step + s].string()};
      words.insert(words.end(), run.steps[s].args.begin(), run.steps[s].args.end());
      out << "  [" << run.steps[s].name << "] " << show(shell_quote(words)) << "\n";
    }
  };
  if (const auto shared = shared_run(spec, out_dir))
    print_run(*shared, 0, "shared steps, once, in " + show(shared->run_dir.string()));
  for (const auto& run : runs) print_run(run, spec.shared_steps, "run " + run.run_id);
  for (const auto& g : spec.gather)
    out << "gather " << show((normalized_dir(out_dir) / g.csv).string()) << " from runs/*/" << g.summary << "\n";
  for (const auto& e : spec.selects) out << "select " << show((normalized_dir(out_dir) / e.csv).string()) << " from " << e.from << "\n";
  for (const auto& p : spec.plots) out << "plot " << show((normalized_dir(out_dir) / p.png).string()) << " from " << p.csv << "\n";
  return 0;
}

int dry_run_pipeline(const PipelineSpec& spec, const RunnerOptions& options, std::ostream& out) {
  select_runs(expand_runs(spec, options.out_dir), options.only_runs, "--run");  // an unknown --run fails first
  size_t to_run = 0, cached = 0;
  dry_run_steps(spec, options, out, to_run, cached);
  out << "dry run: " << to_run << " step(s) would run, " << cached << " cached\n";
  return 0;
}

int stamp_pipeline_step(const PipelineSpec& spec, const CommandLine& cl) {
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

int write_pipeline_tables(const PipelineSpec& spec, const RunnerOptions& options, std::ostream& out) {
  const auto exes = resolve_stages(spec, default_stage_dirs(options.stage_dirs));
  const fs::path out_dir = normalized_dir(options.out_dir);
  const auto shared = shared_run(spec, out_dir);
  const auto runs = expand_runs(spec, out_dir);
  std::optional<RunOutcome> shared_outcome;
  if (shared) shared_outcome = outcome_from_stamps(*shared);
  std::vector<RunOutcome> outcomes;
  for (const auto& r : runs) outcomes.push_back(outcome_from_stamps(r));
  fs::create_directories(out_dir);
  write_provenance(spec, shared, shared_outcome, runs, outcomes, exes, stage_hashes(exes), out_dir);
  PipelineOutcome result;
  write_tables(spec, runs, out_dir, result);
  size_t failed = 0;
  for (const auto& p : result.plots) failed += p.status == "failed" ? 1 : 0;
  if (!options.quiet) {
    for (const auto& t : result.tables) out << "valve-pipeline: wrote " << t.path.string() << " (" << t.rows << " rows)\n";
    for (const auto& e : result.selects) out << "valve-pipeline: " << e.line << "\n";
  }
  return failed ? 3 : 0;
}

std::string pipeline_outcome_line(const PipelineOutcome& outcome) {
  size_t ok = 0;
  size_t cached = 0;
  for (const auto& r : outcome.runs) {
    ok += r.ok ? 1 : 0;
    for (const auto& st : r.steps) cached += st.status == "cached" ? 1 : 0;
  }
  std::string made;
  for (const auto& t : outcome.tables) made += "; wrote " + t.path.filename().string() + " (" + std::to_string(t.rows) + " rows)";
  for (const auto& p : outcome.plots) made += "; plot " + p.png + " " + p.status;
  std::string choices;
  for (const auto& e : outcome.selects) choices += "\nvalve-pipeline: " + e.line;
  return "valve-pipeline: " + std::to_string(ok) + "/" + std::to_string(outcome.runs.size()) + " runs ok, " +
         std::to_string(cached) + " step(s) cached" + made + choices;
}

}  // namespace valve
