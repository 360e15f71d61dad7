#include "valve/pipeline/runner.hpp"

#include <catch2/catch.hpp>

#include "pipeline_test_support.hpp"
#include "valve/core/error.hpp"
#include "valve/core/install_layout.hpp"
#include "valve/pipeline/pipeline_commands.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/pipeline/snakemake_export.hpp"
#include "valve/pipeline/step_cache.hpp"
#include <algorithm>

using namespace valve;
using valve::test::read_text;
using valve::test::TempDir;
using valve::test::write_script;
using valve::test::write_text;
namespace fs = std::filesystem;

namespace {

// Fake stages: small sh scripts in a folder given to the runner with stage_dirs.
void write_fake_stages(const fs::path& dir) {
  // valve-exit CODE: prints to both streams, exits with CODE.
  write_script(dir / "valve-exit", "echo \"to stdout $1\"; echo \"to stderr $1\" >&2; exit \"$1\"");
  // valve-report VALUE: writes a summary in the working directory (the run folder).
  write_script(dir / "valve-report",
               "printf '{\"status\": \"ok\", \"value\": %s, \"args\": \"%s\"}\\n' \"$1\" \"$*\" > report.summary.json");
  // valve-crowd SHARED: marks itself running, waits, counts how many runs ever started.
  write_script(dir / "valve-crowd", "touch \"$1/$$\"; sleep 0.5; ls \"$1\" | wc -l > crowd.txt");
  write_script(dir / "valve-suicide", "kill -9 $$");
  write_text(dir / "valve-broken", "#!/nonexistent/interpreter\n");
  fs::permissions(dir / "valve-broken", fs::perms::owner_all);
}

// Runs in root/out with the fake stages of root/bin.
RunnerOptions fake_stage_options(const fs::path& root) {
  RunnerOptions options;
  options.out_dir = root / "out";
  options.stage_dirs = {root / "bin"};
  return options;
}

PipelineSpec write_and_load(const fs::path& dir, const std::string& text) {
  write_text(dir / "P.json", text);
  return load_pipeline(dir / "P.json");
}

}  // namespace

TEST_CASE("runner: allow_exit, failed runs skip later steps, logs, summary and gather", "[pipeline]") {
  TempDir tmp("runner");
  write_fake_stages(tmp.path() / "bin");
  const auto spec = write_and_load(tmp.path(), R"({
    "variables": {"code": [0, 3, 5]},
    "steps": [
      {"name": "first", "stage": "valve-exit", "args": ["${code}"], "allow_exit": [0, 3]},
      {"name": "second", "stage": "valve-report", "args": ["${code}", "${run_id}"]}
    ],
    "gather": [{"csv": "values.csv", "summary": "report.summary.json",
                "columns": {"code": "${code}", "value": "summary:value", "status": "summary:status"}}]
  })");
  RunnerOptions options = fake_stage_options(tmp.path());
  const PipelineOutcome result = run_pipeline(spec, options);

  CHECK(result.exit_code == 3);
  CHECK(result.status == "failed");
  CHECK_THAT(result.reason, Catch::Contains("1 of 3 runs failed (first: code-5, step first exited with 5"));
  REQUIRE(result.runs.size() == 3);
  CHECK(result.runs[0].ok);
  CHECK(result.runs[1].ok);  // 3 is allowed
  CHECK(result.runs[1].steps[0].exit_code == 3);
  CHECK_FALSE(result.runs[2].ok);
  CHECK(result.runs[2].steps[0].status == "failed");
  CHECK(result.runs[2].steps[1].status == "skipped");
  CHECK(result.runs[2].steps[1].exit_code == -1);
  const fs::path out = tmp.path() / "out";
  CHECK_FALSE(fs::exists(out / "runs/code-5/second.log"));
  CHECK_FALSE(fs::exists(out / "runs/code-5/report.summary.json"));

  // Both streams land in the step log, after the command line.
  const std::string log = read_text(out / "runs/code-3/first.log");
  CHECK(log.rfind("# cd ", 0) == 0);
  CHECK_THAT(log, Catch::Contains("valve-exit 3\n"));
  CHECK_THAT(log, Catch::Contains("to stdout 3"));
  CHECK_THAT(log, Catch::Contains("to stderr 3"));

  CHECK(read_text(out / "values.csv") == "code,value,status\n0,0,ok\n3,3,ok\n5,,\n");

  const ojson summary = ojson::parse(read_text(out / "pipeline.summary.json"));
  CHECK(summary["stage"] == "pipeline");
  CHECK(summary["status"] == "failed");
  CHECK(summary["inputs"][0]["sha256"].get<std::string>().size() == 64);
  CHECK(summary["parameters"]["variables"]["code"].size() == 3);
  CHECK(summary["metrics"]["runs_failed"] == 1);
  CHECK(summary["metrics"]["runs"][2]["exit_codes"]["first"] == 5);
  CHECK(summary["metrics"]["runs"][2]["exit_codes"]["second"].is_null());
  CHECK(summary["metrics"]["runs"][1]["variables"]["code"] == 3);
  CHECK(summary["metrics"]["csv"][0]["rows"] == 3);
  CHECK(summary.contains("wall_time_s"));
}

TEST_CASE("runner: a select entry writes its table and line, prints the line and lists it in the summary", "[pipeline]") {
  TempDir tmp("runner_select");
  write_fake_stages(tmp.path() / "bin");
  // Each run reports a "seal" of value - 2 (value 1..4): the smallest value with seal >= 1 is 3.
  const auto spec = write_and_load(tmp.path(), R"({
    "variables": {"size": [4, 1, 3, 2]},
    "steps": [{"name": "report", "stage": "valve-report", "args": ["${size}"]}],
    "gather": [{"csv": "sizes.csv", "summary": "report.summary.json",
                "columns": {"size": "${size}", "value": "summary:value",
                            "seal": {"min": ["summary:value", "summary:value"]}}}],
    "select": [{"csv": "choice.csv", "from": "sizes.csv", "group_by": [], "at_least": {"value": 3},
                "minimize": ["size"]}]
  })");
  RunnerOptions options = fake_stage_options(tmp.path());
  const PipelineOutcome result = run_pipeline(spec, options);
  REQUIRE(result.exit_code == 0);
  REQUIRE(result.selects.size() == 1);
  const fs::path out = tmp.path() / "out";
  CHECK(read_text(out / "choice.csv") == "found,size,value,seal\ntrue,3,3,3\n");
  CHECK(read_text(out / "choice.txt") == "choice.csv: smallest size with value >= 3: size 3\n");
  CHECK_THAT(pipeline_outcome_line(result), Catch::EndsWith("\nvalve-pipeline: choice.csv: smallest size with value >= 3: size 3"));
  const ojson summary = ojson::parse(read_text(out / "pipeline.summary.json"));
  const ojson& listed = summary["metrics"]["csv"].back();
  CHECK(listed["kind"] == "select");
  CHECK(listed["line"] == "choice.csv: smallest size with value >= 3: size 3");
  CHECK(listed["rows"] == 1);
}

TEST_CASE("runner: stage names cannot carry placeholders, broken and killed stages", "[pipeline]") {
  TempDir tmp("killed");
  write_fake_stages(tmp.path() / "bin");
  CHECK_THROWS_WITH(write_and_load(tmp.path(), R"({"variables": {"w": ["a"]}, "steps": [{"stage": "valve-${w}", "args": []}]})"),
                    Catch::Contains("steps[0].stage: expected a stage name valve-<name>"));
  const auto spec = write_and_load(tmp.path(), R"({
    "steps": [{"name": "a", "stage": "valve-broken", "args": []}]})");
  RunnerOptions options = fake_stage_options(tmp.path());
  const auto broken = run_pipeline(spec, options);
  CHECK(broken.exit_code == 3);
  CHECK(broken.runs[0].steps[0].exit_code == 127);
  CHECK_THAT(broken.runs[0].steps[0].error, Catch::Contains("cannot start"));
  CHECK_THAT(read_text(tmp.path() / "out/runs/single/a.log"), Catch::Contains("cannot start"));

  const auto killed_spec = write_and_load(tmp.path(), R"({
    "steps": [{"name": "k", "stage": "valve-suicide", "args": [], "allow_exit": [0, 137]}]})");
  const auto killed = run_pipeline(killed_spec, options);
  CHECK(killed.exit_code == 3);  // a signal is never an allowed exit
  CHECK(killed.runs[0].steps[0].exit_code == 137);
  CHECK_THAT(killed.runs[0].reason, Catch::Contains("killed by signal 9"));
}

TEST_CASE("runner: a missing stage is rejected before anything is written", "[pipeline]") {
  TempDir tmp("missing");
  const auto spec = write_and_load(tmp.path(), R"({"steps": [
    {"stage": "valve-exit", "args": ["0"]}, {"stage": "valve-no-such-stage-here", "args": []}]})");
  RunnerOptions options = fake_stage_options(tmp.path());
  write_fake_stages(tmp.path() / "bin");
  CHECK_THROWS_AS(run_pipeline(spec, options), InputError);
  CHECK_THROWS_WITH(run_pipeline(spec, options),
                    Catch::StartsWith((tmp.path() / "P.json").string() + ": steps[1].stage: expected an executable valve-no-such-stage-here"));
  CHECK_FALSE(fs::exists(options.out_dir));
}

TEST_CASE("runner: --jobs runs several runs at once, one job runs them one by one", "[pipeline]") {
  TempDir tmp("jobs");
  write_fake_stages(tmp.path() / "bin");
  for (int jobs : {1, 2}) {
    const fs::path shared = tmp.path() / ("shared" + std::to_string(jobs));
    fs::create_directories(shared);
    const auto spec = write_and_load(tmp.path(), R"({"variables": {"k": [1, 2]},
      "steps": [{"stage": "valve-crowd", "args": [")" + shared.string() + R"("]}]})");
    RunnerOptions options;
    options.out_dir = tmp.path() / ("out" + std::to_string(jobs));
    options.stage_dirs = {tmp.path() / "bin"};
    options.jobs = jobs;
    const auto result = run_pipeline(spec, options);
    REQUIRE(result.exit_code == 0);
    // The first run counts the runs started before it finished: 1 alone, 2 in parallel.
    const std::string crowd = read_text(options.out_dir / "runs/k-1/crowd.txt");
    CHECK(std::stoi(crowd) == jobs);
  }
}

TEST_CASE("runner: each run starts from an empty folder", "[pipeline]") {
  TempDir tmp("stale");
  write_fake_stages(tmp.path() / "bin");
  const auto spec = write_and_load(tmp.path(), R"({"steps": [{"stage": "valve-exit", "args": ["0"]}],
    "gather": [{"csv": "t.csv", "summary": "report.summary.json", "columns": {"v": "summary:value"}}]})");
  RunnerOptions options = fake_stage_options(tmp.path());
  // A summary left by an earlier invocation must not be gathered as if this run made it.
  write_text(options.out_dir / "runs/single/report.summary.json", R"({"value": 99})");
  write_text(options.out_dir / "unrelated.txt", "kept");
  const auto result = run_pipeline(spec, options);
  CHECK(result.exit_code == 0);
  CHECK(read_text(options.out_dir / "t.csv") == "v\n\n");
  CHECK(fs::exists(options.out_dir / "unrelated.txt"));
}

TEST_CASE("process: stage lookup order and shell quoting", "[pipeline]") {
  TempDir tmp("lookup");
  write_fake_stages(tmp.path() / "a");
  write_fake_stages(tmp.path() / "b");
  write_text(tmp.path() / "c/valve-exit", "not executable");
  CHECK(find_stage("valve-exit", {tmp.path() / "c", tmp.path() / "b", tmp.path() / "a"}) == tmp.path() / "b/valve-exit");
  CHECK_FALSE(find_stage("valve-exit", {tmp.path() / "c"}).has_value());
  CHECK(find_on_path("sh").has_value());
  CHECK(shell_quote({"a", "b c", "it's", "x=1,2", ""}) == "a 'b c' 'it'\\''s' x=1,2 ''");
  const auto dirs = default_stage_dirs({tmp.path()});
  REQUIRE(dirs.size() >= 2);
  CHECK(dirs[0] == tmp.path());
  CHECK(dirs[1] == executable_directory());
}

TEST_CASE("runner: unchanged steps are cached, changed inputs and failures rerun, --force reruns all", "[pipeline]") {
  TempDir tmp("cache");
  const fs::path bin = tmp.path() / "bin", data = tmp.path() / "data.txt", scene = tmp.path() / "scene.txt";
  // valve-touch NAME SCENE --out D: counts its starts in counts/NAME; SCENE holds the path of
  // a data file that only the stage's summary names (like a scene naming its mesh); fails
  // when the data reads "fail".
  write_script(bin / "valve-touch",
               "echo x >> \"" + (tmp.path() / "counts").string() + "/$1\"; d=$(cat \"$2\"); "
               "[ \"$(cat \"$d\")\" = fail ] && exit 4; mkdir -p \"$4\"; "
               "printf '{\"status\": \"ok\", \"inputs\": [{\"path\": \"%s\"}]}\\n' \"$d\" > \"$4/touch.summary.json\"");
  fs::create_directories(tmp.path() / "counts");
  write_text(data, "one");
  write_text(scene, data.string());
  const auto spec = write_and_load(tmp.path(), R"({"steps": [
    {"name": "a", "stage": "valve-touch", "args": ["a", ")" + scene.string() + R"(", "--out", "${run_dir}/a"]},
    {"name": "b", "stage": "valve-touch", "args": ["b", ")" + scene.string() + R"(", "--out", "${run_dir}/b"]}]})");
  RunnerOptions options;
  options.out_dir = tmp.path() / "out";
  options.stage_dirs = {bin};
  auto starts = [&](const std::string& name) {
    const std::string text = read_text(tmp.path() / "counts" / name);
    return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  };
  auto statuses = [](const PipelineOutcome& r) { return r.runs[0].steps[0].status + "," + r.runs[0].steps[1].status; };

  REQUIRE(run_pipeline(spec, options).exit_code == 0);
  CHECK(starts("a") == 1);
  CHECK(starts("b") == 1);
  const auto again = run_pipeline(spec, options);
  CHECK(again.exit_code == 0);
  CHECK(statuses(again) == "cached,cached");
  CHECK(starts("a") == 1);  // nothing ran
  CHECK(fs::exists(options.out_dir / "runs/single/b/touch.summary.json"));

  // The stamp records the file the summary names; changing it reruns both steps.
  const ojson prov = ojson::parse(read_text(options.out_dir / "provenance.json"));
  CHECK(prov["tool"]["version"] == VALVE_TEST_VERSION);
  CHECK(prov["pipeline"]["sha256"].get<std::string>().size() == 64);
  bool names_data = false;
  for (const auto& in : prov["runs"][0]["steps"][0]["inputs"]) names_data |= in["path"] == data.string();
  CHECK(names_data);
  write_text(data, "two");
  CHECK(plan_runs(expand_runs(spec, options.out_dir), {"x", "x"}, false)[0][0].value() == "command or stage changed");
  const auto changed = run_pipeline(spec, options);
  CHECK(statuses(changed) == "ok,ok");
  CHECK(changed.runs[0].steps[0].run_reason == "input " + data.string() + " changed");
  CHECK(changed.runs[0].steps[1].run_reason == "an earlier step runs");
  CHECK(starts("a") == 2);

  // A failure leaves no stamp and no stale output; the next invocation resumes there.
  write_text(data, "fail");
  const auto failed = run_pipeline(spec, options);
  CHECK(failed.exit_code == 3);
  CHECK(statuses(failed) == "failed,skipped");
  CHECK_FALSE(fs::exists(options.out_dir / "runs/single/a/touch.summary.json"));
  write_text(data, "two");  // back to what b last saw: a reruns (it failed), b follows it
  const auto resumed = run_pipeline(spec, options);
  CHECK(statuses(resumed) == "ok,ok");
  CHECK(resumed.runs[0].steps[0].run_reason == "never ran");

  options.force = true;
  CHECK(statuses(run_pipeline(spec, options)) == "ok,ok");
  CHECK(starts("a") == 5);
  CHECK(starts("b") == 4);
  const std::string log = read_text(options.out_dir / "pipeline.log");
  CHECK_THAT(log, Catch::Contains("run single step a cached"));
  CHECK_THAT(log, Catch::Contains("step a failed exit 4"));
  CHECK_THAT(log, Catch::Contains("(forced)"));
}

TEST_CASE("runner: required pipelines run first, cached like any other, and a failure stops the rest", "[pipeline]") {
  TempDir tmp("required");
  write_fake_stages(tmp.path() / "bin");
  // valve-make TEXT: writes TEXT to made.txt; valve-readback FILE: reports FILE's number.
  write_script(tmp.path() / "bin" / "valve-make", "echo \"$1\" > made.txt");
  write_script(tmp.path() / "bin" / "valve-readback",
               "printf '{\"status\": \"ok\", \"value\": %s}\\n' \"$(cat \"$1\")\" > report.summary.json");
  write_text(tmp.path() / "up.json", R"({"variables": {"n": [1, 2]},
    "steps": [{"stage": "valve-make", "args": ["${n}0"]}]})");
  const auto spec = write_and_load(tmp.path(), R"({
    "requires": [{"pipeline": "up.json", "out": "upstream"}],
    "steps": [{"stage": "valve-readback", "args": ["${out_dir}/upstream/runs/n-2/made.txt"]}],
    "gather": [{"csv": "values.csv", "summary": "report.summary.json", "columns": {"value": "summary:value"}}]
  })");
  REQUIRE(spec.required.size() == 1);
  CHECK(spec.required[0].spec->steps.size() == 1);
  RunnerOptions options = fake_stage_options(tmp.path());
  options.only_runs = {"single"};  // names a run of this pipeline, not of up.json
  const PipelineOutcome first = run_pipeline(spec, options);
  CHECK(first.status == "ok");
  CHECK(read_text(tmp.path() / "out/values.csv") == "value\n20\n");
  CHECK(read_text(tmp.path() / "out/upstream/runs/n-1/made.txt") == "10\n");  // every upstream run ran
  const ojson summary = ojson::parse(read_text(tmp.path() / "out/pipeline.summary.json"));
  CHECK(summary["metrics"]["required"][0]["status"] == "ok");
  CHECK(ojson::parse(read_text(tmp.path() / "out/upstream/pipeline.summary.json"))["status"] == "ok");
  const ojson provenance = ojson::parse(read_text(tmp.path() / "out/provenance.json"));
  CHECK_THAT(provenance["required"][0]["file"].get<std::string>(), Catch::EndsWith("up.json"));
  CHECK(provenance["required"][0]["sha256"].get<std::string>().size() == 64);
  CHECK_THAT(provenance["required"][0]["out"].get<std::string>(), Catch::EndsWith("out/upstream"));

  // Again: the upstream steps are cached.
  const PipelineOutcome second = run_pipeline(spec, options);
  CHECK(second.status == "ok");
  const std::string upstream_log = read_text(tmp.path() / "out/upstream/pipeline.log");
  CHECK(std::count(upstream_log.begin(), upstream_log.end(), '\n') == 4);
  CHECK_THAT(upstream_log, Catch::Contains("run n-2 step valve-make cached"));

  // An upstream failure: no run of the requiring pipeline starts.
  write_text(tmp.path() / "bad.json", R"({"steps": [{"stage": "valve-exit", "args": ["5"]}]})");
  const auto failing = write_and_load(tmp.path(), R"({
    "requires": [{"pipeline": "bad.json", "out": "bad"}],
    "steps": [{"stage": "valve-report", "args": ["1"]}]})");
  options.out_dir = tmp.path() / "out_failing";
  options.only_runs.clear();
  const PipelineOutcome failed = run_pipeline(failing, options);
  CHECK(failed.exit_code == 3);
  CHECK_THAT(failed.reason, Catch::Contains("requires[0]") && Catch::Contains("bad.json") &&
                                Catch::Contains("out_failing/bad") && Catch::Contains("exited with 5") &&
                                Catch::Contains("no run of this pipeline started"));
  REQUIRE(failed.runs.size() == 1);
  CHECK_FALSE(failed.runs[0].ok);
  CHECK_THAT(failed.runs[0].reason, Catch::Contains("not started"));
  CHECK_FALSE(fs::exists(tmp.path() / "out_failing/runs"));
  const ojson failed_summary = ojson::parse(read_text(tmp.path() / "out_failing/pipeline.summary.json"));
  CHECK(failed_summary["status"] == "failed");
  CHECK(failed_summary["metrics"]["required"][0]["status"] == "failed");
  CHECK(failed_summary["metrics"]["runs_failed"] == 1);
  // The same metrics as a summary of a pipeline whose runs ran.
  std::vector<std::string> keys_ok, keys_failed;
  for (auto it = summary["metrics"].begin(); it != summary["metrics"].end(); ++it) keys_ok.push_back(it.key());
  for (auto it = failed_summary["metrics"].begin(); it != failed_summary["metrics"].end(); ++it) keys_failed.push_back(it.key());
  CHECK(keys_ok == keys_failed);
}

TEST_CASE("pipeline spec: requires is checked with the file, cycles and misplaced folders rejected", "[pipeline]") {
  TempDir tmp("requires_spec");
  write_text(tmp.path() / "up.json", R"({"steps": [{"stage": "valve-make", "args": []}]})");
  const auto message = [&](const std::string& text) {
    try {
      write_and_load(tmp.path(), text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string step = R"("steps": [{"stage": "valve-make", "args": []}])";
  CHECK(message(R"({"requires": [{"pipeline": "up.json", "out": "up"}], )" + step + "}") == "(no error)");
  CHECK_THAT(message(R"({"requires": [{"pipeline": "absent.json", "out": "up"}], )" + step + "}"),
             Catch::Contains("P.json") && Catch::Contains("requires[0].pipeline") && Catch::Contains("absent.json"));
  for (const std::string out : {"runs", "runs/x", "../up", "/tmp/up", "pipeline.summary.json", ".", "./", "a/..",
                                 "pipeline.log", "provenance.json"})
    CHECK_THAT(message(R"({"requires": [{"pipeline": "up.json", "out": ")" + out + R"("}], )" + step + "}"),
               Catch::Contains("requires[0].out"));
  CHECK_THAT(message(R"({"requires": [{"pipeline": "up.json", "out": "up"}, {"pipeline": "up.json", "out": "up/inner"}], )" +
                     step + "}"),
             Catch::Contains("requires[1].out") && Catch::Contains("requires[0]"));
  CHECK_THAT(message(R"({"requires": [{"pipeline": "up.json", "out": "tables"}], )" + step +
                     R"(, "gather": [{"csv": "tables/a.csv", "summary": "s.json", "columns": {"a": "1"}}]})"),
             Catch::Contains("requires[0].out") && Catch::Contains("tables/a.csv"));
  CHECK_THAT(message(R"({"requires": [{"pipeline": "up.json", "out": "up", "jobs": 2}], )" + step + "}"),
             Catch::Contains("requires[0].jobs"));
  CHECK_THAT(message(R"({"requires": {"pipeline": "up.json"}, )" + step + "}"), Catch::Contains("requires: expected a list"));
  // P requires Q requires P; P requires itself.
  write_text(tmp.path() / "Q.json", R"({"requires": [{"pipeline": "P.json", "out": "p"}], )" + step + "}");
  CHECK_THAT(message(R"({"requires": [{"pipeline": "Q.json", "out": "q"}], )" + step + "}"),
             Catch::Contains("Q.json") && Catch::Contains("requires[0].pipeline") && Catch::Contains("cycle P.json -> Q.json -> P.json"));
  CHECK_THAT(message(R"({"requires": [{"pipeline": "./P.json", "out": "p"}], )" + step + "}"),
             Catch::Contains("cycle P.json -> P.json"));
  // A symbolic link to this file is this file.
  fs::create_symlink(tmp.path() / "P.json", tmp.path() / "link.json");
  CHECK_THAT(message(R"({"requires": [{"pipeline": "link.json", "out": "p"}], )" + step + "}"),
             Catch::Contains("requires[0].pipeline") && Catch::Contains("cycle P.json -> link.json"));
  // A mistake inside the required file is reported with its own name.
  write_text(tmp.path() / "broken.json", R"({"steps": []})");
  CHECK_THAT(message(R"({"requires": [{"pipeline": "broken.json", "out": "b"}], )" + step + "}"),
             Catch::Contains("broken.json: steps"));
}

TEST_CASE("runner: shared steps run once for all runs, and a rerun of one reruns every run", "[pipeline]") {
  TempDir tmp("shared");
  write_fake_stages(tmp.path() / "bin");
  // valve-prep COUNTER --out DIR: one line more in COUNTER per invocation, DIR/value.txt = 7.
  write_script(tmp.path() / "bin" / "valve-prep", "echo ran >> \"$1\"; mkdir -p \"$3\"; echo 7 > \"$3/value.txt\"; "
                                                  "echo '{\"made\": 1}' > \"$3/prep.json\"");
  // valve-use FILE K --out DIR: DIR/use.summary.json with value = FILE's number times K.
  write_script(tmp.path() / "bin" / "valve-use",
               "mkdir -p \"$4\"; printf '{\"value\": %s}\\n' \"$(( $(cat \"$1\") * $2 ))\" > \"$4/use.summary.json\"");
  const fs::path counter = tmp.path() / "counter.txt";
  write_text(counter, "");
  const auto spec = write_and_load(tmp.path(), R"({"variables": {"k": [1, 2, 3]},
    "steps": [{"name": "prep", "stage": "valve-prep", "args": [")" + counter.string() + R"(", "--out", "${run_dir}/prep"]},
              {"name": "use", "stage": "valve-use", "args": ["${run_dir}/prep/value.txt", "${k}", "--out", "${run_dir}/use"]}],
    "gather": [{"csv": "t.csv", "summary": "use/use.summary.json",
                "columns": {"k": "${k}", "value": "summary:value", "prep": "file:prep/prep.json:made"}}]})");
  RunnerOptions options = fake_stage_options(tmp.path());
  auto lines = [](const std::string& text, const std::string& word) {
    size_t n = 0;
    for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
    return n;
  };

  const PipelineOutcome first = run_pipeline(spec, options);
  REQUIRE(first.exit_code == 0);
  CHECK(lines(read_text(counter), "ran") == 1);
  CHECK(read_text(options.out_dir / "t.csv") == "k,value,prep\n1,7,1\n2,14,1\n3,21,1\n");
  CHECK(fs::exists(options.out_dir / "shared/prep/value.txt"));
  CHECK_FALSE(fs::exists(options.out_dir / "runs/k-1/prep"));
  REQUIRE(first.shared);
  CHECK(first.shared->steps.at(0).status == "ok");

  // Nothing changed: all cached.
  const PipelineOutcome second = run_pipeline(spec, options);
  REQUIRE(second.exit_code == 0);
  CHECK(lines(read_text(counter), "ran") == 1);
  CHECK(second.shared->steps.at(0).status == "cached");
  for (const auto& run : second.runs) CHECK(run.steps.at(0).status == "cached");

  // The shared step's input changed: it runs again, and so does every step of every run.
  write_text(counter, read_text(counter) + "edited\n");
  const PipelineOutcome third = run_pipeline(spec, options);
  REQUIRE(third.exit_code == 0);
  CHECK(lines(read_text(counter), "ran") == 2);
  for (const auto& run : third.runs) {
    CHECK(run.steps.at(0).status == "ok");
    CHECK(run.steps.at(0).run_reason == "a shared step ran");
  }

  // A failing shared step: no run starts.
  const auto failing = write_and_load(tmp.path(), R"({"variables": {"k": [1, 2]},
    "steps": [{"name": "x", "stage": "valve-exit", "args": ["5", "--out", "${run_dir}/x"]},
              {"name": "r", "stage": "valve-report", "args": ["${k}"]}]})");
  options.out_dir = tmp.path() / "out_failing";
  const PipelineOutcome failed = run_pipeline(failing, options);
  CHECK(failed.exit_code == 3);
  CHECK_THAT(failed.reason, Catch::Contains("the shared steps failed"));
  REQUIRE(failed.runs.size() == 2);
  CHECK(failed.runs[0].reason == "not started: a shared step failed");
  CHECK_FALSE(fs::exists(options.out_dir / "runs/k-1/report.summary.json"));
}

TEST_CASE("snakemake export: a rule waits for the steps whose folders its arguments name", "[pipeline]") {
  TempDir tmp("snakefile");
  write_fake_stages(tmp.path() / "bin");
  const auto spec = write_and_load(tmp.path(), R"({"steps": [
    {"name": "a", "stage": "valve-exit", "args": ["0", "--out", "m"]},
    {"name": "b", "stage": "valve-report", "args": ["m/x.json"]},
    {"name": "c", "stage": "valve-report", "args": ["--set", "file=${run_dir}/m/y.json"]},
    {"name": "d", "stage": "valve-report", "args": ["m2/x.json", "--out", "${run_dir}/m2"]},
    {"name": "e", "stage": "valve-report", "args": ["{\"k\": 1}"], "resources": {"threads": 3, "mem_mb": 100, "runtime": 7}}]})");
  const fs::path out = tmp.path() / "out";
  const std::string text = snakefile_text(spec, out, {tmp.path() / "bin"}, "/bin/valve-pipeline");
  auto rule = [&](const std::string& name) {
    const auto at = text.find("rule " + name + ":\n");
    REQUIRE(at != std::string::npos);
    return text.substr(at, text.find("\nrule ", at + 1) - at);
  };
  const std::string stamp_a = step_stamp_path(out / "runs/single", "a").string();
  CHECK(rule("a__single").find("input:") == std::string::npos);
  CHECK_THAT(rule("b__single"), Catch::Contains("\"" + stamp_a + "\""));
  CHECK_THAT(rule("c__single"), Catch::Contains("\"" + stamp_a + "\""));
  CHECK_THAT(rule("d__single"), !Catch::Contains(stamp_a));  // m2 is not m
  // Resources, and the braces of an argument doubled for snakemake's str.format.
  CHECK_THAT(rule("e__single"), Catch::Contains("threads: 3\n") && Catch::Contains("mem_mb=100, runtime=7\n") &&
                                    Catch::Contains("{{") && Catch::Contains("{params.stage_sha256}") &&
                                    Catch::Contains("VALVE_THREADS={threads} "));
  CHECK_THAT(text, Catch::Contains("rule all:\n    input:\n        \"" + step_stamp_path(out / "runs/single", "a").string()));
}
