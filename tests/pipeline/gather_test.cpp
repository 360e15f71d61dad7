#include "valve/pipeline/gather.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "pipeline_test_support.hpp"
#include "valve/pipeline/process.hpp"

using namespace valve;
using valve::test::read_text;
using valve::test::TempDir;
using valve::test::write_text;
namespace fs = std::filesystem;

TEST_CASE("CSV fields are quoted only when RFC 4180 requires it", "[pipeline]") {
  CHECK(csv_field("plain text") == "plain text");
  CHECK(csv_field("") == "");
  CHECK(csv_field("20:60") == "20:60");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_field("two\nlines") == "\"two\nlines\"");
  CHECK(csv_field("cr\r") == "\"cr\r\"");
  CsvTable t{{"a", "b,c"}, {{"1", ""}, {"x\"y", "2"}}};
  CHECK(to_csv(t) == "a,\"b,c\"\n1,\n\"x\"\"y\",2\n");
}

TEST_CASE("CSV cells: %.10g numbers, exact integers, empty for missing and non-finite", "[pipeline]") {
  const ojson nan = std::numeric_limits<double>::quiet_NaN();
  const ojson inf = std::numeric_limits<double>::infinity();
  CHECK(cell_text(nullptr).empty());
  CHECK(cell_text(&nan).empty());
  CHECK(cell_text(&inf).empty());
  const ojson null_value = nullptr, f = 1.23456789012345, i = 123456789012345, s = "ok", b = false;
  const ojson small = 2.5e-12, obj = ojson::parse(R"({"a":[1,2]})");
  CHECK(cell_text(&null_value).empty());
  CHECK(cell_text(&f) == "1.23456789");
  CHECK(cell_text(&i) == "123456789012345");
  CHECK(cell_text(&small) == "2.5e-12");
  CHECK(cell_text(&s) == "ok");
  CHECK(cell_text(&b) == "false");
  CHECK(cell_text(&obj) == R"({"a":[1,2]})");
}

TEST_CASE("gather: one row per run, or per element of rows, gaps stay visible", "[pipeline]") {
  TempDir tmp("gather");
  const auto spec = parse_pipeline(ojson::parse(R"({
    "variables": {"model": ["fe", "ms", "none"]},
    "steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [
      {"csv": "per_run.csv", "summary": "sim_${model}/s.json",
       "columns": {"model": "${model}", "status": "summary:status", "free_edge": "summary:metrics.leaflets.0.free_edge_mm",
                   "note": "summary:note", "id": "${run_id}"}},
      {"csv": "tables/per_component.csv", "summary": "sim_${model}/s.json", "rows": "metrics.components",
       "columns": {"model": "${model}", "component": "row:component", "error_pct": "row:error_pct",
                   "wall_time_s": "summary:wall_time_s"}}
    ]})"),
                                     "P.json", tmp.path());
  const fs::path out = tmp.path() / "out";
  const auto runs = expand_runs(spec, out);
  REQUIRE(runs.size() == 3);
  write_text(runs[0].run_dir / "sim_fe/s.json", R"({"status": "ok", "wall_time_s": 1.5, "note": "a, \"quoted\" note",
    "metrics": {"leaflets": [{"free_edge_mm": 26.2012345678}],
                "components": [{"component": "xx", "error_pct": 1.25}, {"component": "yy", "error_pct": null}]}})");
  write_text(runs[1].run_dir / "sim_ms/s.json", R"({"status": "not_converged", "wall_time_s": 2, "metrics": {"components": []}})");
  // runs[2] has no summary at all.

  std::vector<MissingSummary> missing;
  const CsvTable t1 = gather_table(spec, spec.gather[0], runs, out, &missing);
  CHECK(t1.header == std::vector<std::string>{"model", "status", "free_edge", "note", "id"});  // file order
  REQUIRE(t1.rows.size() == 3);
  CHECK(t1.rows[0] == std::vector<std::string>{"fe", "ok", "26.20123457", "a, \"quoted\" note", "model-fe"});
  CHECK(t1.rows[1] == std::vector<std::string>{"ms", "not_converged", "", "", "model-ms"});
  CHECK(t1.rows[2] == std::vector<std::string>{"none", "", "", "", "model-none"});
  REQUIRE(missing.size() == 1);
  CHECK(missing[0].run_id == "model-none");

  const CsvTable t2 = gather_table(spec, spec.gather[1], runs, out);
  REQUIRE(t2.rows.size() == 3);  // fe: 2 components, ms: empty list (no row), none: a gap row
  CHECK(t2.rows[0] == std::vector<std::string>{"fe", "xx", "1.25", "1.5"});
  CHECK(t2.rows[1] == std::vector<std::string>{"fe", "yy", "", "1.5"});
  CHECK(t2.rows[2] == std::vector<std::string>{"none", "", "", ""});

  const GatherResult written = write_gather(spec, spec.gather[1], runs, out);
  CHECK(written.rows == 3);
  CHECK(written.path == out / "tables/per_component.csv");
  CHECK(read_text(written.path) == "model,component,error_pct,wall_time_s\nfe,xx,1.25,1.5\nfe,yy,,1.5\nnone,,,\n");
  CHECK(read_text(written.path).find("nan") == std::string::npos);

  // A summary that is not JSON is reported, not fatal.
  write_text(runs[1].run_dir / "sim_ms/s.json", "{ truncated");
  missing.clear();
  const CsvTable t3 = gather_table(spec, spec.gather[0], runs, out, &missing);
  CHECK(t3.rows[1] == std::vector<std::string>{"ms", "", "", "", "model-ms"});
  CHECK(missing.size() == 2);
}

TEST_CASE("gather: file: columns join another JSON file of the same run", "[pipeline]") {
  TempDir tmp("gather_file");
  const auto spec = parse_pipeline(ojson::parse(R"({
    "variables": {"model": ["fe", "ms"]},
    "steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [
      {"csv": "pareto.csv", "summary": "compare/c.json",
       "columns": {"model": "${model}", "error_mm": "summary:mean_mm",
                   "wall_s": "file:sim_${model}/s.json:metrics.wall_s"}}
    ]})"),
                                     "P.json", tmp.path());
  const fs::path out = tmp.path() / "out";
  const auto runs = expand_runs(spec, out);
  write_text(runs[0].run_dir / "compare/c.json", R"({"mean_mm": 0.8})");
  write_text(runs[0].run_dir / "sim_fe/s.json", R"({"metrics": {"wall_s": 11.5}})");
  write_text(runs[1].run_dir / "compare/c.json", R"({"mean_mm": 0.9})");  // no sim_ms/s.json
  std::vector<MissingSummary> missing;
  const CsvTable t = gather_table(spec, spec.gather[0], runs, out, &missing);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0] == std::vector<std::string>{"fe", "0.8", "11.5"});
  CHECK(t.rows[1] == std::vector<std::string>{"ms", "0.9", ""});
  REQUIRE(missing.size() == 1);
  CHECK(missing[0].reason.find("sim_ms/s.json") != std::string::npos);

  // The file part is checked like any placeholder text, and must not be empty.
  CHECK_THROWS_WITH(parse_pipeline(ojson::parse(R"({"steps": [{"stage": "valve-x", "args": []}],
    "gather": [{"csv": "a.csv", "summary": "s.json", "columns": {"t": "file::metrics.t"}}]})"), "P.json", tmp.path()),
                    Catch::Contains("gather[0].columns.t") && Catch::Contains("file:<json file in the run folder>:<path>"));
  CHECK_THROWS_WITH(parse_pipeline(ojson::parse(R"({"steps": [{"stage": "valve-x", "args": []}],
    "gather": [{"csv": "a.csv", "summary": "s.json", "columns": {"t": "file:${nope}/s.json:t"}}]})"), "P.json", tmp.path()),
                    Catch::Contains("nope"));
}

TEST_CASE("gather: min and max columns take the extreme of several sources, empty when one is missing", "[pipeline]") {
  TempDir tmp("gather_extreme");
  const auto spec = parse_pipeline(ojson::parse(R"({
    "variables": {"run": [1, 2, 3]},
    "steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [
      {"csv": "h.csv", "summary": "s.json",
       "columns": {"run": "${run}",
                   "native_min": {"min": ["summary:h.1", "summary:h.2"]},
                   "widest": {"max": ["summary:h.1", "summary:h.2", "file:other.json:w"]}}}
    ]})"),
                                     "P.json", tmp.path());
  const fs::path out = tmp.path() / "out";
  const auto runs = expand_runs(spec, out);
  write_text(runs[0].run_dir / "s.json", R"({"h": [9, 1.25, 3]})");
  write_text(runs[0].run_dir / "other.json", R"({"w": 7})");
  write_text(runs[1].run_dir / "s.json", R"({"h": [9, -0.5, 2e-3]})");
  write_text(runs[1].run_dir / "other.json", R"({"w": "wide"})");                  // not a number
  write_text(runs[2].run_dir / "s.json", R"({"h": [9, 4]})");                      // h.2 missing
  const CsvTable t = gather_table(spec, spec.gather[0], runs, out);
  REQUIRE(t.rows.size() == 3);
  CHECK(t.rows[0] == std::vector<std::string>{"1", "1.25", "7"});
  CHECK(t.rows[1] == std::vector<std::string>{"2", "-0.5", ""});
  CHECK(t.rows[2] == std::vector<std::string>{"3", "", ""});

  auto parse = [&](const std::string& columns) {
    return parse_pipeline(ojson::parse(R"({"steps": [{"stage": "valve-x", "args": []}],
      "gather": [{"csv": "a.csv", "summary": "s.json", "columns": )" + columns + "}]}"), "P.json", tmp.path());
  };
  CHECK_THROWS_WITH(parse(R"({"m": {"min": ["summary:a"]}})"),
                    Catch::Contains("gather[0].columns.m.min: expected a list of two or more"));
  CHECK_THROWS_WITH(parse(R"({"m": {"max": ["summary:a", "3"]}})"),
                    Catch::Contains("gather[0].columns.m.max[1]: expected a summary:, row: or file: source, found \"3\""));
  CHECK_THROWS_WITH(parse(R"({"m": {"mean": ["summary:a", "summary:b"]}})"),
                    Catch::Contains("gather[0].columns.m: expected a string") && Catch::Contains("{\"min\" or \"max\""));
  CHECK_THROWS_WITH(parse(R"({"m": {"min": ["sumary:a", "summary:b"]}})"),
                    Catch::Contains("gather[0].columns.m.min[0]: expected the source summary:"));
}

TEST_CASE("plots: script with terminal, separator and output, skipped without gnuplot", "[pipeline]") {
  TempDir tmp("plot");
  auto spec_with = [&](const std::string& gnuplot) {
    return parse_pipeline(ojson::parse(R"({"steps": [{"stage": "valve-x", "args": []}],
      "gather": [{"csv": "t.csv", "summary": "s.json", "columns": {"x": "summary:x", "y": "summary:y"}}],
      "plots": [{"png": "p.png", "csv": "t.csv", "gnuplot": )" + gnuplot + "}]}"),
                          "P.json", tmp.path());
  };
  const fs::path out = tmp.path() / "out";
  const auto spec = spec_with(R"("plot '${csv}' using 1:2 with lines")");
  const std::string script = plot_script(spec, spec.plots[0], out, out / "p.png");
  CHECK_THAT(script, Catch::Contains("set terminal pngcairo"));
  CHECK_THAT(script, Catch::Contains("set datafile separator ','"));
  CHECK_THAT(script, Catch::Contains("set output '" + (out / "p.png").string() + "'"));
  CHECK_THAT(script, Catch::Contains("plot '" + (out / "t.csv").string() + "' using 1:2"));
  const auto own_terminal = spec_with(R"("set term svg; plot '${csv}'")");
  CHECK_THAT(plot_script(own_terminal, own_terminal.plots[0], out, out / "p.png"), !Catch::Contains("pngcairo"));

  const PlotResult skipped = render_plot(spec, spec.plots[0], out, std::nullopt);
  CHECK(skipped.status == "skipped");
  CHECK(fs::exists(out / "p.png.gp"));
  CHECK_FALSE(fs::exists(out / "p.png"));

  const auto gnuplot = find_on_path("gnuplot");
  if (!gnuplot) {
    WARN("gnuplot is not on PATH: rendering not tested");
    return;
  }
  write_text(out / "t.csv", "x,y\n1,2\n2,4\n3,3\n");
  const PlotResult made = render_plot(spec, spec.plots[0], out, gnuplot);
  CHECK(made.status == "made");
  CHECK(fs::file_size(out / "p.png") > 100);
  const auto bad = spec_with(R"("plot '${csv}' using 1:2 with nonsense")");
  const PlotResult failed = render_plot(bad, bad.plots[0], out, gnuplot);
  CHECK(failed.status == "failed");
  CHECK_THAT(failed.reason, Catch::Contains("p.png.log"));
  CHECK(fs::file_size(out / "p.png") > 100);  // the good image from before is kept
  for (const auto& e : fs::directory_iterator(out)) CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
}
