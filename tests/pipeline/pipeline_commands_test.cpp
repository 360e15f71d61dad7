// valve-pipeline's commands on fake sh stages: the command line's shape, list, the dry run,
// stamp, tables and the closing line of run.
#include "valve/pipeline/pipeline_commands.hpp"

#include <catch2/catch.hpp>

#include <sstream>

#include "pipeline_test_support.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/step_cache.hpp"

using namespace valve;
using valve::test::read_text;
using valve::test::TempDir;
using valve::test::write_script;
using valve::test::write_text;
namespace fs = std::filesystem;

namespace {

CommandLine command_line(std::vector<std::string> words) {
  words.insert(words.begin(), "valve-pipeline");
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  return CommandLine(static_cast<int>(argv.size()), argv.data(),
                     {"out", "jobs", "stage-dir", "run", "step", "exit-code", "stage-sha256"},
                     {"quiet", "force", "dry-run", "snakemake"});
}

std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Two runs (n = 1, 2) of one step each; valve-report writes the summary the gather reads.
struct FakePipeline {
  TempDir tmp{"commands"};
  PipelineSpec spec;
  FakePipeline() {
    write_script(tmp.path() / "bin" / "valve-report",
                 "printf '{\"status\": \"ok\", \"value\": %s}\\n' \"$1\" > report.summary.json");
    write_text(tmp.path() / "P.json", R"({
      "variables": {"n": [1, 2]},
      "steps": [{"name": "report", "stage": "valve-report", "args": ["${n}"]}],
      "gather": [{"csv": "values.csv", "summary": "report.summary.json", "columns": {"n": "${n}", "value": "summary:value"}}]
    })");
    spec = load_pipeline(tmp.path() / "P.json");
  }
  RunnerOptions options() const {
    RunnerOptions o;
    o.out_dir = tmp.path() / "out";
    o.stage_dirs = {tmp.path() / "bin"};
    return o;
  }
  fs::path bin() const { return tmp.path() / "bin"; }
};

}  // namespace

TEST_CASE("pipeline commands: the command line's shape, --jobs and --stage-dir", "[pipeline]") {
  CHECK(pipeline_command(command_line({"run", "P.json"})) == "run");
  CHECK(pipeline_command(command_line({"export", "P.json", "--snakemake"})) == "export");
  CHECK(error_of([] { pipeline_command(command_line({"launch", "P.json"})); }) ==
        "valve-pipeline: command: expected \"run P.json\", \"list P.json\" or \"export --snakemake P.json\", found 2 "
        "positional argument(s) starting with \"launch\"");
  CHECK_THAT(error_of([] { pipeline_command(command_line({})); }), Catch::EndsWith("found 0 positional argument(s)"));
  CHECK(error_of([] { pipeline_command(command_line({"export", "P.json"})); }) ==
        "valve-pipeline: export: expected the format --snakemake, found none");
  CHECK_THAT(error_of([] { pipeline_command(command_line({"export", "P.json", "--snakemake", "--force"})); }),
             Catch::EndsWith("found --force"));
  CHECK_THAT(error_of([] { pipeline_command(command_line({"export", "P.json", "--snakemake", "--run", "x"})); }),
             Catch::EndsWith("found --run"));

  CHECK(pipeline_jobs(command_line({"run", "P.json"})) == 1);
  CHECK(pipeline_jobs(command_line({"run", "P.json", "--jobs", "1024"})) == 1024);
  for (const char* bad : {"0", "1025", "3x", ""})
    CHECK(error_of([&] { pipeline_jobs(command_line({"run", "P.json", "--jobs", bad})); }) ==
          std::string("valve-pipeline: --jobs: expected an integer in [1, 1024], found \"") + bad + "\"");

  TempDir tmp("stage_dirs");
  const auto dirs = pipeline_stage_dirs(command_line({"run", "P.json", "--stage-dir", tmp.path().string()}));
  REQUIRE(dirs.size() == 1);
  CHECK(dirs[0] == tmp.path());
  CHECK_THAT(error_of([&] { pipeline_stage_dirs(command_line({"run", "P.json", "--stage-dir", (tmp.path() / "none").string()})); }),
             Catch::Contains("--stage-dir: expected a folder of stage executables, found no such folder"));
}

TEST_CASE("pipeline commands: list shows each run's command, under $OUT without --out", "[pipeline]") {
  FakePipeline p;
  const std::string exe = (p.bin() / "valve-report").string();
  std::ostringstream text;
  CHECK(list_pipeline(p.spec, command_line({"list", "P.json", "--stage-dir", p.bin().string()}), text) == 0);
  CHECK(text.str() == "pipeline P (" + p.spec.file + "): 2 run(s), grid over n (2), 1 step(s) each\n"
                      "# OUT stands for the --out folder\n"
                      "run n-1\n  [report] " + exe + " 1\n"
                      "run n-2\n  [report] " + exe + " 2\n"
                      "gather $OUT/values.csv from runs/*/report.summary.json\n");
  std::ostringstream with_out;
  list_pipeline(p.spec, command_line({"list", "P.json", "--stage-dir", p.bin().string(), "--out", "/study"}), with_out);
  CHECK_THAT(with_out.str(), Catch::Contains("gather /study/values.csv from"));
  CHECK_THAT(with_out.str(), !Catch::Contains("$OUT"));
}

TEST_CASE("pipeline commands: a dry run counts the steps to run, then none after a run", "[pipeline]") {
  FakePipeline p;
  std::ostringstream before;
  dry_run_pipeline(p.spec, p.options(), before);
  CHECK_THAT(before.str(), Catch::Contains("run n-1\n  [report] run: "));
  CHECK_THAT(before.str(), Catch::EndsWith("dry run: 2 step(s) would run, 0 cached\n"));
  CHECK_FALSE(fs::exists(p.options().out_dir));

  REQUIRE(run_pipeline(p.spec, p.options()).exit_code == 0);
  std::ostringstream after;
  RunnerOptions one = p.options();
  one.only_runs = {"n-2"};
  dry_run_pipeline(p.spec, one, after);
  CHECK(after.str() == "run n-2\n  [report] cached\ndry run: 0 step(s) would run, 1 cached\n");
  one.only_runs = {"n-3"};
  CHECK_THAT(error_of([&] { dry_run_pipeline(p.spec, one, after); }), Catch::Contains("n-3"));
}

TEST_CASE("pipeline commands: stamp writes the step's stamp only for an allowed exit code", "[pipeline]") {
  FakePipeline p;
  const std::string out = p.options().out_dir.string();
  const std::string sha(64, 'a');
  const fs::path stamp = step_stamp_path(p.options().out_dir / "runs" / "n-1", "report");
  auto stamp_with = [&](const std::string& code, const std::string& hash) {
    return stamp_pipeline_step(p.spec, command_line({"stamp", "P.json", "--out", out, "--run", "n-1", "--step", "report",
                                                     "--exit-code", code, "--stage-sha256", hash}));
  };
  CHECK(stamp_with("1", sha) == 3);  // allow_exit defaults to [0]
  CHECK_FALSE(fs::exists(stamp));
  CHECK(error_of([&] { stamp_with("0", "ABC"); }) ==
        "valve-pipeline: --stage-sha256: expected 64 lowercase hex digits, found \"ABC\"");
  CHECK(error_of([&] { stamp_with("256", sha); }) ==
        "valve-pipeline: --exit-code: expected an integer in [0, 255], found \"256\"");
  CHECK(error_of([&] {
          stamp_pipeline_step(p.spec, command_line({"stamp", "P.json", "--out", out, "--run", "n-1", "--step", "mesh"}));
        }) == "valve-pipeline: --step: expected a step of run n-1, found \"mesh\"");
  CHECK(stamp_with("0", sha) == 0);
  CHECK(fs::is_regular_file(stamp));
}

TEST_CASE("pipeline commands: tables are written again from the run folders", "[pipeline]") {
  FakePipeline p;
  REQUIRE(run_pipeline(p.spec, p.options()).exit_code == 0);
  const fs::path csv = p.options().out_dir / "values.csv";
  fs::remove(csv);
  RunnerOptions loud = p.options();
  loud.quiet = false;
  std::ostringstream text;
  CHECK(write_pipeline_tables(p.spec, loud, text) == 0);
  CHECK(text.str() == "valve-pipeline: wrote " + csv.string() + " (2 rows)\n");
  CHECK_THAT(read_text(csv), Catch::EndsWith("\n1,1\n2,2\n"));
  CHECK(fs::is_regular_file(p.options().out_dir / "provenance.json"));
}

TEST_CASE("pipeline commands: run's closing line counts ok runs and cached steps", "[pipeline]") {
  PipelineOutcome outcome;
  outcome.runs.resize(3);
  outcome.runs[0].ok = outcome.runs[2].ok = true;
  outcome.runs[0].steps = {{"a", "cached"}, {"b", "ok"}};
  outcome.runs[1].steps = {{"a", "cached"}, {"b", "failed"}};
  outcome.runs[2].steps = {{"a", "ok"}, {"b", "ok"}};
  GatherResult table;
  table.path = "/out/values.csv";
  table.rows = 2;
  outcome.tables.push_back(table);
  PlotResult plot;
  plot.png = "values.png";
  plot.status = "skipped";
  outcome.plots.push_back(plot);
  CHECK(pipeline_outcome_line(outcome) ==
        "valve-pipeline: 2/3 runs ok, 2 step(s) cached; wrote values.csv (2 rows); plot values.png skipped");
}
