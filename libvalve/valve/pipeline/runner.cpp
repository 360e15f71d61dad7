#include "valve/pipeline/runner.hpp"

#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>

#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/pipeline/step_cache.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

bool allowed(const std::vector<int>& codes, int code) {
  return std::find(codes.begin(), codes.end(), code) != codes.end();
}

std::string timestamp() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", std::localtime(&t));
  return buf;
}

// One line per step outcome; a log that cannot be opened is not worth failing a run for.
void log_step(const fs::path& log, const std::string& run_id, const StepOutcome& so) {
  if (log.empty()) return;
  std::ofstream out(log, std::ios::app);
  if (!out) return;
  char wall[32];
  std::snprintf(wall, sizeof wall, "%.3f", so.wall_time_s);
  out << timestamp() << " run " << run_id << " step " << so.name << " " << so.status;
  if (so.status != "cached") out << " exit " << so.exit_code << " wall_s " << wall;
  if (!so.run_reason.empty()) out << " (" << so.run_reason << ")";
  if (!so.error.empty()) out << " error: " << so.error;
  out << "\n";
}

// The state of one run while its steps execute one after another.
struct ActiveRun {
  size_t run = 0, step = 0;
  Stopwatch run_clock, step_clock;
};

}  // namespace

std::vector<fs::path> resolve_stages(const PipelineSpec& spec, const std::vector<fs::path>& dirs) {
  std::vector<fs::path> exes;
  for (const auto& step : spec.steps) {
    const auto exe = find_stage(step.stage, dirs);
    if (!exe) {
      std::string where;
      for (const auto& d : dirs) where += d.string() + ", ";
      throw_input_error(spec.file, step.key + ".stage",
                        "an executable " + step.stage + " in " + where + "or on PATH", "none");
    }
    exes.push_back(*exe);
  }
  return exes;
}

std::vector<StepPlan> plan_runs(const std::vector<RunPlan>& runs, const std::vector<std::string>& executable_sha256,
                                bool force, const std::string& rerun_all) {
  std::vector<StepPlan> plans;
  for (const RunPlan& run : runs) {
    StepPlan plan;
    bool running = force || !rerun_all.empty();
    for (size_t i = 0; i < run.steps.size(); ++i) {
      if (running) {
        plan.push_back(force ? std::string("forced") : !rerun_all.empty() && i == 0 ? rerun_all : std::string("an earlier step runs"));
        continue;
      }
      plan.push_back(step_rerun_reason(run.run_dir, run.steps[i], step_cache_key(executable_sha256.at(i), run.steps[i])));
      running = plan.back().has_value();
    }
    plans.push_back(plan);
  }
  return plans;
}

std::vector<RunOutcome> execute_runs(const std::vector<RunPlan>& runs, const std::vector<fs::path>& executables,
                                     const ExecutionOptions& options, const RunProgress& progress) {
  const int jobs = options.jobs;
  const bool quiet = options.quiet;
  const std::vector<StepPlan> plans = plan_runs(runs, options.executable_sha256, options.force, options.rerun_all);
  std::vector<RunOutcome> out(runs.size());
  for (size_t r = 0; r < runs.size(); ++r) {
    out[r].run_id = runs[r].run_id;
    out[r].variables = runs[r].variables;
    for (const auto& s : runs[r].steps) {
      StepOutcome so;
      so.name = s.name;
      out[r].steps.push_back(so);
    }
  }
  std::map<pid_t, ActiveRun> active;
  size_t next = 0, finished = 0, failed = 0;

  auto report = [&](const std::string& last) {
    if (!progress) return;
    double done = static_cast<double>(finished);
    for (const auto& [pid, a] : active) done += static_cast<double>(a.step) / static_cast<double>(runs[a.run].steps.size());
    progress(done / static_cast<double>(runs.size()),
             std::to_string(finished) + "/" + std::to_string(runs.size()) + " runs done" +
                 (failed ? " (" + std::to_string(failed) + " failed)" : "") + ", " + std::to_string(active.size()) +
                 " running, last: " + last);
  };

  auto finish_run = [&](ActiveRun& a, bool ok, const std::string& reason) {
    RunOutcome& o = out[a.run];
    o.ok = ok;
    o.reason = reason;
    o.wall_time_s = a.run_clock.seconds();
    ++finished;
    if (!ok) {
      ++failed;
      if (!quiet) std::fprintf(stderr, "[valve-pipeline] run %s failed: %s\n", o.run_id.c_str(), reason.c_str());
    }
    report(o.run_id + (ok ? " done" : " failed"));
  };

  // Starts step a.step of its run, or finishes the run when it has no step left. A step that
  // cannot start fails the run at once. Returns whether a step is now running.
  auto start_step = [&](ActiveRun a) {
    const RunPlan& run = runs[a.run];
    while (a.step < run.steps.size() && !plans[a.run][a.step]) {
      StepOutcome& cached = out[a.run].steps[a.step];
      cached.status = "cached";
      cached.exit_code = 0;
      log_step(options.log, run.run_id, cached);
      ++a.step;
    }
    if (a.step >= run.steps.size()) {
      finish_run(a, true, "");
      return false;
    }
    const ResolvedStep& step = run.steps[a.step];
    StepOutcome& so = out[a.run].steps[a.step];
    so.run_reason = *plans[a.run][a.step];
    clear_step_outputs(run.run_dir, step);
    a.step_clock = Stopwatch();
    std::string error;
    const pid_t pid = spawn_process(executables.at(a.step), step.args, run.run_dir,
                                    run.run_dir / (step.name + ".log"), error);
    if (pid < 0) {
      so.status = "failed";
      so.exit_code = 127;
      so.error = error;
      log_step(options.log, run.run_id, so);
      finish_run(a, false, "step " + step.name + ": " + error);
      return false;
    }
    active[pid] = a;
    return true;
  };

  while (next < runs.size() || !active.empty()) {
    while (active.size() < static_cast<size_t>(std::max(jobs, 1)) && next < runs.size()) {
      ActiveRun a;
      a.run = next++;
      const fs::path& dir = runs[a.run].run_dir;
      std::error_code ec;
      // Nothing cached: start from an empty folder, as a first run would.
      if (!plans[a.run].empty() && plans[a.run][0]) fs::remove_all(dir, ec);
      fs::create_directories(dir, ec);
      if (ec) {
        finish_run(a, false, dir.string() + ": cannot create the run folder: " + ec.message());
        continue;
      }
      start_step(a);
    }
    if (active.empty()) continue;
    ProcessExit exit;
    const pid_t pid = wait_any_child(exit);
    if (pid < 0) throw Error("valve-pipeline: lost track of the running stages (wait failed)");
    const auto it = active.find(pid);
    if (it == active.end()) continue;  // not one of ours
    ActiveRun a = it->second;
    active.erase(it);
    const ResolvedStep& step = runs[a.run].steps[a.step];
    StepOutcome& so = out[a.run].steps[a.step];
    so.exit_code = exit.code;
    so.error = exit.error;
    so.wall_time_s = a.step_clock.seconds();
    so.cpu_time_s = exit.cpu_time_s;
    if (exit.signal == 0 && allowed(step.allow_exit, exit.code)) {
      so.status = "ok";
      try {
        write_step_stamp(runs[a.run].run_dir, step, step_cache_key(options.executable_sha256.at(a.step), step));
      } catch (const std::exception& e) {  // the step stands; it will run again next time
        if (!quiet) std::fprintf(stderr, "[valve-pipeline] warning: no cache stamp for %s: %s\n", step.name.c_str(), e.what());
      }
      log_step(options.log, runs[a.run].run_id, so);
      ++a.step;
      if (start_step(a)) report(runs[a.run].run_id + " " + step.name + " done");
    } else {
      so.status = "failed";
      log_step(options.log, runs[a.run].run_id, so);
      const std::string log = (fs::path("runs") / runs[a.run].run_id / (step.name + ".log")).string();
      finish_run(a, false,
                 "step " + step.name + (exit.signal ? " was " + exit.error : " exited with " + std::to_string(exit.code)) +
                     ", see " + log);
    }
  }
  return out;
}

std::vector<std::string> stage_hashes(const std::vector<fs::path>& executables) {
  std::map<fs::path, std::string> known;
  std::vector<std::string> hashes;
  for (const auto& e : executables) {
    if (!known.count(e)) known[e] = sha256_file(e);
    hashes.push_back(known[e]);
  }
  return hashes;
}

void resolve_required_stages(const PipelineSpec& spec, const std::vector<fs::path>& dirs) {
  for (const auto& r : spec.required) {
    resolve_stages(*r.spec, dirs);
    resolve_required_stages(*r.spec, dirs);
  }
}

namespace {

nlohmann::json run_provenance(const RunPlan& run, const RunOutcome& outcome, const std::vector<std::string>& hashes,
                              size_t first_step) {
  nlohmann::json jr = {{"run_id", run.run_id}, {"variables", nlohmann::json(run.variables)},
                       {"steps", nlohmann::json::array()}};
  for (size_t s = 0; s < run.steps.size(); ++s) {
    const ResolvedStep& step = run.steps[s];
    const StepOutcome& so = outcome.steps[s];
    nlohmann::json js = {{"name", step.name}, {"stage", step.stage}, {"args", step.args}, {"status", so.status},
                         {"cache_key", step_cache_key(hashes[first_step + s], step)}, {"inputs", nlohmann::json::array()}};
    if (!so.run_reason.empty()) js["ran_because"] = so.run_reason;
    if (so.status == "ok" || so.status == "cached")
      for (const auto& in : read_step_stamp_inputs(run.run_dir, step.name))
        js["inputs"].push_back({{"path", in.path}, {"sha256", in.sha256}});
    jr["steps"].push_back(js);
  }
  return jr;
}

}  // namespace

void write_provenance(const PipelineSpec& spec, const std::optional<RunPlan>& shared,
                      const std::optional<RunOutcome>& shared_outcome, const std::vector<RunPlan>& runs,
                      const std::vector<RunOutcome>& outcomes, const std::vector<fs::path>& executables,
                      const std::vector<std::string>& hashes, const fs::path& out) {
  nlohmann::json p = {{"tool", {{"name", "valve"}, {"version", VALVE_VERSION}}},
                      {"created", timestamp()},
                      {"pipeline", {{"file", fs::absolute(spec.file).string()}, {"name", spec.name}}},
                      {"stages", nlohmann::json::array()},
                      {"runs", nlohmann::json::array()}};
  std::error_code ec;
  if (fs::is_regular_file(spec.file, ec)) p["pipeline"]["sha256"] = sha256_file(spec.file);
  // The required pipelines' own provenance lies in their folders; here, which file ran where.
  p["required"] = nlohmann::json::array();
  for (const auto& r : spec.required) {
    nlohmann::json jr = {{"file", fs::absolute(r.spec->file).string()}, {"out", (out / r.out).string()}};
    if (fs::is_regular_file(r.spec->file, ec)) jr["sha256"] = sha256_file(r.spec->file);
    p["required"].push_back(jr);
  }
  for (size_t i = 0; i < spec.steps.size(); ++i)
    p["stages"].push_back({{"step", spec.steps[i].name}, {"stage", spec.steps[i].stage},
                           {"executable", executables[i].string()}, {"sha256", hashes[i]}});
  if (shared && shared_outcome) p["shared"] = run_provenance(*shared, *shared_outcome, hashes, 0);
  for (size_t r = 0; r < runs.size(); ++r) p["runs"].push_back(run_provenance(runs[r], outcomes[r], hashes, spec.shared_steps));
  write_file_atomic(out / "provenance.json", p.dump(2) + "\n");
}

namespace {

// The runs and output folders of the pipelines `spec` requires (and they require), so that
// a file in the way stops everything before the first run.
void check_required_folders(const PipelineSpec& spec, const fs::path& out) {
  for (const auto& r : spec.required) {
    expand_runs(*r.spec, out / r.out);
    std::error_code ec;
    if (fs::exists(out / r.out, ec) && !fs::is_directory(out / r.out, ec))
      throw_input_error(spec.file, r.key + ".out", "a folder", "the file " + (out / r.out).string());
    check_required_folders(*r.spec, out / r.out);
  }
}

}  // namespace

void write_tables(const PipelineSpec& spec, const std::vector<RunPlan>& runs, const fs::path& out,
                  PipelineOutcome& result) {
  // Aggregates read the tables as just made, in memory: earlier aggregates included.
  std::map<std::string, CsvTable> tables;
  for (const auto& csv : gather_csvs(spec)) result.tables.push_back(write_gather_csv(spec, csv, runs, out, &tables[csv]));
  for (const auto& a : spec.aggregates)
    result.aggregates.push_back(write_aggregate(a, tables.at(a.from), out, &tables[a.csv]));
  for (const auto& e : spec.selects) result.selects.push_back(write_select(e, tables.at(e.from), out));
  const auto gnuplot = spec.plots.empty() ? std::nullopt : find_on_path("gnuplot");
  if (!spec.plots.empty() && !gnuplot)
    std::fprintf(stderr, "valve-pipeline: warning: gnuplot is not on PATH, skipping %zu plot(s)\n", spec.plots.size());
  for (const auto& p : spec.plots) result.plots.push_back(render_plot(spec, p, out, gnuplot));
}

PipelineOutcome run_pipeline(const PipelineSpec& spec, const RunnerOptions& options) {
  // Everything that can reject the pipeline happens before the output folder is created.
  const auto exes = resolve_stages(spec, default_stage_dirs(options.stage_dirs));
  const std::vector<RunPlan> runs = select_runs(expand_runs(spec, options.out_dir), options.only_runs, "--run");
  const fs::path out = normalized_dir(options.out_dir);
  resolve_required_stages(spec, default_stage_dirs(options.stage_dirs));
  check_required_folders(spec, out);

  StageSummary summary("pipeline", out);  // makes the folder, or refuses it (exit 2)
  std::error_code ec;
  if (fs::is_regular_file(spec.file, ec)) summary.add_input("pipeline", spec.file);
  summary.parameters() = nlohmann::json(spec.source);

  PipelineOutcome result;
  nlohmann::json& m = summary.metrics();
  m["name"] = spec.name;
  m["jobs"] = options.jobs;
  m["required"] = nlohmann::json::array();
  std::string upstream_failure;  // empty while every required pipeline succeeds
  for (const auto& r : spec.required) {
    RunnerOptions upstream = options;
    upstream.out_dir = out / r.out;
    upstream.only_runs.clear();  // --run names runs of this pipeline
    const PipelineOutcome done = run_pipeline(*r.spec, upstream);
    m["required"].push_back({{"pipeline", r.spec->file}, {"out", upstream.out_dir.string()}, {"status", done.status}});
    if (done.exit_code != 0) {
      upstream_failure = r.key + " (" + r.spec->file + ", in " + upstream.out_dir.string() + ") failed: " + done.reason;
      break;
    }
  }

  Progress progress("valve-pipeline", options.quiet);
  const std::optional<RunPlan> shared = shared_run(spec, out);
  const size_t first_run_step = spec.shared_steps;
  const std::vector<std::string> hashes = stage_hashes(exes);
  ExecutionOptions exec;
  exec.jobs = options.jobs;
  exec.quiet = options.quiet;
  exec.force = options.force;
  exec.log = out / "pipeline.log";
  auto report = [&](double fraction, const std::string& detail) { progress.update(fraction, detail); };
  if (upstream_failure.empty() && shared) {
    ExecutionOptions once = exec;
    once.executable_sha256.assign(hashes.begin(), hashes.begin() + first_run_step);
    result.shared = execute_runs({*shared}, {exes.begin(), exes.begin() + first_run_step}, once, report).front();
    if (!result.shared->ok) upstream_failure = "the shared steps failed: " + result.shared->reason;
    else if (std::any_of(result.shared->steps.begin(), result.shared->steps.end(),
                         [](const StepOutcome& so) { return so.status == "ok"; }))
      exec.rerun_all = "a shared step ran";
  }
  if (upstream_failure.empty()) {
    exec.executable_sha256.assign(hashes.begin() + first_run_step, hashes.end());
    result.runs = execute_runs(runs, {exes.begin() + first_run_step, exes.end()}, exec, report);
    write_provenance(spec, shared, result.shared, runs, result.runs, exes, hashes, out);
    write_tables(spec, runs, out, result);
  } else {
    // No run starts; tables, plots and provenance are not touched.
    for (const auto& run : runs) {
      RunOutcome o;
      o.run_id = run.run_id;
      o.variables = run.variables;
      o.reason = result.shared && !result.shared->ok ? "not started: a shared step failed"
                                                     : "not started: a required pipeline failed";
      result.runs.push_back(o);
    }
  }

  size_t failed_runs = 0, failed_plots = 0;
  for (const auto& r : result.runs) failed_runs += r.ok ? 0 : 1;
  for (const auto& p : result.plots) failed_plots += p.status == "failed" ? 1 : 0;
  progress.finish(std::to_string(runs.size() - failed_runs) + "/" + std::to_string(runs.size()) + " runs ok");

  result.status = failed_runs + failed_plots == 0 ? "ok" : "failed";
  if (!upstream_failure.empty()) {
    result.status = "failed";
    result.reason = upstream_failure + "; no run of this pipeline started";
  } else if (failed_runs) {
    const RunOutcome& first = *std::find_if(result.runs.begin(), result.runs.end(), [](const RunOutcome& r) { return !r.ok; });
    result.reason = std::to_string(failed_runs) + " of " + std::to_string(runs.size()) + " runs failed (first: " +
                    first.run_id + ", " + first.reason + ")";
  } else if (failed_plots) {
    const PlotResult& first = *std::find_if(result.plots.begin(), result.plots.end(),
                                            [](const PlotResult& p) { return p.status == "failed"; });
    result.reason = std::to_string(failed_plots) + " plot(s) failed (first: " + first.png + ", " + first.reason + ")";
  }
  result.exit_code = result.status == "ok" ? 0 : 3;

  m["runs_total"] = runs.size();
  m["runs_ok"] = runs.size() - failed_runs;
  m["runs_failed"] = failed_runs;
  m["stages"] = nlohmann::json::object();
  for (size_t i = 0; i < spec.steps.size(); ++i) m["stages"][spec.steps[i].stage] = exes[i].string();
  m["runs"] = nlohmann::json::array();
  auto run_metrics = [&](const RunOutcome& o, const RunPlan& plan) {
    nlohmann::json jr = {{"run_id", o.run_id},
                         {"run_dir", plan.run_dir.string()},
                         {"variables", nlohmann::json(o.variables)},
                         {"status", o.ok ? "ok" : "failed"},
                         {"wall_time_s", o.wall_time_s},
                         {"exit_codes", nlohmann::json::object()},
                         {"steps", nlohmann::json::array()}};
    if (!o.reason.empty()) jr["reason"] = o.reason;
    for (size_t s = 0; s < o.steps.size(); ++s) {
      const StepOutcome& so = o.steps[s];
      jr["exit_codes"][so.name] = so.exit_code >= 0 ? nlohmann::json(so.exit_code) : nlohmann::json(nullptr);
      nlohmann::json js = {{"name", so.name},
                           {"stage", plan.steps[s].stage},
                           {"status", so.status},
                           {"exit_code", jr["exit_codes"][so.name]},
                           {"cached", so.status == "cached"},
                           {"wall_time_s", so.wall_time_s},
                           {"cpu_time_s", so.cpu_time_s},
                           {"log", (plan.run_dir / (so.name + ".log")).string()}};
      if (!so.error.empty()) js["error"] = so.error;
      jr["steps"].push_back(js);
    }
    return jr;
  };
  if (result.shared) m["shared"] = run_metrics(*result.shared, *shared);
  for (size_t r = 0; r < runs.size(); ++r) m["runs"].push_back(run_metrics(result.runs[r], runs[r]));
  m["csv"] = nlohmann::json::array();
  for (const auto& t : result.tables) {
    nlohmann::json missing = nlohmann::json::array();
    for (const auto& x : t.missing) missing.push_back({{"run_id", x.run_id}, {"reason", x.reason}});
    m["csv"].push_back({{"file", t.path.string()}, {"kind", "gather"}, {"rows", t.rows}, {"missing_summaries", missing}});
  }
  for (const auto& a : result.aggregates)
    m["csv"].push_back({{"file", a.path.string()}, {"kind", "aggregate"}, {"from", (out / a.from).string()}, {"rows", a.rows}});
  for (const auto& e : result.selects)
    m["csv"].push_back({{"file", e.path.string()}, {"kind", "select"}, {"from", (out / e.from).string()},
                        {"rows", e.rows}, {"text", e.text.string()}, {"line", e.line}});
  m["plots"] = {{"made", nlohmann::json::array()}, {"skipped", nlohmann::json::array()}, {"failed", nlohmann::json::array()}};
  for (const auto& p : result.plots) {
    if (p.status == "made") m["plots"]["made"].push_back((out / p.png).string());
    else m["plots"][p.status].push_back({{"png", (out / p.png).string()}, {"reason", p.reason}});
  }
  summary.set_status(result.status, result.reason);
  summary.write();
  return result;
}

}  // namespace valve
