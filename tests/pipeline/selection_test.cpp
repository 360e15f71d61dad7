#include "valve/pipeline/selection.hpp"

#include <catch2/catch.hpp>

#include "pipeline_test_support.hpp"

using namespace valve;
using valve::test::message_of;
using valve::test::parse;
using valve::test::read_text;
using valve::test::TempDir;

namespace {

// A pipeline with one gather table sizing.csv and the given select entry (JSON text).
std::string with_select(const std::string& select) {
  return R"({"steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [{"csv": "sizing.csv", "summary": "s.json",
                "columns": {"stiffness": "summary:k", "width": "summary:w", "height": "summary:h",
                            "area": "summary:a", "seal_mm": "summary:seal", "status": "summary:status"}}],
    "select": [)" + select + "]}";
}

// Three stiffnesses; the graft sizes are listed out of area order on purpose.
const CsvTable sizing{{"stiffness", "width", "height", "area", "seal_mm", "status"},
                      {{"x1", "14", "27", "260", "1.4", "ok"},
                       {"x1", "0", "27", "230", "0.6", "ok"},          // too little seal
                       {"x1", "7", "13", "220", "2.0", "ok"},          // the smallest that seals
                       {"x1", "0", "0", "200", "5.0", "not_converged"},  // filtered out
                       {"x1", "7", "27", "240", "", "ok"},             // no measure: not a candidate
                       {"x0.5", "7", "13", "221", "1.0", "ok"},        // at the bound: qualifies
                       {"x0.5", "0", "13", "210", "0.99", "ok"},
                       {"x2", "0", "0", "200", "0.2", "ok"}}};

}  // namespace

TEST_CASE("select: per group the row meeting every bound with the smallest minimized value", "[pipeline]") {
  const PipelineSpec spec = parse(with_select(R"({"csv": "choice.csv", "from": "sizing.csv",
      "where": {"status": ["ok"]}, "group_by": ["stiffness"], "at_least": {"seal_mm": 1},
      "minimize": ["area"], "agree_on": ["width", "height"]})"));
  REQUIRE(spec.selects.size() == 1);
  const SelectSpec& sel = spec.selects[0];
  CHECK(sel.header == std::vector<std::string>{"stiffness", "found", "width", "height", "area", "seal_mm", "status"});
  const Selection s = select_table(sel, sizing);
  REQUIRE(s.table.rows.size() == 3);  // groups in order of first appearance
  CHECK(s.table.rows[0] == std::vector<std::string>{"x1", "true", "7", "13", "220", "2.0", "ok"});
  CHECK(s.table.rows[1] == std::vector<std::string>{"x0.5", "true", "7", "13", "221", "1.0", "ok"});
  CHECK(s.table.rows[2] == std::vector<std::string>{"x2", "false", "", "", "", "", ""});
  CHECK(s.line ==
        "choice.csv: smallest area with seal_mm >= 1: stiffness x1: width 7, height 13; stiffness x0.5: width 7, "
        "height 13; stiffness x2: none; not every stiffness has a qualifying row");

  // Without the stiffest law every group agrees; with a stricter bound they differ.
  CsvTable two = sizing;
  two.rows.pop_back();
  CHECK(select_table(sel, two).line.find("; width, height the same for every stiffness") != std::string::npos);
  SelectSpec strict = sel;
  strict.thresholds[0].bound = 1.2;
  two.rows.push_back({"x0.5", "14", "27", "262", "1.3", "ok"});
  const Selection differ = select_table(strict, two);  // x0.5's 7/13 seals only 1.0 mm now
  CHECK(differ.table.rows[0][2] == "7");
  CHECK(differ.table.rows[1][2] == "14");
  CHECK(differ.line.find("; width, height change with stiffness") != std::string::npos);
}

TEST_CASE("select: at_most bounds a column from above, alone or beside at_least", "[pipeline]") {
  // x1's smallest sealing graft (7/13, area 220) is too large under area <= 215; its next
  // candidates (230: too little seal, 240: no measure, 260) are larger still, so x1 has none.
  const PipelineSpec both = parse(with_select(R"({"csv": "c.csv", "from": "sizing.csv", "where": {"status": ["ok"]},
      "group_by": ["stiffness"], "at_least": {"seal_mm": 1}, "at_most": {"area": 221}, "minimize": ["area"]})"));
  const Selection s = select_table(both.selects[0], sizing);
  REQUIRE(s.table.rows.size() == 3);
  CHECK(s.table.rows[0][1] == "true");  // x1: 220 <= 221
  CHECK(s.table.rows[1][1] == "true");  // x0.5: 221, at the bound, qualifies
  CHECK(s.line.rfind("c.csv: smallest area with seal_mm >= 1 and area <= 221: ", 0) == 0);
  SelectSpec tighter = both.selects[0];
  tighter.thresholds[1].bound = 215;
  const Selection none = select_table(tighter, sizing);
  CHECK(none.table.rows[0][1] == "false");
  CHECK(none.table.rows[1][1] == "false");
  // at_most alone: the largest seal is not wanted, the smallest area with seal_mm <= 1 is.
  const PipelineSpec alone = parse(with_select(R"({"csv": "c.csv", "from": "sizing.csv", "where": {"status": ["ok"]},
      "group_by": [], "at_most": {"seal_mm": 1}, "minimize": ["area"]})"));
  const Selection a = select_table(alone.selects[0], sizing);
  REQUIRE(a.table.rows.size() == 1);
  CHECK(a.table.rows[0] == std::vector<std::string>{"true", "x2", "0", "0", "200", "0.2", "ok"});
  // Neither bound, or an empty or non-numeric one, is refused with its key.
  const std::string ok = R"("csv": "c.csv", "from": "sizing.csv", "group_by": [], )";
  CHECK(message_of(with_select("{" + ok + R"("minimize": ["area"]})")) ==
        "P.json: select[0].at_least: expected an object of column: number (or at_most), found nothing (one of them is "
        "required)");
  CHECK(message_of(with_select("{" + ok + R"("at_most": {}, "minimize": ["area"]})")).find(
            "select[0].at_most: expected a non-empty object") != std::string::npos);
  CHECK(message_of(with_select("{" + ok + R"("at_most": {"area": true}, "minimize": ["area"]})")) ==
        "P.json: select[0].at_most.area: expected a finite number, found boolean true");
}

TEST_CASE("select: ties keep the earlier row, later minimize columns break them, no groups gives one row", "[pipeline]") {
  const PipelineSpec spec = parse(with_select(R"({"csv": "c.csv", "from": "sizing.csv", "group_by": [],
      "at_least": {"seal_mm": 0.5, "area": 0}, "minimize": ["width", "height"]})"));
  CsvTable t{sizing.header,
             {{"x1", "7", "27", "1", "1", "ok"}, {"x1", "7", "13", "1", "1", "ok"}, {"x2", "7", "13", "1", "1", "ok"}}};
  const Selection s = select_table(spec.selects[0], t);
  REQUIRE(s.table.rows.size() == 1);
  CHECK(s.table.rows[0] == std::vector<std::string>{"true", "x1", "7", "13", "1", "1", "ok"});
  CHECK(s.line == "c.csv: smallest width, then height with seal_mm >= 0.5 and area >= 0: width 7, height 13");
  // No row qualifies: the group is still there.
  t.rows = {{"x1", "7", "27", "1", "0.1", "ok"}};
  CHECK(select_table(spec.selects[0], t).table.rows[0][0] == "false");
}

TEST_CASE("select: the table and its line are written beside each other", "[pipeline]") {
  TempDir tmp("select_write");
  const PipelineSpec spec = parse(with_select(R"({"csv": "out/choice.csv", "from": "sizing.csv",
      "group_by": ["stiffness"], "at_least": {"seal_mm": 1}, "minimize": ["area"]})"));
  const SelectResult r = write_select(spec.selects[0], sizing, tmp.path());
  CHECK(r.rows == 3);
  CHECK(r.text == tmp.path() / "out/choice.txt");
  CHECK(read_text(r.text) == r.line + "\n");
  // No "where": the unsettled run's row competes too, and is the smallest.
  CHECK(read_text(r.path).rfind("stiffness,found,width,height,area,seal_mm,status\nx1,true,0,0,200,5.0,not_converged\n", 0) == 0);
}

TEST_CASE("select: a bad entry is one line naming its key, before anything runs", "[pipeline]") {
  const std::string ok = R"("csv": "c.csv", "from": "sizing.csv", "group_by": ["stiffness"], )";
  CHECK(message_of(with_select("{" + ok + R"("at_least": {"seal_mm": 1}})")) ==
        "P.json: select[0].minimize: expected a non-empty list of column names, found nothing (the key is required)");
  CHECK(message_of(with_select("{" + ok + R"("at_least": {"seal": 1}, "minimize": ["area"]})")) ==
        "P.json: select[0].at_least.seal: expected a column of sizing.csv (stiffness, width, height, area, seal_mm, "
        "status), found \"seal\"");
  CHECK(message_of(with_select("{" + ok + R"("at_least": {"seal_mm": "1 mm"}, "minimize": ["area"]})")) ==
        "P.json: select[0].at_least.seal_mm: expected a finite number, found string \"1 mm\"");
  CHECK(message_of(with_select("{" + ok + R"("at_least": {}, "minimize": ["area"]})")).find(
            "select[0].at_least: expected a non-empty object") != std::string::npos);
  CHECK(message_of(with_select("{" + ok + R"("at_least": {"seal_mm": 1}, "minimize": ["area", "area"]})")) ==
        "P.json: select[0].minimize[1]: expected a column not named before in minimize, found \"area\"");
  CHECK(message_of(with_select(R"({"csv": "sizing.csv", "from": "sizing.csv", "group_by": [], "at_least": {"seal_mm": 1},
      "minimize": ["area"]})")).find("select[0].csv: expected a file name not used by another table") != std::string::npos);
  CHECK(message_of(with_select(R"({"csv": "c.txt", "from": "sizing.csv", "group_by": [], "at_least": {"seal_mm": 1},
      "minimize": ["area"]})")).find("select[0].csv: expected a file name ending in .csv") != std::string::npos);
  CHECK(message_of(with_select("{" + ok + R"("at_least": {"seal_mm": 1}, "minimize": ["area"], "agree": ["width"]})"))
            .find("select[0]") != std::string::npos);
  // A plot may draw the selection.
  const PipelineSpec with_plot = parse(R"json({"steps": [{"stage": "valve-simulate", "args": []}],
    "gather": [{"csv": "s.csv", "summary": "s.json", "columns": {"a": "summary:a", "b": "summary:b"}}],
    "select": [{"csv": "c.csv", "from": "s.csv", "group_by": [], "at_least": {"a": 1}, "minimize": ["b"]}],
    "plots": [{"png": "p.png", "csv": "c.csv", "gnuplot": "plot '${csv}' using (column('b')):(column('found'))"}]})json");
  CHECK(with_plot.plots.size() == 1);
}
