#include "valve/pipeline/pipeline_spec.hpp"

#include <catch2/catch.hpp>

#include "pipeline_test_support.hpp"
#include <set>

#include "valve/core/error.hpp"

using namespace valve;
using valve::test::message_of;
using valve::test::parse;
namespace fs = std::filesystem;

namespace {


// A pipeline with the given variables (JSON object text) and one step using `args`.
std::string with_variables(const std::string& variables, const std::string& args = R"(["--out", "${run_dir}"])",
                           const std::string& extra = "") {
  return R"({"variables": )" + variables + extra + R"(, "steps": [{"stage": "valve-generate", "args": )" + args +
         "}]}";
}


std::vector<std::string> texts(const SweepVariable& v) {
  std::vector<std::string> out;
  for (const auto& x : v.values) out.push_back(value_text(x));
  return out;
}

}  // namespace

TEST_CASE("grid sweep: one run per combination, first variable slowest", "[pipeline]") {
  const auto spec = parse(with_variables(R"({"a": [1, 2, 3], "b": ["x", "y"], "c": {"range": [1, 4]}})"));
  const auto runs = expand_sweep(spec.variables, spec.sweep);
  REQUIRE(runs.size() == 3 * 2 * 4);
  CHECK(runs.front() == ojson::parse(R"({"a": 1, "b": "x", "c": 1})"));
  CHECK(runs[1] == ojson::parse(R"({"a": 1, "b": "x", "c": 2})"));
  CHECK(runs[4] == ojson::parse(R"({"a": 1, "b": "y", "c": 1})"));
  CHECK(runs.back() == ojson::parse(R"({"a": 3, "b": "y", "c": 4})"));
  std::set<std::string> distinct;
  for (const auto& r : runs) distinct.insert(r.dump());
  CHECK(distinct.size() == runs.size());
  // Variable order is the file's order, not alphabetical.
  CHECK(runs.front().begin().key() == "a");
}

TEST_CASE("zip sweep: the k-th values are taken together", "[pipeline]") {
  const auto spec = parse(with_variables(R"({"angle": [0, 45, 90], "mesh": {"range": [5, 7]}})", R"(["${angle}"])",
                                         R"(, "sweep": "zip")"));
  const auto runs = expand_sweep(spec.variables, spec.sweep);
  REQUIRE(runs.size() == 3);
  CHECK(runs[0] == ojson::parse(R"({"angle": 0, "mesh": 5})"));
  CHECK(runs[2] == ojson::parse(R"({"angle": 90, "mesh": 7})"));
}

TEST_CASE("no variables: one run called single", "[pipeline]") {
  const auto spec = parse(R"({"steps": [{"stage": "valve-generate", "args": []}]})");
  const auto runs = expand_runs(spec, "/tmp/out");
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].run_id == "single");
  CHECK(runs[0].run_dir == fs::path("/tmp/out/runs/single"));
  CHECK(spec.name == "P");  // the file stem
}

TEST_CASE("ranges: inclusive ends, steps, descending, decimals", "[pipeline]") {
  auto var = [](const std::string& range) { return parse(with_variables(R"({"x": {"range": )" + range + "}}")).variables[0]; };
  CHECK(texts(var("[1, 10]")) == std::vector<std::string>{"1", "2", "3", "4", "5", "6", "7", "8", "9", "10"});
  CHECK(var("[1, 10]").values[0].is_number_integer());
  CHECK(texts(var("[0, 10, 5]")) == std::vector<std::string>{"0", "5", "10"});
  CHECK(texts(var("[0, 9, 4]")) == std::vector<std::string>{"0", "4", "8"});
  CHECK(texts(var("[3, 1]")) == std::vector<std::string>{"3", "2", "1"});
  CHECK(texts(var("[10, 0, -5]")) == std::vector<std::string>{"10", "5", "0"});
  CHECK(texts(var("[0, 0.3, 0.1]")) == std::vector<std::string>{"0", "0.1", "0.2", "0.3"});
  CHECK(texts(var("[0.5, 1.5, 0.25]")) == std::vector<std::string>{"0.5", "0.75", "1", "1.25", "1.5"});
  CHECK(texts(var("[2, 2]")) == std::vector<std::string>{"2"});
  CHECK_THROWS_WITH(var("[0, 1, 0]"), Catch::Contains("variables.x.range: expected a nonzero step"));
  CHECK_THROWS_WITH(var("[0, 10, -1]"), Catch::Contains("expected a step that moves from a towards b"));
  CHECK_THROWS_WITH(var("[0]"), Catch::Contains("expected [a, b] or [a, b, step]"));
  CHECK_THROWS_WITH(var(R"([0, "10"])"), Catch::Contains("expected finite numbers"));
  CHECK_THROWS_WITH(var("[0, 1e9]"), Catch::Contains("expected at most 100000 values"));
}

TEST_CASE("numbers substitute in shortest round-trip form", "[pipeline]") {
  CHECK(format_number(45.0) == "45");
  CHECK(format_number(-45.0) == "-45");
  CHECK(format_number(0.1) == "0.1");
  CHECK(format_number(1e-5) == "1e-05");
  CHECK(format_number(100000.0) == "100000");
  CHECK(format_number(2.5e20) == "2.5e+20");
  CHECK(format_number(1.0 / 3.0) == "0.3333333333333333");
  CHECK(format_number(-0.0) == "0");
  CHECK(value_text(ojson::parse("45.0")) == "45");
  CHECK(value_text(ojson::parse("45")) == "45");
  CHECK(value_text(ojson::parse("true")) == "true");
  CHECK(value_text(ojson::parse(R"({"label": "20:60", "sx": 1})")) == "20:60");
  CHECK(value_text(ojson::parse(R"({"sx": 1})")) == R"({"sx":1})");
}

TEST_CASE("substitution: variables, object fields, built-ins, escapes", "[pipeline]") {
  const auto spec = parse(with_variables(
      R"({"angle": [45.0], "ratio": [{"label": "20:60", "sx": "20 kPa", "n": {"k": [7, 8]}}]})",
      R"(["--seed", "${angle}", "--set", "edge_loads.stress_x=${ratio.sx}", "${ratio}", "${ratio.n.k.1}",
          "${run_dir}/m", "${pipeline_dir}/s.json", "${out_dir}", "${run_id}", "$${angle}", "a${angle}b${angle}"])"));
  const auto runs = expand_runs(spec, "/tmp/out/");
  REQUIRE(runs.size() == 1);
  const auto& a = runs[0].steps[0].args;
  CHECK(a[1] == "45");
  CHECK(a[3] == "edge_loads.stress_x=20 kPa");
  CHECK(a[4] == "20:60");
  CHECK(a[5] == "8");
  CHECK(a[6] == "/tmp/out/runs/angle-45_ratio-20-60/m");
  CHECK(a[7] == "/data/study/s.json");
  CHECK(a[8] == "/tmp/out");
  CHECK(a[9] == "angle-45_ratio-20-60");
  CHECK(a[10] == "${angle}");
  CHECK(a[11] == "a45b45");

  const Bindings b{{"x", 1.5}};
  CHECK(substitute("x=${x}", b, "f", "k") == "x=1.5");
  CHECK_THROWS_WITH(substitute("${y}", b, "f", "k"), "f: k: expected a known variable, found ${y}");
}

TEST_CASE("placeholder errors name the key path before anything runs", "[pipeline]") {
  CHECK(message_of(R"({"variables": {"ratio": [1]}, "steps": [
          {"stage": "valve-generate", "args": []},
          {"stage": "valve-simulate", "args": ["--out", "${run_dir}", "--seed", "${rato}"]}]})") ==
        "P.json: steps[1].args[3]: expected a known variable, found ${rato}");
  CHECK(message_of(with_variables(R"({"ratio": [{"sx": 1}, {"sy": 2}]})", R"(["${ratio.sx}"])")) ==
        "P.json: steps[0].args[0]: expected a field sx in every value of ratio, found ${ratio.sx} (missing in variables.ratio[1])");
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", R"(["${a"])")),
             Catch::Contains("steps[0].args[0]: expected a closing } after ${"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", R"(["${}"])")),
             Catch::Contains("expected a variable name inside ${...}, found ${}"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", R"(["${run_dir.x}"])")),
             Catch::Contains("expected a field of an object-valued variable, found ${run_dir.x}"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", R"(["${csv}"])")),
             Catch::Contains("expected a known variable, found ${csv}"));
  CHECK_THAT(message_of(with_variables(R"({"run_dir": [1]})")), Catch::Contains("variables.run_dir: expected a variable name other"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", R"(["--out"])", R"(, "gather": [{"csv": "t.csv",
      "summary": "s.json", "columns": {"x": "${b}"}}])")),
             Catch::Contains("gather[0].columns.x: expected a known variable, found ${b}"));
}

TEST_CASE("structural errors: keys, steps, variables, zip, gather, plots", "[pipeline]") {
  CHECK(message_of(R"({"stepz": []})") ==
        "P.json: stepz: expected a known key (name, description, requires, variables, sweep, shared_steps, steps, gather, aggregate, select, plots), found an unknown key");
  CHECK_THAT(message_of(R"({"name": "x"})"), Catch::Contains("steps: expected a list of steps, found nothing"));
  CHECK_THAT(message_of(R"({"steps": []})"), Catch::Contains("steps: expected a non-empty list of steps"));
  CHECK_THAT(message_of(R"({"steps": [{"args": []}]})"), Catch::Contains("steps[0].stage: expected a string, found nothing"));
  CHECK_THAT(message_of(R"({"steps": [{"stage": "valve-generate"}]})"), Catch::Contains("steps[0].args: expected a list of strings"));
  CHECK_THAT(message_of(R"({"steps": [{"stage": "sh", "args": []}]})"), Catch::Contains("steps[0].stage: expected a stage name valve-<name>"));
  CHECK_THAT(message_of(R"({"steps": [{"stage": "valve-x", "args": [], "alow_exit": [0]}]})"),
             Catch::Contains("steps[0].alow_exit: expected a known key"));
  CHECK_THAT(message_of(R"({"steps": [{"stage": "valve-x", "args": [], "allow_exit": [0, 300]}]})"),
             Catch::Contains("steps[0].allow_exit: expected exit codes in [0, 255]"));
  CHECK_THAT(message_of(R"({"steps": [{"stage": "valve-x", "args": []}, {"stage": "valve-x", "args": []}]})"),
             Catch::Contains("steps[1].name: expected a step name not used before"));
  CHECK_THAT(message_of(R"({"steps": [{"name": "../x", "stage": "valve-x", "args": []}]})"),
             Catch::Contains("steps[0].name: expected a step name"));
  CHECK_THAT(message_of(with_variables(R"({"a": 5})")), Catch::Contains("variables.a: expected a list of values or"));
  CHECK_THAT(message_of(with_variables(R"({"a": []})")), Catch::Contains("variables.a: expected a non-empty list"));
  CHECK_THAT(message_of(with_variables(R"({"a": [[1]]})")), Catch::Contains("variables.a[0]: expected a number, string"));
  CHECK_THAT(message_of(with_variables(R"({"a": {"range": [1, 2], "step": 1}})")), Catch::Contains("variables.a.step: expected a known key"));
  CHECK(message_of(with_variables(R"({"angle": [0, 45], "mesh": {"range": [1, 10]}})", R"([])", R"(, "sweep": "zip")")) ==
        "P.json: variables.mesh: expected 2 values (as many as variables.angle, sweep zip), found 10");
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", R"([])", R"(, "sweep": "cartesian")")),
             Catch::Contains("sweep: expected \"grid\" or \"zip\""));
  CHECK_THAT(message_of(with_variables(R"({"a": {"range": [1, 1000]}, "b": {"range": [1, 1000]}})")),
             Catch::Contains("variables: expected at most 100000 runs"));
  const std::string g = R"(, "gather": [{"csv": "t.csv", "summary": "s.json", "columns": {"c": "row:x"}}])";
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", "[]", g)),
             Catch::Contains("gather[0].columns.c: expected a \"rows\" path in gather[0] for a row: column"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", "[]", R"(, "gather": [{"csv": "../t.csv", "summary": "s", "columns": {"c": "x"}}])")),
             Catch::Contains("gather[0].csv: expected a relative file path inside the output folder"));
  for (const char* owned : {"runs/t.csv", "pipeline.summary.json", "./runs/x/t.csv", "/tmp/t.csv", "a/../../t.csv", "t/"})
    CHECK_THAT(message_of(with_variables(R"({"a": [1]})", "[]", R"(, "gather": [{"csv": ")" + std::string(owned) +
                                                                     R"(", "summary": "s", "columns": {"c": "x"}}])")),
               Catch::Contains("gather[0].csv: expected a relative file path inside the output folder"));
  const std::string ok_gather = R"(, "gather": [{"csv": "t.csv", "summary": "s.json", "columns": {"c": "summary:status"}}])";
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", "[]", ok_gather + R"(, "plots": [{"png": "p.png", "csv": "u.csv", "gnuplot": "plot 1"}])")),
             Catch::Contains("plots[0].csv: expected one of the gather, aggregate or select tables (t.csv)"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", "[]", ok_gather + R"(, "plots": [{"png": "p.png", "csv": "t.csv", "gnuplot": "set out 'x.png'; plot 1"}])")),
             Catch::Contains("plots[0].gnuplot: expected a script without set output"));
  CHECK_THAT(message_of(with_variables(R"({"a": [1]})", "[]", ok_gather + R"(, "plots": [{"png": "p.png", "csv": "t.csv", "gnuplot": "plot '${a}'"}])")),
             Catch::Contains("plots[0].gnuplot: expected a known variable, found ${a}"));
  // Columns named in a plot must be its table's (gather t.csv has the one column c).
  CHECK(message_of(with_variables(R"({"a": [1]})", "[]", ok_gather + R"J(, "plots": [{"png": "p.png", "csv": "t.csv", "gnuplot": "plot '${csv}' using (column('c')):(strcol(\"d\") eq 'x' ? 1 : 0)"}])J")) ==
        "P.json: plots[0].gnuplot: expected columns of t.csv (c), found \"d\"");
  CHECK_NOTHROW(parse(with_variables(R"({"a": [1]})", "[]", ok_gather + R"J(, "plots": [{"png": "p.png", "csv": "t.csv", "gnuplot": "plot '${csv}' using (column('c')):(strcol('c') eq 'x' ? 1 : 0)"}])J")));
  // A valid one parses, with the plot lines joined.
  const auto spec = parse(with_variables(R"({"a": [1]})", "[]", ok_gather + R"(, "plots": [{"png": "p.png", "csv": "t.csv", "gnuplot": ["set offsets 1,1,1,1", "plot '${csv}'"]}])"));
  CHECK(spec.plots[0].gnuplot == "set offsets 1,1,1,1\nplot '${csv}'\n");
}

TEST_CASE("run ids are readable slugs and unique", "[pipeline]") {
  const auto spec = parse(with_variables(R"({"angle": [45], "ratio": [{"label": "20:60"}], "mesh": [3]})"));
  CHECK(expand_runs(spec, "/o")[0].run_id == "angle-45_ratio-20-60_mesh-3");

  std::vector<ojson> colliding;
  for (const char* v : {"a b", "a-b", "a/b", "a:b", "-0.5", "", "x_y"}) colliding.push_back(ojson{{"v", v}});
  const auto ids = make_run_ids(colliding);
  CHECK(ids[0] == "v-a-b");
  CHECK(ids[1] == "v-a-b-2");
  CHECK(ids[2] == "v-a-b-3");
  CHECK(ids[3] == "v-a-b-4");
  CHECK(ids[4] == "v--0.5");
  CHECK(ids[5] == "v-empty");
  CHECK(ids[6] == "v-x-y");

  // Long values are cut, and still unique.
  std::vector<ojson> longs;
  for (int k = 0; k < 3; ++k) longs.push_back(ojson{{"v", std::string(100, 'z') + std::to_string(k)}});
  const auto long_ids = make_run_ids(longs);
  CHECK(std::set<std::string>(long_ids.begin(), long_ids.end()).size() == 3);
  for (const auto& id : long_ids) CHECK(id.size() < 60);

  // A grid of many similar values never collides.
  const auto big = parse(with_variables(R"({"x": {"range": [0, 2, 0.01]}, "y": ["p q", "p-q", "p_q"]})"));
  const auto runs = expand_runs(big, "/o");
  std::set<std::string> seen;
  for (const auto& r : runs) seen.insert(r.run_id);
  CHECK(seen.size() == runs.size());
  CHECK(runs.size() == 201 * 3);
}

TEST_CASE("find_path walks objects and array indices", "[pipeline]") {
  const ojson j = ojson::parse(R"({"metrics": {"leaflets": [{"free_edge_mm": 26.2}, {"free_edge_mm": 25}]}, "s": "ok"})");
  REQUIRE(find_path(j, "metrics.leaflets.1.free_edge_mm"));
  CHECK(*find_path(j, "metrics.leaflets.1.free_edge_mm") == 25);
  CHECK(find_path(j, "") == &j);
  CHECK(find_path(j, "metrics.leaflets.2.free_edge_mm") == nullptr);
  CHECK(find_path(j, "metrics.leaflets.x") == nullptr);
  CHECK(find_path(j, "s.x") == nullptr);
  CHECK(find_path(j, "metrics..leaflets") == nullptr);
}

TEST_CASE("pipeline files may carry comments, syntax errors name the line", "[pipeline]") {
  const auto doc = ojson::parse("{\n// a comment\n\"steps\": [] /* another */\n}", nullptr, true, true);
  CHECK(doc.contains("steps"));
  CHECK_THROWS_WITH(load_pipeline("/nonexistent/P.json"), Catch::Contains("/nonexistent/P.json"));
}

TEST_CASE("shared steps: the leading steps without sweep variables run once in DIR/shared", "[pipeline]") {
  const PipelineSpec spec = test::parse(R"({"variables": {"k": [1, 2]}, "steps": [
    {"name": "a", "stage": "valve-x", "args": ["--out", "${run_dir}/a"]},
    {"name": "b", "stage": "valve-x", "args": ["${run_dir}/a/f.vtp", "--out", "${run_dir}/b"]},
    {"name": "c", "stage": "valve-x", "args": ["--k", "${k}", "--set", "file=${run_dir}/b/g.json", "--out", "${run_dir}/c"]},
    {"name": "d", "stage": "valve-x", "args": ["${run_dir}/ab/h.vtp", "${run_dir}/a", "--out", "${run_dir}/d"]}],
    "gather": [{"csv": "t.csv", "summary": "b/x.summary.json", "columns": {"k": "${k}"}}]})");
  CHECK(spec.shared_steps == 2);
  CHECK(spec.shared_outs == std::vector<std::string>{"a", "b"});
  const auto shared = shared_run(spec, "/out");
  REQUIRE(shared);
  CHECK(shared->run_dir == "/out/shared");
  REQUIRE(shared->steps.size() == 2);
  CHECK(shared->steps[1].args == std::vector<std::string>{"/out/shared/a/f.vtp", "--out", "/out/shared/b"});
  const auto runs = expand_runs(spec, "/out");
  REQUIRE(runs.size() == 2);
  REQUIRE(runs[1].steps.size() == 2);
  CHECK(runs[1].steps[0].args ==
        std::vector<std::string>{"--k", "2", "--set", "file=/out/shared/b/g.json", "--out", "/out/runs/k-2/c"});
  // "ab" is not the shared folder "a"; "${run_dir}/a" alone is.
  CHECK(runs[1].steps[1].args ==
        std::vector<std::string>{"/out/runs/k-2/ab/h.vtp", "/out/shared/a", "--out", "/out/runs/k-2/d"});
  CHECK(run_file(spec, runs[0], "/out", "b/x.summary.json") == "/out/shared/b/x.summary.json");
  CHECK(run_file(spec, runs[0], "/out", "c/x.summary.json") == "/out/runs/k-1/c/x.summary.json");
}

TEST_CASE("shared steps: none without variables, and the leading run stops where it must", "[pipeline]") {
  const std::string steps = R"([{"name": "a", "stage": "valve-x", "args": ["--out", "${run_dir}/a"]},
                                {"name": "b", "stage": "valve-x", "args": ["--out", "${run_dir}/b"]}])";
  CHECK(test::parse(R"({"steps": )" + steps + "}").shared_steps == 0);
  CHECK(test::parse(R"({"variables": {"k": [1]}, "steps": )" + steps + "}").shared_steps == 2);
  CHECK(test::parse(R"({"shared_steps": false, "variables": {"k": [1]}, "steps": )" + steps + "}").shared_steps == 0);
  CHECK_THAT(test::message_of(R"({"shared_steps": "no", "variables": {"k": [1]}, "steps": )" + steps + "}"),
             Catch::Contains("P.json: shared_steps: expected true or false, found string"));
  // The run id differs between runs.
  CHECK(test::parse(R"({"variables": {"k": [1]}, "steps": [
    {"stage": "valve-x", "args": ["${run_id}", "--out", "${run_dir}/a"]}]})").shared_steps == 0);
  // No --out inside the run folder: where it writes is unknown.
  CHECK(test::parse(R"({"variables": {"k": [1]}, "steps": [
    {"stage": "valve-x", "args": ["${run_dir}/a"]}]})").shared_steps == 0);
  // A later step names the folder relative to its own run folder.
  CHECK(test::parse(R"({"variables": {"k": [1]}, "steps": [
    {"name": "a", "stage": "valve-x", "args": ["--out", "${run_dir}/a"]},
    {"name": "b", "stage": "valve-x", "args": ["${k}", "a/f.vtp", "--out", "${run_dir}/b"]}]})").shared_steps == 0);
  // Only leading steps: a step after a varying one runs in every run.
  CHECK(test::parse(R"({"variables": {"k": [1]}, "steps": [
    {"name": "a", "stage": "valve-x", "args": ["${k}", "--out", "${run_dir}/a"]},
    {"name": "b", "stage": "valve-x", "args": ["--out", "${run_dir}/b"]}]})").shared_steps == 0);
}

TEST_CASE("step resources: defaults and per-step values", "[pipeline]") {
  const PipelineSpec spec = test::parse(R"({"steps": [
    {"name": "a", "stage": "valve-x", "args": []},
    {"name": "b", "stage": "valve-x", "args": [], "resources": {"threads": 4, "mem_mb": 16000, "runtime": 240}}]})");
  CHECK(spec.steps[0].resources.threads == 1);
  CHECK(spec.steps[0].resources.mem_mb == 2048);
  CHECK(spec.steps[0].resources.runtime_min == 60);
  CHECK(spec.steps[1].resources.threads == 4);
  CHECK(spec.steps[1].resources.mem_mb == 16000);
  CHECK(spec.steps[1].resources.runtime_min == 240);
  CHECK_THAT(test::message_of(R"({"steps": [{"stage": "valve-x", "args": [], "resources": {"threads": 0}}]})"),
             Catch::Contains("steps[0].resources.threads: expected a positive integer"));
  CHECK_THAT(test::message_of(R"({"steps": [{"stage": "valve-x", "args": [], "resources": {"gpus": 1}}]})"),
             Catch::Contains("steps[0].resources.gpus: expected a known key"));
}
