#pragma once
// Gathering run results into CSV tables and plotting them with gnuplot.
//
// A gather table has one row per run (in run order), or, with "rows", one row per element
// of that array in the run's summary. A CSV named by several gather entries holds their
// tables one after the other, in entry order, under their common header. Missing data never drops a run silently: a run whose
// summary is missing or unreadable, or has no "rows" array, still gets one row, with empty
// cells where values are missing (an empty "rows" array gives no row: it is data, not a gap).
// Cells: strings as they are, integers exactly, other numbers with %.10g, non-finite
// numbers and nulls empty, booleans true/false, objects and arrays as compact JSON.
// CSV: a header row, fields quoted per RFC 4180 only when they hold , " CR or LF,
// lines ending in \n.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "valve/pipeline/pipeline_spec.hpp"

namespace valve {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// One field, quoted when RFC 4180 requires it.
std::string csv_field(const std::string& text);

/// The whole table as CSV text.
std::string to_csv(const CsvTable& table);

/// A JSON value as a CSV cell (see the header comment); nullptr gives an empty cell.
std::string cell_text(const ojson* value);

/// A run whose summary could not be used, and why.
struct MissingSummary {
  std::string run_id, reason;
};

/// Builds the table of `gather` over `runs` (summaries read from each run folder).
CsvTable gather_table(const PipelineSpec& spec, const GatherSpec& gather, const std::vector<RunPlan>& runs,
                      const std::filesystem::path& out_dir, std::vector<MissingSummary>* missing = nullptr);

struct GatherResult {
  std::filesystem::path path;  ///< DIR/<csv>
  size_t rows = 0;
  std::vector<MissingSummary> missing;
};

/// gather_table of one entry alone, written atomically to DIR/<csv>.
GatherResult write_gather(const PipelineSpec& spec, const GatherSpec& gather, const std::vector<RunPlan>& runs,
                          const std::filesystem::path& out_dir);

/// The table of the CSV `csv`: the gather_table of every entry naming it, concatenated in
/// entry order (parse_pipeline has checked that they share one header).
CsvTable gather_csv_table(const PipelineSpec& spec, const std::string& csv, const std::vector<RunPlan>& runs,
                          const std::filesystem::path& out_dir, std::vector<MissingSummary>* missing = nullptr);

/// gather_csv_table, written atomically to DIR/<csv>; the table is also stored in `*table`
/// when given, for the aggregates that read it. What the runner writes, once per CSV.
GatherResult write_gather_csv(const PipelineSpec& spec, const std::string& csv, const std::vector<RunPlan>& runs,
                              const std::filesystem::path& out_dir, CsvTable* table = nullptr);

struct PlotResult {
  std::string png;
  std::string status;  ///< "made", "skipped" (no gnuplot) or "failed"
  std::string reason;
};

/// The gnuplot script of a plot writing to `png_path`: "set terminal pngcairo noenhanced
/// size 900,600" unless the text sets a terminal (noenhanced: run ids and column names
/// from the CSV keep their underscores), "set datafile separator ','", "set output", the
/// text with ${csv}, ${png}, ${out_dir}, ${pipeline_dir} substituted, and "unset output".
std::string plot_script(const PipelineSpec& spec, const PlotSpec& plot, const std::filesystem::path& out_dir,
                        const std::filesystem::path& png_path);

/// Writes DIR/<png>.gp (the script, to re-run by hand) and, when `gnuplot` is given, runs it
/// in DIR with its output in DIR/<png>.log; the image is written to a temporary file and
/// renamed into place only when gnuplot succeeds.
PlotResult render_plot(const PipelineSpec& spec, const PlotSpec& plot, const std::filesystem::path& out_dir,
                       const std::optional<std::filesystem::path>& gnuplot);

}  // namespace valve
