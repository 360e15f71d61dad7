#include "valve/pipeline/aggregate.hpp"

#include <catch2/catch.hpp>

#include "pipeline_test_support.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/runner.hpp"

using namespace valve;
using valve::test::message_of;
using valve::test::parse;
using valve::test::read_text;
using valve::test::TempDir;
using valve::test::write_script;
using valve::test::write_text;
namespace fs = std::filesystem;

namespace {

using Rows = std::vector<std::vector<std::string>>;


// A pipeline with one gather table biaxial.csv (model, component, angle, err) and the given
// aggregate list (JSON text).
std::string with_aggregate(const std::string& aggregate, const std::string& extra = "") {
  return R"({"steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [{"csv": "biaxial.csv", "summary": "s.json", "rows": "components",
                "columns": {"model": "summary:model", "component": "row:component", "angle": "summary:angle",
                            "err": "row:error_pct"}}],
    "aggregate": )" + aggregate + extra + "}";
}


// The rows of biaxial.csv used by the computation tests, in gather order.
const CsvTable biaxial{{"model", "component", "angle", "err"},
                       {{"fe", "E11", "45", "1"},
                        {"fe", "E22", "45", "2"},
                        {"ms", "E11", "45", "2"},
                        {"fe", "E11", "45", "3"},
                        {"fe", "E12", "45", "100"},  // filtered out by component
                        {"ms", "E22", "45", ""},     // empty: skipped
                        {"fe", "E22", "45", "4"},
                        {"ms", "E11", "0", "50"},    // filtered out by angle
                        {"ms", "E11", "45", "n/a"},  // not a number: skipped
                        {"ms", "E22", "45", "4"},
                        {"ms", "E22", "45", "9"},
                        {"none", "E11", "45", ""},   // a group without numbers
                        {"ms", "E11", "45", "5"},
                        {"ms", "E11", "45", "7"},
                        {"ms", "E22", "45", "4"},
                        {"ms", "E11", "45", "5"}}};

}  // namespace

TEST_CASE("aggregate: numeric cells are finite decimal text", "[pipeline]") {
  CHECK(numeric_cell("3") == 3.0);
  CHECK(numeric_cell("-0.5") == -0.5);
  CHECK(numeric_cell("1e-05") == 1e-05);
  CHECK(numeric_cell("+2.") == 2.0);
  CHECK(numeric_cell(".25") == 0.25);
  for (const char* text : {"", " 3", "3 ", "n/a", "nan", "inf", "-inf", "0x10", "1,5", "+", "3kPa", "true"})
    CHECK_FALSE(numeric_cell(text).has_value());
}

TEST_CASE("aggregate: stats against hand-computed values", "[pipeline]") {
  const std::vector<double> v{1, 2, 3, 4};
  CHECK(stat_cell("mean", v) == "2.5");
  CHECK(stat_cell("sd", v) == "1.290994449");  // sqrt(5/3)
  CHECK(stat_cell("median", v) == "2.5");
  CHECK(stat_cell("min", v) == "1");
  CHECK(stat_cell("max", v) == "4");
  CHECK(stat_cell("count", v) == "4");
  const std::vector<double> w{9, 2, 4, 4, 5, 7, 4, 5};  // unsorted on purpose
  CHECK(stat_cell("mean", w) == "5");
  CHECK(stat_cell("sd", w) == "2.138089935");  // sqrt(32/7), n - 1
  CHECK(stat_cell("median", w) == "4.5");
  CHECK(stat_cell("median", {3, 1, 2}) == "2");
  CHECK(stat_cell("min", {-0.25, 1e-7}) == "-0.25");
  CHECK(stat_cell("max", {-0.25, 1e-7}) == "1e-07");
  CHECK(stat_cell("mean", {1, 2, 2}) == "1.666666667");
  // Small spreads around a large mean keep their digits.
  CHECK(stat_cell("sd", {1e9 + 1, 1e9 + 2, 1e9 + 3}) == "1");
  // Undefined stats are empty, never nan; a count is never undefined.
  CHECK(stat_cell("mean", {}).empty());
  CHECK(stat_cell("median", {}).empty());
  CHECK(stat_cell("min", {}).empty());
  CHECK(stat_cell("sd", {}).empty());
  CHECK(stat_cell("sd", {42}).empty());
  CHECK(stat_cell("count", {}) == "0");
  CHECK(stat_cell("mean", {42}) == "42");
}

TEST_CASE("aggregate: where filters, groups in order of first appearance, empty groups", "[pipeline]") {
  const auto spec = parse(with_aggregate(R"([
    {"csv": "summary.csv", "from": "biaxial.csv",
     "where": {"component": ["E11", "E22"], "angle": [45.0]},
     "group_by": ["model", "component"],
     "stats": {"err": ["mean", "sd", "min", "max", "median", "count"]}}])"));
  REQUIRE(spec.aggregates.size() == 1);
  CHECK(spec.aggregates[0].where[1].values == std::vector<std::string>{"45"});  // 45.0 compares as "45"
  const CsvTable t = aggregate_table(spec.aggregates[0], biaxial);
  CHECK(t.header == std::vector<std::string>{"model", "component", "err_mean", "err_sd", "err_min", "err_max",
                                             "err_median", "err_count"});
  CHECK(t.rows == Rows{{"fe", "E11", "2", "1.414213562", "1", "3", "2", "2"},      // 1, 3
                       {"fe", "E22", "3", "1.414213562", "2", "4", "3", "2"},      // 2, 4
                       {"ms", "E11", "4.75", "2.061552813", "2", "7", "5", "4"},   // 2, 5, 7, 5 (50 and n/a out)
                       {"ms", "E22", "5.666666667", "2.886751346", "4", "9", "4", "3"},  // 4, 9, 4
                       {"none", "E11", "", "", "", "", "", "0"}});
  CHECK(to_csv(t).find("nan") == std::string::npos);

  // Stats of several columns, in file order; a value column may also be a key column.
  const auto two = parse(with_aggregate(R"([{"csv": "by_angle.csv", "from": "biaxial.csv", "group_by": ["angle"],
    "stats": {"err": ["count", "max"], "angle": ["mean"]}}])"));
  const CsvTable ta = aggregate_table(two.aggregates[0], biaxial);
  CHECK(ta.header == std::vector<std::string>{"angle", "err_count", "err_max", "angle_mean"});
  CHECK(ta.rows == Rows{{"45", "12", "100", "45"}, {"0", "1", "50", "0"}});

  // true_count counts the cells that read true (booleans as gather writes them); numbers,
  // "TRUE" and empty cells do not count.
  const CsvTable flags{{"model", "closed"}, {{"fe", "true"}, {"fe", "false"}, {"fe", "true"}, {"ms", "TRUE"}, {"ms", "1"}, {"ms", ""}}};
  const auto counted = parse(R"({"steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [{"csv": "c.csv", "summary": "s.json", "columns": {"model": "summary:m", "closed": "summary:c"}}],
    "aggregate": [{"csv": "n.csv", "from": "c.csv", "group_by": ["model"], "stats": {"closed": ["true_count", "count"]}}]})");
  CHECK(aggregate_table(counted.aggregates[0], flags).rows == Rows{{"fe", "2", "0"}, {"ms", "0", "1"}});

  // Text filters match the cell text exactly; numbers in the list as their shortest text.
  const auto numeric = parse(with_aggregate(R"([{"csv": "x.csv", "from": "biaxial.csv",
    "where": {"err": [4, "5", 1e2]}, "group_by": [], "stats": {"err": ["count", "mean"]}}])"));
  CHECK(aggregate_table(numeric.aggregates[0], biaxial).rows == Rows{{"6", "20.33333333"}});  // 100, 4, 4, 4, 5, 5
}

TEST_CASE("aggregate: no group_by gives one row, also when nothing passes the filters", "[pipeline]") {
  const auto spec = parse(with_aggregate(R"([
    {"csv": "all.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["count", "median", "sd"]}},
    {"csv": "nothing.csv", "from": "biaxial.csv", "where": {"model": ["xx"]}, "group_by": [],
     "stats": {"err": ["count", "mean", "sd"]}},
    {"csv": "nothing_grouped.csv", "from": "biaxial.csv", "where": {"model": ["xx"]}, "group_by": ["model"],
     "stats": {"err": ["count"]}}])"));
  const CsvTable all = aggregate_table(spec.aggregates[0], biaxial);
  CHECK(all.header == std::vector<std::string>{"err_count", "err_median", "err_sd"});
  REQUIRE(all.rows.size() == 1);
  CHECK(all.rows[0][0] == "13");
  CHECK(all.rows[0][1] == "4");
  CHECK(to_csv(aggregate_table(spec.aggregates[1], biaxial)) == "err_count,err_mean,err_sd\n0,,\n");
  CHECK(to_csv(aggregate_table(spec.aggregates[2], biaxial)) == "model,err_count\n");
  CHECK(to_csv(aggregate_table(spec.aggregates[0], CsvTable{biaxial.header, {}})) == "err_count,err_median,err_sd\n0,,\n");
}

TEST_CASE("aggregate: an aggregate may read an earlier one, plots may use both", "[pipeline]") {
  const auto spec = parse(with_aggregate(R"([
    {"csv": "per_model.csv", "from": "biaxial.csv", "where": {"angle": ["45"]}, "group_by": ["model", "component"],
     "stats": {"err": ["mean"]}},
    {"csv": "tables/overall.csv", "from": "./per_model.csv", "group_by": ["component"], "stats": {"err_mean": ["max", "count"]}}])",
                                         R"(, "plots": [{"png": "o.png", "csv": "tables/overall.csv", "gnuplot": "plot '${csv}'"}])"));
  REQUIRE(spec.aggregates.size() == 2);
  CHECK(spec.aggregates[1].from == "per_model.csv");
  CHECK(spec.aggregates[1].header == std::vector<std::string>{"component", "err_mean_max", "err_mean_count"});
  const CsvTable first = aggregate_table(spec.aggregates[0], biaxial);
  const CsvTable second = aggregate_table(spec.aggregates[1], first);
  // fe: E11 2, E22 3, E12 100; ms: E11 4.75, E22 5.666666667; none: E11 (empty, not counted)
  CHECK(second.rows == Rows{{"E11", "4.75", "2"}, {"E22", "5.666666667", "2"}, {"E12", "100", "1"}});
}

TEST_CASE("aggregate: validation errors name the key path", "[pipeline]") {
  const std::string a = R"({"csv": "s.csv", "from": "biaxial.csv", "group_by": ["model"], "stats": {"err": ["mean"]}})";
  CHECK(message_of(with_aggregate("[" + a + "]")) == "(no error)");
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["mean"]}, "wher": {}}])")) ==
        "P.json: aggregate[0].wher: expected a known key (csv, from, where, group_by, stats), found an unknown key");
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxal.csv", "group_by": [], "stats": {"err": ["mean"]}}])")) ==
        "P.json: aggregate[0].from: expected a gather table or an earlier aggregate table (biaxial.csv), found \"biaxal.csv\"");
  // A later aggregate is not readable yet, nor is the aggregate itself.
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "t.csv", "group_by": [], "stats": {"err_mean": ["max"]}},
    {"csv": "t.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["mean"]}}])")) ==
        "P.json: aggregate[0].from: expected a gather table or an earlier aggregate table (biaxial.csv), found \"t.csv\"");
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "s.csv", "group_by": [], "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].from: expected a gather table or an earlier aggregate table"));
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["mean", "avg"]}}])")) ==
        "P.json: aggregate[0].stats.err[1]: expected a stat (mean, sd, min, max, median, count, true_count), found \"avg\"");
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": [], "stats": {"eror": ["mean"]}}])")) ==
        "P.json: aggregate[0].stats.eror: expected a column of biaxial.csv (model, component, angle, err), found \"eror\"");
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": ["model", "modle"], "stats": {"err": ["mean"]}}])")) ==
        "P.json: aggregate[0].group_by[1]: expected a column of biaxial.csv (model, component, angle, err), found \"modle\"");
  CHECK(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "where": {"componant": ["E11"]}, "group_by": [], "stats": {"err": ["mean"]}}])")) ==
        "P.json: aggregate[0].where.componant: expected a column of biaxial.csv (model, component, angle, err), found \"componant\"");
  // Columns of an earlier aggregate are its output columns, not those of its source.
  CHECK(message_of(with_aggregate("[" + a + R"(, {"csv": "t.csv", "from": "s.csv", "group_by": ["component"], "stats": {"err_mean": ["max"]}}])")) ==
        "P.json: aggregate[1].group_by[0]: expected a column of s.csv (model, err_mean), found \"component\"");
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "where": {"model": []}, "group_by": [], "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].where.model: expected a non-empty list of values, found array []"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "where": {"model": "fe"}, "group_by": [], "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].where.model: expected a non-empty list of values"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "where": {"model": [null]}, "group_by": [], "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].where.model[0]: expected a string, number or boolean, found null"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].group_by: expected a list of column names, found nothing"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": "model", "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].group_by: expected a list of column names, found string"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": ["model", "model"], "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].group_by[1]: expected a column not named before in group_by, found \"model\""));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": []}])")),
             Catch::Contains("aggregate[0].stats: expected an object of column: list of stats, found nothing"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": [], "stats": {}}])")),
             Catch::Contains("aggregate[0].stats: expected a non-empty object"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": "mean"}}])")),
             Catch::Contains("aggregate[0].stats.err: expected a non-empty list of stats (mean, sd, min, max, median, count, true_count)"));
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "s.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["mean", "mean"]}}])")),
             Catch::Contains("aggregate[0].stats.err[1]: expected an output column name not used before in aggregate[0], found \"err_mean\""));
  // Output files: inside DIR, not a gather table, not another aggregate.
  CHECK(message_of(with_aggregate(R"([{"csv": "biaxial.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["mean"]}}])")) ==
        "P.json: aggregate[0].csv: expected a file name not used by a gather table or an earlier aggregate, found \"biaxial.csv\" (also gather[0])");
  CHECK(message_of(with_aggregate("[" + a + ", " + a + "]")) ==
        "P.json: aggregate[1].csv: expected a file name not used by a gather table or an earlier aggregate, found \"s.csv\" (also aggregate[0])");
  CHECK_THAT(message_of(with_aggregate(R"([{"csv": "runs/s.csv", "from": "biaxial.csv", "group_by": [], "stats": {"err": ["mean"]}}])")),
             Catch::Contains("aggregate[0].csv: expected a relative file path inside the output folder"));
  CHECK_THAT(message_of(with_aggregate(R"({"csv": "s.csv"})")), Catch::Contains("aggregate: expected a list of aggregate tables"));
  CHECK_THAT(message_of(with_aggregate(R"(["s.csv"])")), Catch::Contains("aggregate[0]: expected an object with csv, from, group_by and stats"));
  // Plots name an aggregate table only when there is one.
  CHECK(message_of(with_aggregate("[" + a + "]", R"(, "plots": [{"png": "p.png", "csv": "u.csv", "gnuplot": "plot 1"}])")) ==
        "P.json: plots[0].csv: expected one of the gather, aggregate or select tables (biaxial.csv, s.csv), found \"u.csv\"");
}

TEST_CASE("gather: entries sharing a csv are concatenated, their columns must match", "[pipeline]") {
  TempDir tmp("shared");
  const auto spec = parse_pipeline(ojson::parse(R"({
    "variables": {"model": ["fe", "ms"]},
    "steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [
      {"csv": "all.csv", "summary": "uni.json", "columns": {"model": "${model}", "load": "uni", "v": "summary:v"}},
      {"csv": "other.csv", "summary": "uni.json", "columns": {"v": "summary:v"}},
      {"csv": "./all.csv", "summary": "bi.json", "rows": "rows",
       "columns": {"model": "${model}", "load": "bi", "v": "row:v"}}
    ]})"),
                                   "P.json", tmp.path());
  CHECK(gather_csvs(spec) == std::vector<std::string>{"all.csv", "other.csv"});
  const fs::path out = tmp.path() / "out";
  const auto runs = expand_runs(spec, out);
  REQUIRE(runs.size() == 2);
  write_text(runs[0].run_dir / "uni.json", R"({"v": 1})");
  write_text(runs[1].run_dir / "uni.json", R"({"v": 2})");
  write_text(runs[0].run_dir / "bi.json", R"({"rows": [{"v": 3}, {"v": 4}]})");
  // runs[1] has no bi.json: a gap row, reported as missing.

  std::vector<MissingSummary> missing;
  const CsvTable t = gather_csv_table(spec, "all.csv", runs, out, &missing);
  CHECK(t.header == std::vector<std::string>{"model", "load", "v"});
  CHECK(t.rows == Rows{{"fe", "uni", "1"}, {"ms", "uni", "2"}, {"fe", "bi", "3"}, {"fe", "bi", "4"}, {"ms", "bi", ""}});
  REQUIRE(missing.size() == 1);
  CHECK(missing[0].run_id == "model-ms");
  CsvTable written;
  const GatherResult r = write_gather_csv(spec, "all.csv", runs, out, &written);
  CHECK(r.rows == 5);
  CHECK(written.rows == t.rows);
  CHECK(read_text(out / "all.csv") == "model,load,v\nfe,uni,1\nms,uni,2\nfe,bi,3\nfe,bi,4\nms,bi,\n");

  // Two entries reading the same missing summary: a gap row each, one missing report.
  const auto same = parse_pipeline(ojson::parse(R"({"steps": [{"stage": "valve-x", "args": []}], "gather": [
    {"csv": "t.csv", "summary": "s.json", "columns": {"v": "summary:v"}},
    {"csv": "t.csv", "summary": "s.json", "rows": "list", "columns": {"v": "row:v"}}]})"),
                                   "P.json", tmp.path());
  missing.clear();
  const CsvTable gaps = gather_csv_table(same, "t.csv", expand_runs(same, out), out, &missing);
  CHECK(gaps.rows == Rows{{""}, {""}});
  CHECK(missing.size() == 1);

  // Same names in another order, or other names: one header cannot hold both.
  const std::string steps = R"({"steps": [{"stage": "valve-x", "args": []}], "gather": [
    {"csv": "all.csv", "summary": "s.json", "columns": {"a": "summary:a", "b": "summary:b"}},
    {"csv": "other.csv", "summary": "s.json", "columns": {"a": "summary:a"}},)";
  CHECK(message_of(steps + R"({"csv": "all.csv", "summary": "t.json", "columns": {"b": "summary:b", "a": "summary:a"}}]})") ==
        "P.json: gather[2].columns: expected the same columns as gather[0] (same csv), found b, a (gather[0]: a, b)");
  CHECK_THAT(message_of(steps + R"({"csv": "all.csv", "summary": "t.json", "columns": {"a": "summary:a", "c": "summary:b"}}]})"),
             Catch::Contains("gather[2].columns: expected the same columns as gather[0] (same csv), found a, c"));
  CHECK_THAT(message_of(steps + R"({"csv": "all.csv", "summary": "t.json", "columns": {"a": "summary:a"}}]})"),
             Catch::Contains("gather[2].columns: expected the same columns as gather[0] (same csv), found a (gather[0]: a, b)"));
  CHECK(message_of(steps + R"({"csv": "other.csv", "summary": "t.json", "columns": {"a": "summary:x"}}]})") == "(no error)");
}

TEST_CASE("runner: shared gather csv, chained aggregates, summary lists every table", "[pipeline]") {
  TempDir tmp("aggregate_run");
  // valve-report VALUE: a summary with the value and a list of two rows derived from it.
  write_script(tmp.path() / "bin/valve-report",
               "printf '{\"status\": \"ok\", \"value\": %s, \"rows\": [{\"k\": \"a\", \"x\": %s}, {\"k\": \"b\", \"x\": \"n/a\"}]}\\n' "
               "\"$1\" \"$1\" > report.summary.json");
  write_text(tmp.path() / "P.json", R"({
    "variables": {"v": [1, 2, 4]},
    "steps": [{"stage": "valve-report", "args": ["${v}"]}],
    "gather": [
      {"csv": "values.csv", "summary": "report.summary.json", "columns": {"kind": "value", "x": "summary:value"}},
      {"csv": "values.csv", "summary": "report.summary.json", "rows": "rows",
       "columns": {"kind": "row:k", "x": "row:x"}}
    ],
    "aggregate": [
      {"csv": "by_kind.csv", "from": "values.csv", "group_by": ["kind"], "stats": {"x": ["mean", "sd", "count"]}},
      {"csv": "overall.csv", "from": "by_kind.csv", "where": {"x_count": [3]}, "group_by": [],
       "stats": {"x_mean": ["min", "max", "count"]}}
    ],
    "plots": [{"png": "by_kind.png", "csv": "by_kind.csv", "gnuplot": "plot '${csv}' using 2:3 skip 1"}]
  })");
  const auto spec = load_pipeline(tmp.path() / "P.json");
  RunnerOptions options;
  options.out_dir = tmp.path() / "out";
  options.stage_dirs = {tmp.path() / "bin"};
  const PipelineOutcome result = run_pipeline(spec, options);
  CHECK(result.exit_code == 0);
  const fs::path out = tmp.path() / "out";
  CHECK(read_text(out / "values.csv") == "kind,x\nvalue,1\nvalue,2\nvalue,4\na,1\nb,n/a\na,2\nb,n/a\na,4\nb,n/a\n");
  // value and a: 1, 2, 4 (mean 7/3, sd sqrt(7/3)); b: no numbers.
  CHECK(read_text(out / "by_kind.csv") ==
        "kind,x_mean,x_sd,x_count\nvalue,2.333333333,1.527525232,3\na,2.333333333,1.527525232,3\nb,,,0\n");
  CHECK(read_text(out / "overall.csv") == "x_mean_min,x_mean_max,x_mean_count\n2.333333333,2.333333333,2\n");
  REQUIRE(result.tables.size() == 1);
  CHECK(result.tables[0].rows == 9);
  REQUIRE(result.aggregates.size() == 2);
  CHECK(result.aggregates[1].from == "by_kind.csv");
  CHECK(fs::exists(out / "by_kind.png.gp"));

  const ojson summary = ojson::parse(read_text(out / "pipeline.summary.json"));
  const ojson& csv = summary["metrics"]["csv"];
  REQUIRE(csv.size() == 3);
  CHECK(csv[0]["kind"] == "gather");
  CHECK(csv[0]["rows"] == 9);
  CHECK(csv[0]["missing_summaries"].empty());
  CHECK(csv[1]["kind"] == "aggregate");
  CHECK(csv[1]["file"] == (normalized_dir(out) / "by_kind.csv").string());
  CHECK(csv[1]["from"] == (normalized_dir(out) / "values.csv").string());
  CHECK(csv[1]["rows"] == 3);
  CHECK(csv[2]["rows"] == 1);
}
