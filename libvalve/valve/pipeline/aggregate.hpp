#pragma once
// Grouped statistics of a gathered table: the "aggregate" entries of a pipeline (format and
// rules in pipeline_spec.hpp). Aggregates work on the cell texts of the table as written,
// so a table read back from its CSV gives the same result as the one held in memory.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "valve/pipeline/gather.hpp"
#include "valve/pipeline/pipeline_spec.hpp"

namespace valve {

/// A cell as a number: decimal text ("3", "-0.5", "1e-05", "+2.") that is finite; nullopt
/// for empty cells, words, "nan", "inf" and hexadecimal.
std::optional<double> numeric_cell(const std::string& text);

/// One statistic ("mean", "sd", "min", "max", "median", "count"; true_count is counted by
/// aggregate_table from the cell texts) of `values` as a cell:
/// empty when undefined (no values; sd of fewer than 2), integral values exactly, others
/// with %.10g. `values` need not be sorted.
std::string stat_cell(const std::string& stat, std::vector<double> values);

/// The "where" filters and group_by columns of an aggregate or select entry, found in a
/// table's header (an Error naming `key` when one is missing); cells read by table_cell.
class RowGrouping {
 public:
  RowGrouping(const CsvTable& table, const std::vector<AggregateFilter>& where,
              const std::vector<std::string>& group_by, const std::string& key, const std::string& from);
  bool kept(const std::vector<std::string>& row) const;               ///< passes every filter
  std::vector<std::string> group(const std::vector<std::string>& row) const;  ///< its group_by cells
  bool grouped() const { return !keys_.empty(); }
  const std::vector<size_t>& key_columns() const { return keys_; }

 private:
  std::vector<std::pair<size_t, const AggregateFilter*>> filters_;
  std::vector<size_t> keys_;
};

/// Cell `c` of `row`; a short row (never written by gather) reads as empty cells.
std::string table_cell(const std::vector<std::string>& row, size_t c);

/// Index of `column` in the table's header; an Error naming `key` and `from` when absent.
size_t table_column(const CsvTable& table, const std::string& column, const std::string& key, const std::string& from);

/// The aggregate table of `from` (whose header must hold every column the spec names,
/// which parse_pipeline has checked; an Error otherwise).
CsvTable aggregate_table(const AggregateSpec& aggregate, const CsvTable& from);

struct AggregateResult {
  std::filesystem::path path;  ///< DIR/<csv>
  std::string from;            ///< the source csv, relative to DIR
  size_t rows = 0;
};

/// aggregate_table, written atomically to DIR/<csv>; the table is also stored in `*table`
/// when given, for later aggregates that read it.
AggregateResult write_aggregate(const AggregateSpec& aggregate, const CsvTable& from,
                                const std::filesystem::path& out_dir, CsvTable* table = nullptr);

}  // namespace valve
