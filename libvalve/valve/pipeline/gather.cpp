#include "valve/pipeline/gather.hpp"

#include <unistd.h>

#include <algorithm>
#include <map>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <regex>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/aggregate.hpp"
#include "valve/pipeline/process.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

std::string gnuplot_string(const fs::path& p) {
  // gnuplot single-quoted strings escape a quote by doubling it.
  std::string out = "'";
  for (char c : p.string()) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string to_csv(const CsvTable& table) {
  std::string out;
  auto line = [&out](const std::vector<std::string>& fields) {
    for (size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + csv_field(fields[i]);
    out += "\n";
  };
  line(table.header);
  for (const auto& row : table.rows) line(row);
  return out;
}

std::string cell_text(const ojson* v) {
  if (!v || v->is_null()) return "";
  if (v->is_number_float()) {
    const double x = v->get<double>();
    if (!std::isfinite(x)) return "";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", x);
    return buf;
  }
  if (v->is_number()) return v->dump();
  if (v->is_string()) return v->get<std::string>();
  if (v->is_boolean()) return v->get<bool>() ? "true" : "false";
  return v->dump();
}

namespace {

// A run's JSON file, or null (reported in `missing`) when it is absent or not JSON: the
// cells that read it are then empty.
ojson read_run_json(const std::string& run_id, const fs::path& file, std::vector<MissingSummary>* missing) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    if (missing) missing->push_back({run_id, file.string() + ": no such file"});
    return nullptr;
  }
  try {
    return ojson::parse(read_text_file(file));
  } catch (const std::exception&) {
    if (missing) missing->push_back({run_id, file.string() + ": not valid JSON"});
    return nullptr;
  }
}

}  // namespace

CsvTable gather_table(const PipelineSpec& spec, const GatherSpec& gather, const std::vector<RunPlan>& runs,
                      const fs::path& out_dir, std::vector<MissingSummary>* missing) {
  CsvTable table;
  for (const auto& c : gather.columns) table.header.push_back(c.header);
  for (const auto& run : runs) {
    const Bindings b = run_bindings(spec, run, out_dir);
    const fs::path file = run_file(spec, run, out_dir, substitute(gather.summary, b, spec.file, gather.key + ".summary"));
    const ojson summary = read_run_json(run.run_id, file, missing);
    std::map<std::string, ojson> other_files;  // file: columns, read once per run
    auto file_value = [&](const ColumnSpec& c) -> const ojson* {
      const std::string name = substitute(c.file, b, spec.file, gather.key + ".columns." + c.header);
      auto it = other_files.find(name);
      if (it == other_files.end()) it = other_files.emplace(name, read_run_json(run.run_id, run_file(spec, run, out_dir, name), missing)).first;
      return find_path(it->second, c.text);
    };
    std::vector<const ojson*> elements{nullptr};
    if (!gather.rows.empty()) {
      const ojson* rows = find_path(summary, gather.rows);
      if (rows && rows->is_array()) {
        elements.clear();
        for (const auto& e : *rows) elements.push_back(&e);
      }
    }
    for (const ojson* element : elements) {
      std::function<std::string(const ColumnSpec&)> cell = [&](const ColumnSpec& c) -> std::string {
        switch (c.source) {
          case ColumnSpec::Source::literal:
            return substitute(c.text, b, spec.file, gather.key + ".columns." + c.header);
          case ColumnSpec::Source::summary:
            return cell_text(find_path(summary, c.text));
          case ColumnSpec::Source::row:
            return cell_text(element ? find_path(*element, c.text) : nullptr);
          case ColumnSpec::Source::file:
            return cell_text(file_value(c));
          case ColumnSpec::Source::min:
          case ColumnSpec::Source::max: {
            // Every part must be a number: the extreme of what happens to be present would
            // pass a run that lost one of its measures for a run that measured it.
            std::optional<double> extreme;
            for (const auto& part : c.parts) {
              const auto x = numeric_cell(cell(part));
              if (!x) return "";
              if (!extreme || (c.source == ColumnSpec::Source::min ? *x < *extreme : *x > *extreme)) extreme = x;
            }
            const ojson value = *extreme;
            return cell_text(&value);
          }
        }
        return "";
      };
      std::vector<std::string> row;
      for (const auto& c : gather.columns) row.push_back(cell(c));
      table.rows.push_back(row);
    }
  }
  return table;
}

GatherResult write_gather(const PipelineSpec& spec, const GatherSpec& gather, const std::vector<RunPlan>& runs,
                          const fs::path& out_dir) {
  GatherResult result;
  const CsvTable table = gather_table(spec, gather, runs, out_dir, &result.missing);
  result.path = out_dir / gather.csv;
  result.rows = table.rows.size();
  write_file_atomic(result.path, to_csv(table));
  return result;
}

CsvTable gather_csv_table(const PipelineSpec& spec, const std::string& csv, const std::vector<RunPlan>& runs,
                          const fs::path& out_dir, std::vector<MissingSummary>* missing) {
  CsvTable table;
  bool first = true;
  for (const auto& g : spec.gather) {
    if (g.csv != csv) continue;
    std::vector<MissingSummary> gaps;
    CsvTable part = gather_table(spec, g, runs, out_dir, &gaps);
    // Entries sharing a csv often read the same summary: report each missing file once.
    for (const auto& gap : gaps)
      if (missing && std::none_of(missing->begin(), missing->end(), [&](const MissingSummary& m) {
            return m.run_id == gap.run_id && m.reason == gap.reason;
          }))
        missing->push_back(gap);
    if (first) table.header = part.header;
    first = false;
    for (auto& row : part.rows) table.rows.push_back(std::move(row));
  }
  if (first) throw Error(spec.file + ": no gather entry writes " + csv);
  return table;
}

GatherResult write_gather_csv(const PipelineSpec& spec, const std::string& csv, const std::vector<RunPlan>& runs,
                              const fs::path& out_dir, CsvTable* table) {
  GatherResult result;
  const CsvTable t = gather_csv_table(spec, csv, runs, out_dir, &result.missing);
  result.path = out_dir / csv;
  result.rows = t.rows.size();
  write_file_atomic(result.path, to_csv(t));
  if (table) *table = t;
  return result;
}

std::string plot_script(const PipelineSpec& spec, const PlotSpec& plot, const fs::path& out_dir,
                        const fs::path& png_path) {
  const Bindings b{{"csv", (out_dir / plot.csv).string()},
                   {"png", (out_dir / plot.png).string()},
                   {"out_dir", out_dir.string()},
                   {"pipeline_dir", spec.pipeline_dir.string()}};
  const std::string text = substitute(plot.gnuplot, b, spec.file, plot.key + ".gnuplot");
  static const std::regex sets_terminal(R"(\bset\s+t(e|er|erm|ermi|ermin|ermina|erminal)?\b)");
  std::string script = "# " + spec.file + " " + plot.key + ", written by valve-pipeline\n";
  if (!std::regex_search(text, sets_terminal)) script += "set terminal pngcairo noenhanced size 900,600\n";
  script += "set datafile separator ','\n";
  script += "set output " + gnuplot_string(png_path) + "\n";
  script += text;
  if (!text.empty() && text.back() != '\n') script += "\n";
  script += "unset output\n";  // closes the file before gnuplot exits
  return script;
}

PlotResult render_plot(const PipelineSpec& spec, const PlotSpec& plot, const fs::path& out_dir,
                       const std::optional<fs::path>& gnuplot) {
  PlotResult result{plot.png, "made", ""};
  const fs::path png = out_dir / plot.png;
  write_file_atomic(out_dir / (plot.png + ".gp"), plot_script(spec, plot, out_dir, png));
  if (!gnuplot) return {plot.png, "skipped", "gnuplot is not on PATH"};

  // Run a copy of the script that writes a temporary image, so a failed plot never leaves a
  // half-written PNG and never replaces a good one from an earlier run.
  const std::string tag = ".tmp" + std::to_string(::getpid());
  const fs::path tmp_png = png.parent_path() / ("." + png.filename().string() + tag + ".png");
  const fs::path tmp_script = png.parent_path() / ("." + png.filename().string() + tag + ".gp");
  const fs::path log = out_dir / (plot.png + ".log");
  write_file_atomic(tmp_script, plot_script(spec, plot, out_dir, tmp_png));
  const ProcessExit exit = run_process(*gnuplot, {tmp_script.string()}, out_dir, log);
  std::error_code ec;
  fs::remove(tmp_script, ec);
  if (exit.code != 0) {
    result = {plot.png, "failed",
              "gnuplot exited with " + std::to_string(exit.code) + (exit.error.empty() ? "" : " (" + exit.error + ")") +
                  ", see " + log.string()};
  } else if (!fs::is_regular_file(tmp_png, ec) || fs::file_size(tmp_png, ec) == 0) {
    result = {plot.png, "failed", "gnuplot wrote no image, see " + log.string()};
  } else {
    fs::rename(tmp_png, png, ec);
    if (ec) result = {plot.png, "failed", png.string() + ": cannot move the image into place: " + ec.message()};
  }
  fs::remove(tmp_png, ec);
  return result;
}

}  // namespace valve
