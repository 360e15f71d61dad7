#include "valve/pipeline/aggregate.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

std::string number_cell(double x) {
  // Integral values exactly (counts, min/max of integer columns); the rest like gather cells.
  char buf[40];
  if (x == std::floor(x) && std::fabs(x) < 1e15)
    std::snprintf(buf, sizeof buf, "%.0f", x == 0 ? 0.0 : x);  // no "-0"
  else
    std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

}  // namespace

std::string table_cell(const std::vector<std::string>& row, size_t c) { return c < row.size() ? row[c] : std::string(); }

size_t table_column(const CsvTable& table, const std::string& column, const std::string& key, const std::string& from) {
  const auto it = std::find(table.header.begin(), table.header.end(), column);
  if (it == table.header.end()) throw Error(key + ": the table " + from + " has no column " + column);
  return static_cast<size_t>(it - table.header.begin());
}

RowGrouping::RowGrouping(const CsvTable& table, const std::vector<AggregateFilter>& where,
                         const std::vector<std::string>& group_by, const std::string& key, const std::string& from) {
  for (const auto& f : where) filters_.emplace_back(table_column(table, f.column, key, from), &f);
  for (const auto& g : group_by) keys_.push_back(table_column(table, g, key, from));
}

bool RowGrouping::kept(const std::vector<std::string>& row) const {
  return std::all_of(filters_.begin(), filters_.end(), [&](const auto& f) {
    return std::find(f.second->values.begin(), f.second->values.end(), table_cell(row, f.first)) != f.second->values.end();
  });
}

std::vector<std::string> RowGrouping::group(const std::vector<std::string>& row) const {
  std::vector<std::string> key;
  for (size_t c : keys_) key.push_back(table_cell(row, c));
  return key;
}

std::optional<double> numeric_cell(const std::string& text) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  // from_chars is locale-independent and takes no '+'; allow one before a digit or point.
  if (begin != end && *begin == '+' && begin + 1 != end && (std::isdigit(static_cast<unsigned char>(begin[1])) || begin[1] == '.'))
    ++begin;
  if (begin == end) return std::nullopt;
  double x = 0;
  const auto [ptr, ec] = std::from_chars(begin, end, x, std::chars_format::general);
  if (ec != std::errc() || ptr != end || !std::isfinite(x)) return std::nullopt;
  return x;
}

std::string stat_cell(const std::string& stat, std::vector<double> values) {
  const size_t n = values.size();
  if (stat == "count") return number_cell(static_cast<double>(n));
  if (n == 0) return "";
  double sum = 0;
  for (double v : values) sum += v;
  const double mean = sum / static_cast<double>(n);
  if (stat == "mean") return number_cell(mean);
  if (stat == "sd") {
    if (n < 2) return "";
    // Two passes: the one-pass sum of squares loses digits when the spread is small
    // compared with the mean (strains around 1 differing in the 6th digit).
    double squares = 0;
    for (double v : values) squares += (v - mean) * (v - mean);
    return number_cell(std::sqrt(squares / static_cast<double>(n - 1)));
  }
  if (stat == "min") return number_cell(*std::min_element(values.begin(), values.end()));
  if (stat == "max") return number_cell(*std::max_element(values.begin(), values.end()));
  if (stat == "median") {
    std::sort(values.begin(), values.end());
    const double mid = n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
    return number_cell(mid);
  }
  throw Error("aggregate: unknown stat " + stat);
}

CsvTable aggregate_table(const AggregateSpec& aggregate, const CsvTable& from) {
  const RowGrouping grouping(from, aggregate.where, aggregate.group_by, aggregate.key, aggregate.from);
  std::vector<size_t> value_columns;
  for (const auto& s : aggregate.stats) value_columns.push_back(table_column(from, s.column, aggregate.key, aggregate.from));

  // Per group (in order of first appearance): the numeric values of each stats column.
  std::vector<std::vector<std::string>> group_keys;
  std::vector<std::vector<std::vector<double>>> group_values;
  std::vector<std::vector<size_t>> group_true;  // cells "true" (booleans are written so)
  std::map<std::vector<std::string>, size_t> group_of;
  auto group_for = [&](const std::vector<std::string>& key) {
    const auto [it, added] = group_of.emplace(key, group_keys.size());
    if (added) {
      group_keys.push_back(key);
      group_values.emplace_back(value_columns.size());
      group_true.emplace_back(value_columns.size(), 0);
    }
    return it->second;
  };
  // No group_by: the whole table is one group, present even when no row passes (count 0).
  if (!grouping.grouped()) group_for({});

  for (const auto& row : from.rows) {
    if (!grouping.kept(row)) continue;
    const size_t g = group_for(grouping.group(row));
    for (size_t v = 0; v < value_columns.size(); ++v) {
      const std::string cell = table_cell(row, value_columns[v]);
      if (const auto x = numeric_cell(cell)) group_values[g][v].push_back(*x);
      group_true[g][v] += cell == "true" ? 1 : 0;
    }
  }

  CsvTable table;
  table.header = aggregate.header;
  for (size_t g = 0; g < group_keys.size(); ++g) {
    std::vector<std::string> row = group_keys[g];
    for (size_t v = 0; v < aggregate.stats.size(); ++v)
      for (const auto& stat : aggregate.stats[v].stats)
        row.push_back(stat == "true_count" ? number_cell(static_cast<double>(group_true[g][v]))
                                           : stat_cell(stat, group_values[g][v]));
    table.rows.push_back(row);
  }
  return table;
}

AggregateResult write_aggregate(const AggregateSpec& aggregate, const CsvTable& from, const fs::path& out_dir,
                                CsvTable* table) {
  const CsvTable result = aggregate_table(aggregate, from);
  AggregateResult out{out_dir / aggregate.csv, aggregate.from, result.rows.size()};
  write_file_atomic(out.path, to_csv(result));
  if (table) *table = result;
  return out;
}

}  // namespace valve
