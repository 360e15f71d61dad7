#include "valve/pipeline/selection.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/aggregate.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

std::string join_words(const std::vector<std::string>& words, const std::string& separator) {
  std::string out;
  for (size_t i = 0; i < words.size(); ++i) out += (i ? separator : "") + words[i];
  return out;
}

}  // namespace

Selection select_table(const SelectSpec& select, const CsvTable& from) {
  auto index = [&](const std::string& c) { return table_column(from, c, select.key, select.from); };
  const RowGrouping grouping(from, select.where, select.group_by, select.key, select.from);
  const std::vector<size_t>& keys = grouping.key_columns();
  std::vector<size_t> order, agree;
  for (const auto& c : select.minimize) order.push_back(index(c));
  for (const auto& c : select.agree_on) agree.push_back(index(c));
  std::vector<size_t> bounded;
  for (const auto& t : select.thresholds) bounded.push_back(index(t.column));

  // Per group (in order of first appearance among the rows that pass "where"): the best row
  // so far and its minimized values.
  struct Choice {
    std::vector<std::string> key;
    const std::vector<std::string>* row = nullptr;
    std::vector<double> rank;
  };
  std::vector<Choice> groups;
  std::map<std::vector<std::string>, size_t> group_of;
  if (keys.empty()) groups.push_back({}), group_of[{}] = 0;
  for (const auto& row : from.rows) {
    if (!grouping.kept(row)) continue;
    const std::vector<std::string> key = grouping.group(row);
    const auto [it, added] = group_of.emplace(key, groups.size());
    if (added) groups.push_back({key, nullptr, {}});
    Choice& g = groups[it->second];
    bool meets = true;
    for (size_t k = 0; k < bounded.size() && meets; ++k) {
      const SelectThreshold& t = select.thresholds[k];
      const auto x = numeric_cell(table_cell(row, bounded[k]));
      meets = x && (t.at_most ? *x <= t.bound : *x >= t.bound);
    }
    if (!meets) continue;
    std::vector<double> rank;
    for (size_t c : order) {
      const auto x = numeric_cell(table_cell(row, c));
      if (!x) break;
      rank.push_back(*x);
    }
    if (rank.size() != order.size()) continue;
    if (!g.row || rank < g.rank) g.row = &row, g.rank = rank;  // strict: ties keep the earlier row
  }

  Selection out;
  out.table.header = select.header;
  std::vector<std::string> choices;
  std::optional<std::vector<std::string>> first_agreed;
  bool all_found = true, agree_everywhere = true;
  const std::vector<size_t>& named = agree.empty() ? order : agree;
  const std::vector<std::string>& named_columns = agree.empty() ? select.minimize : select.agree_on;
  for (const Choice& g : groups) {
    std::vector<std::string> row = g.key;
    row.push_back(g.row ? "true" : "false");
    for (size_t c = 0; c < from.header.size(); ++c)
      if (std::find(keys.begin(), keys.end(), c) == keys.end())
        row.push_back(g.row ? table_cell(*g.row, c) : std::string());
    out.table.rows.push_back(row);

    std::vector<std::string> label;
    for (size_t k = 0; k < keys.size(); ++k) label.push_back(select.group_by[k] + " " + g.key[k]);
    std::string choice = label.empty() ? std::string() : join_words(label, ", ") + ": ";
    if (!g.row) {
      choice += "none";
      all_found = false;
    } else {
      std::vector<std::string> values, agreed;
      for (size_t k = 0; k < named.size(); ++k) {
        const std::string v = table_cell(*g.row, named[k]);
        values.push_back(named_columns[k] + " " + v);
        agreed.push_back(v);
      }
      choice += join_words(values, ", ");
      if (!first_agreed) first_agreed = agreed;
      else if (*first_agreed != agreed) agree_everywhere = false;
    }
    choices.push_back(choice);
  }
  std::vector<std::string> rule;
  for (const auto& t : select.thresholds) rule.push_back(t.column + (t.at_most ? " <= " : " >= ") + format_number(t.bound));
  out.line = select.csv + ": smallest " + join_words(select.minimize, ", then ") + " with " + join_words(rule, " and ") +
             ": " + join_words(choices, "; ");
  if (!select.agree_on.empty() && groups.size() > 1) {
    const std::string columns = join_words(select.agree_on, ", ");
    if (!all_found)
      out.line += "; not every " + join_words(select.group_by, ", ") + " has a qualifying row";
    else if (agree_everywhere)
      out.line += "; " + columns + " the same for every " + join_words(select.group_by, ", ");
    else
      out.line += "; " + columns + " change with " + join_words(select.group_by, ", ");
  }
  return out;
}

SelectResult write_select(const SelectSpec& select, const CsvTable& from, const fs::path& out_dir) {
  const Selection s = select_table(select, from);
  SelectResult out{out_dir / select.csv, out_dir / fs::path(select.csv).replace_extension(".txt"), select.from, s.line,
                   s.table.rows.size()};
  write_file_atomic(out.path, to_csv(s.table));
  write_file_atomic(out.text, s.line + "\n");
  return out;
}

}  // namespace valve
