#include "valve/pipeline/pipeline_spec.hpp"

#include <algorithm>
#include <functional>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <set>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

// Big sweeps are almost always a typo (a range step of 0.001 instead of 0.1); a pipeline
// that really needs more runs should be split.
constexpr std::size_t max_runs = 100000;

const std::vector<std::string> run_builtins{"run_dir", "run_id", "out_dir", "pipeline_dir"};
const std::vector<std::string> plot_builtins{"csv", "png", "out_dir", "pipeline_dir"};

std::string describe(const ojson& v) {
  std::string dump = v.dump();
  if (dump.size() > 60) dump = dump.substr(0, 57) + "...";
  return std::string(v.type_name()) + " " + dump;
}

[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& expected,
                       const std::string& found) {
  throw_input_error(file, key, expected, found);
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

std::string child_key(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

void check_keys(const ojson& obj, const std::vector<std::string>& allowed, const std::string& file,
                const std::string& path) {
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end())
      fail(file, child_key(path, it.key()), "a known key (" + join(allowed, ", ") + ")", "an unknown key");
}

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// A placeholder reference: an identifier, then optional ".field" parts (letters, digits, _ -).
bool is_reference(const std::string& s) {
  const auto dot = s.find('.');
  if (!is_identifier(s.substr(0, dot))) return false;
  if (dot == std::string::npos) return true;
  std::string part;
  for (size_t i = dot + 1; i <= s.size(); ++i) {
    if (i == s.size() || s[i] == '.') {
      if (part.empty()) return false;
      part.clear();
    } else if (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_' || s[i] == '-') {
      part += s[i];
    } else {
      return false;
    }
  }
  return true;
}

struct Piece {
  bool placeholder = false;
  std::string text;  // literal text, or the reference inside ${...}
};

std::vector<Piece> split_placeholders(const std::string& s, const std::string& file, const std::string& key) {
  std::vector<Piece> out;
  std::string literal;
  for (size_t i = 0; i < s.size();) {
    if (s.compare(i, 3, "$${") == 0) {
      literal += "${";
      i += 3;
    } else if (s.compare(i, 2, "${") == 0) {
      const auto close = s.find('}', i + 2);
      if (close == std::string::npos) fail(file, key, "a closing } after ${", s.substr(i));
      const std::string inner = s.substr(i + 2, close - i - 2);
      if (!is_reference(inner)) fail(file, key, "a variable name inside ${...}", "${" + inner + "}");
      if (!literal.empty()) out.push_back({false, literal});
      literal.clear();
      out.push_back({true, inner});
      i = close + 1;
    } else {
      literal += s[i++];
    }
  }
  if (!literal.empty()) out.push_back({false, literal});
  return out;
}

std::pair<std::string, std::string> split_reference(const std::string& ref) {
  const auto dot = ref.find('.');
  if (dot == std::string::npos) return {ref, ""};
  return {ref.substr(0, dot), ref.substr(dot + 1)};
}

/// Checks every placeholder of `text` against the builtins and variables before anything
/// runs, so that a typo in the last step of the last run is found in the first second.
void check_placeholders(const std::string& text, const std::vector<std::string>& builtins,
                        const std::vector<SweepVariable>& variables, const std::string& file,
                        const std::string& key) {
  for (const auto& piece : split_placeholders(text, file, key)) {
    if (!piece.placeholder) continue;
    const auto [name, field] = split_reference(piece.text);
    const auto var = std::find_if(variables.begin(), variables.end(),
                                  [&](const SweepVariable& v) { return v.name == name; });
    if (var == variables.end()) {
      if (std::find(builtins.begin(), builtins.end(), name) == builtins.end())
        fail(file, key, "a known variable", "${" + piece.text + "}");
      if (!field.empty()) fail(file, key, "a field of an object-valued variable", "${" + piece.text + "}");
      continue;
    }
    if (field.empty()) continue;
    for (size_t k = 0; k < var->values.size(); ++k)
      if (!find_path(var->values[k], field))
        fail(file, key, "a field " + field + " in every value of " + name,
             "${" + piece.text + "} (missing in variables." + name + "[" + std::to_string(k) + "])");
  }
}

std::string required_string(const ojson& obj, const std::string& k, const std::string& file,
                            const std::string& path) {
  const std::string key = child_key(path, k);
  if (!obj.contains(k)) fail(file, key, "a string", "nothing (the key is required)");
  const ojson& v = obj.at(k);
  if (!v.is_string() || v.get<std::string>().empty()) fail(file, key, "a non-empty string", describe(v));
  return v.get<std::string>();
}

/// A relative path that stays inside the folder it is relative to.
std::string inside_path(const ojson& obj, const std::string& k, const std::string& file,
                        const std::string& path) {
  const std::string text = required_string(obj, k, file, path);
  const fs::path p = fs::path(text).lexically_normal();
  bool escapes = p.is_absolute() || !p.has_filename() || p.empty();
  for (const auto& part : p)
    if (part == "..") escapes = true;
  // runs/ and the summary belong to the runner.
  escapes = escapes || *p.begin() == "runs" || p == "pipeline.summary.json";
  if (escapes)
    fail(file, child_key(path, k), "a relative file path inside the output folder (not in runs/, not pipeline.summary.json)",
         "\"" + text + "\"");
  return p.string();
}

bool is_file_name_part(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
}

SweepVariable parse_variable(const std::string& name, const ojson& v, const std::string& file) {
  const std::string key = "variables." + name;
  if (!is_identifier(name))
    fail(file, key, "a variable name of letters, digits and _ (not starting with a digit)", "\"" + name + "\"");
  for (const auto* list : {&run_builtins, &plot_builtins})
    if (std::find(list->begin(), list->end(), name) != list->end())
      fail(file, key, "a variable name other than the built-ins (" + join(run_builtins, ", ") + ", csv, png)",
           "\"" + name + "\"");
  SweepVariable var{name, {}};
  if (v.is_array()) {
    if (v.empty()) fail(file, key, "a non-empty list of values", "an empty list");
    for (size_t k = 0; k < v.size(); ++k) {
      const ojson& e = v[k];
      if (e.is_number_float() && !std::isfinite(e.get<double>()))
        fail(file, key + "[" + std::to_string(k) + "]", "a finite number", describe(e));
      if (!(e.is_number() || e.is_string() || e.is_boolean() || e.is_object()))
        fail(file, key + "[" + std::to_string(k) + "]", "a number, string, boolean or object", describe(e));
      var.values.push_back(e);
    }
    return var;
  }
  if (!v.is_object() || !v.contains("range"))
    fail(file, key, "a list of values or {\"range\": [a, b]} or {\"range\": [a, b, step]}", describe(v));
  check_keys(v, {"range"}, file, key);
  const ojson& r = v["range"];
  const std::string rkey = key + ".range";
  if (!r.is_array() || r.size() < 2 || r.size() > 3) fail(file, rkey, "[a, b] or [a, b, step]", describe(r));
  bool integral = true;
  for (const auto& e : r) {
    if (!e.is_number() || !std::isfinite(e.get<double>())) fail(file, rkey, "finite numbers", describe(r));
    integral = integral && (e.is_number_integer() || e.get<double>() == std::floor(e.get<double>()));
  }
  const double a = r[0].get<double>(), b = r[1].get<double>();
  const double step = r.size() == 3 ? r[2].get<double>() : (b >= a ? 1.0 : -1.0);
  if (step == 0) fail(file, rkey, "a nonzero step", describe(r));
  if ((b - a) * step < 0) fail(file, rkey, "a step that moves from a towards b", describe(r));
  // The small tolerance keeps b when (b - a) / step is an integer up to rounding (0.1 steps).
  const double count = std::floor((b - a) / step + 1e-9) + 1;
  if (count > static_cast<double>(max_runs))
    fail(file, rkey, "at most " + std::to_string(max_runs) + " values", format_number(count));
  // Values are a + k*step rounded to the decimals of a and step, so that 0.1 steps give 0.3,
  // not 0.30000000000000004.
  auto decimals = [](double x) {
    const std::string s = format_number(x);
    const auto dot = s.find('.');
    return (dot == std::string::npos || s.find('e') != std::string::npos) ? -1 : int(s.size() - dot - 1);
  };
  const int da = decimals(a), ds = decimals(step);
  const int digits = (da < 0 && a != std::floor(a)) || (ds < 0 && step != std::floor(step)) ? -1 : std::max({da, ds, 0});
  for (long k = 0; k < static_cast<long>(count); ++k) {
    double x = a + static_cast<double>(k) * step;
    if (integral) {
      var.values.emplace_back(static_cast<long long>(std::llround(x)));
      continue;
    }
    if (digits >= 0) {
      const double scale = std::pow(10.0, digits);
      x = std::round(x * scale) / scale;
    }
    var.values.emplace_back(x);
  }
  return var;
}

StepSpec parse_step(const ojson& s, size_t i, const std::vector<SweepVariable>& variables,
                    const std::string& file) {
  StepSpec step;
  step.key = "steps[" + std::to_string(i) + "]";
  if (!s.is_object()) fail(file, step.key, "an object with stage and args", describe(s));
  check_keys(s, {"name", "stage", "args", "allow_exit", "resources"}, file, step.key);
  step.stage = required_string(s, "stage", file, step.key);
  const std::string suffix = step.stage.rfind("valve-", 0) == 0 ? step.stage.substr(6) : "";
  if (suffix.empty() || !std::all_of(suffix.begin(), suffix.end(), is_file_name_part))
    fail(file, step.key + ".stage", "a stage name valve-<name>", "\"" + step.stage + "\"");
  step.name = s.contains("name") ? required_string(s, "name", file, step.key) : step.stage;
  if (step.name[0] == '.' || !std::all_of(step.name.begin(), step.name.end(), is_file_name_part))
    fail(file, step.key + ".name", "a step name of letters, digits, _ . - (it names the log file)",
         "\"" + step.name + "\"");
  if (!s.contains("args")) fail(file, step.key + ".args", "a list of strings", "nothing (the key is required)");
  const ojson& args = s["args"];
  if (!args.is_array()) fail(file, step.key + ".args", "a list of strings", describe(args));
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string key = step.key + ".args[" + std::to_string(k) + "]";
    if (!args[k].is_string() && !args[k].is_number()) fail(file, key, "a string", describe(args[k]));
    step.args.push_back(value_text(args[k]));
    check_placeholders(step.args.back(), run_builtins, variables, file, key);
  }
  if (s.contains("allow_exit")) {
    const ojson& ae = s["allow_exit"];
    const std::string key = step.key + ".allow_exit";
    if (!ae.is_array() || ae.empty()) fail(file, key, "a non-empty list of exit codes", describe(ae));
    step.allow_exit.clear();
    for (const auto& e : ae) {
      if (!e.is_number_integer() || e.get<long long>() < 0 || e.get<long long>() > 255)
        fail(file, key, "exit codes in [0, 255]", describe(ae));
      step.allow_exit.push_back(e.get<int>());
    }
  }
  if (s.contains("resources")) {
    const ojson& r = s["resources"];
    const std::string key = step.key + ".resources";
    if (!r.is_object()) fail(file, key, "an object of threads, mem_mb, runtime", describe(r));
    check_keys(r, {"threads", "mem_mb", "runtime"}, file, key);
    auto positive = [&](const char* name, int& into) {
      if (!r.contains(name)) return;
      const ojson& v = r[name];
      if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 10000000)
        fail(file, child_key(key, name), "a positive integer", describe(v));
      into = v.get<int>();
    };
    positive("threads", step.resources.threads);
    positive("mem_mb", step.resources.mem_mb);
    positive("runtime", step.resources.runtime_min);
  }
  return step;
}

// Whether a step's arguments use a sweep variable or the run id (they differ between runs).
bool step_varies(const StepSpec& step, const std::vector<SweepVariable>& variables, const std::string& file) {
  for (size_t k = 0; k < step.args.size(); ++k)
    for (const auto& piece : split_placeholders(step.args[k], file, step.key)) {
      if (!piece.placeholder) continue;
      const std::string name = split_reference(piece.text).first;
      if (name == "run_id" || std::any_of(variables.begin(), variables.end(),
                                          [&](const SweepVariable& v) { return v.name == name; }))
        return true;
    }
  return false;
}

const std::string run_dir_prefix = "${run_dir}/";

// The folder of "--out ${run_dir}/<folder>", or "" when the step writes elsewhere.
std::string run_out_folder(const StepSpec& step) {
  for (size_t k = 0; k + 1 < step.args.size(); ++k) {
    if (step.args[k] != "--out") continue;
    const std::string& o = step.args[k + 1];
    if (o.rfind(run_dir_prefix, 0) != 0) return "";
    std::string rel = fs::path(o.substr(run_dir_prefix.size())).lexically_normal().string();
    while (!rel.empty() && rel.back() == '/') rel.pop_back();
    if (rel.empty() || rel == "." || rel.rfind("..", 0) == 0 || rel.find('$') != std::string::npos) return "";
    return rel;
  }
  return "";
}

// Where `text` names `folder` (or a file in it) at `at`: followed by its end, '/' or a
// character that cannot continue a folder name.
bool folder_ends_at(const std::string& text, size_t end) {
  return end == text.size() || !is_file_name_part(text[end]);
}

// Whether an argument names `folder` relative to the working directory (a run folder).
bool names_relative(const std::string& arg, const std::string& folder) {
  for (size_t at = arg.find(folder); at != std::string::npos; at = arg.find(folder, at + 1)) {
    const bool starts = at == 0 || arg[at - 1] == '=' || arg[at - 1] == ',';
    if (starts && folder_ends_at(arg, at + folder.size())) return true;
  }
  return false;
}

// `arg` with every "${run_dir}/<folder>" of a shared folder replaced by its DIR/shared copy.
std::string to_shared(std::string arg, const std::vector<std::string>& folders) {
  for (const auto& folder : folders) {
    const std::string from = run_dir_prefix + folder, to = "${out_dir}/shared/" + folder;
    for (size_t at = arg.find(from); at != std::string::npos; at = arg.find(from, at)) {
      if (!folder_ends_at(arg, at + from.size()) || (at > 0 && arg[at - 1] == '$')) {
        at += from.size();
        continue;
      }
      arg.replace(at, from.size(), to);
      at += to.size();
    }
  }
  return arg;
}

void find_shared_steps(PipelineSpec& spec) {
  if (spec.variables.empty()) return;
  for (size_t i = 0; i < spec.steps.size(); ++i) {
    const StepSpec& step = spec.steps[i];
    const std::string folder = run_out_folder(step);
    if (folder.empty() || step_varies(step, spec.variables, spec.file)) return;
    for (size_t j = i + 1; j < spec.steps.size(); ++j)
      for (const auto& a : spec.steps[j].args)
        if (names_relative(a, folder)) return;
    spec.shared_outs.push_back(folder);
    spec.shared_steps = i + 1;
  }
}

// Levenshtein distance (insertions, deletions, substitutions), for near-miss names.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// A column given as a string: a literal with placeholders, or a summary:, row: or file: source.
ColumnSpec parse_column_text(const std::string& header, const std::string& text, const GatherSpec& spec,
                             const std::vector<SweepVariable>& variables, const std::string& file,
                             const std::string& key) {
  ColumnSpec col{header, ColumnSpec::Source::literal, text, {}, {}};
  if (text.rfind("summary:", 0) == 0) {
    col.source = ColumnSpec::Source::summary;
    col.text = text.substr(8);
  } else if (text.rfind("file:", 0) == 0) {
    const size_t colon = text.find(':', 5);
    if (colon == std::string::npos || colon == 5 || colon + 1 == text.size())
      fail(file, key, "\"file:<json file in the run folder>:<path>\"", "\"" + text + "\"");
    col.source = ColumnSpec::Source::file;
    col.file = text.substr(5, colon - 5);
    col.text = text.substr(colon + 1);
    check_placeholders(col.file, run_builtins, variables, file, key);
  } else if (text.rfind("row:", 0) == 0) {
    if (spec.rows.empty()) fail(file, key, "a \"rows\" path in " + spec.key + " for a row: column", "\"" + text + "\"");
    col.source = ColumnSpec::Source::row;
    col.text = text.substr(4);
  } else {
    // "sumary:status" would otherwise fill the column with its own text on every row; a
    // literal such as "fe:ray" or "http://..." is not near any source's name.
    const size_t colon = text.find(':');
    if (colon != std::string::npos && colon > 0 && colon + 1 < text.size()) {
      const std::string prefix = text.substr(0, colon);
      for (const std::string known : {"summary", "file", "row"})
        if (edit_distance(prefix, known) <= (known.size() >= 6 ? 2u : 1u))
          fail(file, key, "the source " + known + ": (or literal text)", "\"" + prefix + ":\"");
    }
    check_placeholders(text, run_builtins, variables, file, key);
  }
  return col;
}

GatherSpec parse_gather(const ojson& g, size_t i, const std::vector<SweepVariable>& variables,
                        const std::string& file) {
  GatherSpec spec;
  spec.key = "gather[" + std::to_string(i) + "]";
  if (!g.is_object()) fail(file, spec.key, "an object with csv, summary and columns", describe(g));
  check_keys(g, {"csv", "summary", "rows", "columns"}, file, spec.key);
  spec.csv = inside_path(g, "csv", file, spec.key);
  spec.summary = required_string(g, "summary", file, spec.key);
  check_placeholders(spec.summary, run_builtins, variables, file, spec.key + ".summary");
  if (g.contains("rows")) spec.rows = required_string(g, "rows", file, spec.key);
  const std::string ckey = spec.key + ".columns";
  if (!g.contains("columns")) fail(file, ckey, "an object of column specs", "nothing (the key is required)");
  const ojson& cols = g["columns"];
  if (!cols.is_object() || cols.empty()) fail(file, ckey, "a non-empty object of column specs", describe(cols));
  for (auto it = cols.begin(); it != cols.end(); ++it) {
    const std::string key = ckey + "." + it.key();
    const ojson& value = it.value();
    const char* expected =
        "a string (text with ${...}, \"summary:<path>\", \"row:<path>\" or \"file:<file>:<path>\") or "
        "{\"min\" or \"max\": [sources]}";
    if (value.is_string()) {
      spec.columns.push_back(parse_column_text(it.key(), value.get<std::string>(), spec, variables, file, key));
      continue;
    }
    if (!value.is_object() || value.size() != 1 || !(value.contains("min") || value.contains("max")))
      fail(file, key, expected, describe(value));
    const bool is_min = value.contains("min");
    const std::string rkey = key + (is_min ? ".min" : ".max");
    const ojson& list = value.begin().value();
    if (!list.is_array() || list.size() < 2)
      fail(file, rkey, "a list of two or more summary:, row: or file: sources", describe(list));
    ColumnSpec col{it.key(), is_min ? ColumnSpec::Source::min : ColumnSpec::Source::max, "", {}, {}};
    for (size_t k = 0; k < list.size(); ++k) {
      const std::string pkey = rkey + "[" + std::to_string(k) + "]";
      if (!list[k].is_string()) fail(file, pkey, "a summary:, row: or file: source", describe(list[k]));
      ColumnSpec part = parse_column_text(it.key(), list[k].get<std::string>(), spec, variables, file, pkey);
      // A literal among numbers compared would be a constant bound, most likely a misspelt source.
      if (part.source == ColumnSpec::Source::literal)
        fail(file, pkey, "a summary:, row: or file: source", "\"" + list[k].get<std::string>() + "\"");
      col.parts.push_back(std::move(part));
    }
    spec.columns.push_back(col);
  }
  return spec;
}

std::vector<std::string> headers(const std::vector<ColumnSpec>& columns) {
  std::vector<std::string> out;
  for (const auto& c : columns) out.push_back(c.header);
  return out;
}

/// A non-empty list of strings at obj[k], e.g. group_by (which may be empty when allow_empty).
std::vector<std::string> string_list(const ojson& obj, const std::string& k, bool allow_empty, const std::string& file,
                                     const std::string& path) {
  const std::string key = child_key(path, k);
  const std::string what = allow_empty ? "a list of column names" : "a non-empty list of column names";
  if (!obj.contains(k)) fail(file, key, what, "nothing (the key is required)");
  const ojson& v = obj.at(k);
  if (!v.is_array() || (!allow_empty && v.empty())) fail(file, key, what, describe(v));
  std::vector<std::string> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_string() || v[i].get<std::string>().empty())
      fail(file, key + "[" + std::to_string(i) + "]", "a non-empty string", describe(v[i]));
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

/// The header of every table an aggregate may read: the gather CSVs, then the aggregates
/// parsed so far, in order.
using KnownTables = std::vector<std::pair<std::string, std::vector<std::string>>>;

/// The columns of the table `name` (an InputError at key.from when it is not known).
const std::vector<std::string>& known_table(const KnownTables& tables, const std::string& name, const std::string& key,
                                            const std::string& file) {
  const auto table = std::find_if(tables.begin(), tables.end(), [&](const auto& t) { return t.first == name; });
  if (table == tables.end()) {
    std::vector<std::string> names;
    for (const auto& t : tables) names.push_back(t.first);
    fail(file, key + ".from",
         "a gather table or an earlier aggregate table (" + (names.empty() ? std::string("none") : join(names, ", ")) + ")",
         "\"" + name + "\"");
  }
  return table->second;
}

using ColumnCheck = std::function<void(const std::string& name, const std::string& key)>;

/// Fails at `key` when `name` is not a column of the table `from`. Checked when the file is
/// read, not when the table is: a misspelt column would otherwise give an empty statistic
/// after the whole sweep has run.
ColumnCheck column_check(const std::vector<std::string>& columns, const std::string& from, const std::string& file) {
  return [&columns, from, file](const std::string& name, const std::string& key) {
    if (std::find(columns.begin(), columns.end(), name) == columns.end())
      fail(file, key, "a column of " + from + " (" + join(columns, ", ") + ")", "\"" + name + "\"");
  };
}

/// The "where" filters of an aggregate or select entry at `path` (none without the key).
std::vector<AggregateFilter> parse_where(const ojson& a, const std::string& path, const ColumnCheck& check_column,
                                         const std::string& file) {
  std::vector<AggregateFilter> where;
  if (!a.contains("where")) return where;
  const ojson& w = a["where"];
  const std::string wkey = path + ".where";
  if (!w.is_object()) fail(file, wkey, "an object of column: list of values", describe(w));
  for (auto it = w.begin(); it != w.end(); ++it) {
    const std::string key = wkey + "." + it.key();
    check_column(it.key(), key);
    const ojson& values = it.value();
    if (!values.is_array() || values.empty()) fail(file, key, "a non-empty list of values", describe(values));
    AggregateFilter filter{it.key(), {}};
    for (size_t k = 0; k < values.size(); ++k) {
      const ojson& e = values[k];
      if (e.is_number_float() && !std::isfinite(e.get<double>()))
        fail(file, key + "[" + std::to_string(k) + "]", "a finite number", describe(e));
      if (!(e.is_string() || e.is_number() || e.is_boolean()))
        fail(file, key + "[" + std::to_string(k) + "]", "a string, number or boolean", describe(e));
      filter.values.push_back(value_text(e));  // 45.0 -> "45", as the cell text is written
    }
    where.push_back(filter);
  }
  return where;
}

/// A list of distinct columns of the table at obj[k] (group_by, minimize, agree_on).
std::vector<std::string> distinct_columns(const ojson& obj, const std::string& k, bool allow_empty,
                                          const std::string& path, const ColumnCheck& check_column,
                                          const std::string& file) {
  std::vector<std::string> list = string_list(obj, k, allow_empty, file, path);
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string key = path + "." + k + "[" + std::to_string(i) + "]";
    check_column(list[i], key);
    if (std::find(list.begin(), list.begin() + static_cast<long>(i), list[i]) != list.begin() + static_cast<long>(i))
      fail(file, key, "a column not named before in " + k, "\"" + list[i] + "\"");
  }
  return list;
}

AggregateSpec parse_aggregate(const ojson& a, size_t i, const KnownTables& tables, const PipelineSpec& spec,
                              const std::string& file) {
  AggregateSpec agg;
  agg.key = "aggregate[" + std::to_string(i) + "]";
  if (!a.is_object()) fail(file, agg.key, "an object with csv, from, group_by and stats", describe(a));
  check_keys(a, {"csv", "from", "where", "group_by", "stats"}, file, agg.key);
  agg.csv = inside_path(a, "csv", file, agg.key);
  for (const auto& g : spec.gather)
    if (g.csv == agg.csv)
      fail(file, agg.key + ".csv", "a file name not used by a gather table or an earlier aggregate",
           "\"" + agg.csv + "\" (also " + g.key + ")");
  for (const auto& other : spec.aggregates)
    if (other.csv == agg.csv)
      fail(file, agg.key + ".csv", "a file name not used by a gather table or an earlier aggregate",
           "\"" + agg.csv + "\" (also " + other.key + ")");

  agg.from = inside_path(a, "from", file, agg.key);
  const std::vector<std::string>& columns = known_table(tables, agg.from, agg.key, file);
  const ColumnCheck check_column = column_check(columns, agg.from, file);

  agg.where = parse_where(a, agg.key, check_column, file);
  agg.group_by = distinct_columns(a, "group_by", /*allow_empty=*/true, agg.key, check_column, file);
  agg.header = agg.group_by;

  const std::string skey = agg.key + ".stats";
  if (!a.contains("stats")) fail(file, skey, "an object of column: list of stats", "nothing (the key is required)");
  const ojson& stats = a["stats"];
  if (!stats.is_object() || stats.empty()) fail(file, skey, "a non-empty object of column: list of stats", describe(stats));
  const auto& names = aggregate_stat_names();
  for (auto it = stats.begin(); it != stats.end(); ++it) {
    const std::string key = skey + "." + it.key();
    check_column(it.key(), key);
    const ojson& list = it.value();
    if (!list.is_array() || list.empty())
      fail(file, key, "a non-empty list of stats (" + join(names, ", ") + ")", describe(list));
    AggregateStats col{it.key(), {}};
    for (size_t k = 0; k < list.size(); ++k) {
      const std::string ekey = key + "[" + std::to_string(k) + "]";
      if (!list[k].is_string() || std::find(names.begin(), names.end(), list[k].get<std::string>()) == names.end())
        fail(file, ekey, "a stat (" + join(names, ", ") + ")", list[k].is_string() ? "\"" + list[k].get<std::string>() + "\"" : describe(list[k]));
      const std::string header = it.key() + "_" + list[k].get<std::string>();
      if (std::find(agg.header.begin(), agg.header.end(), header) != agg.header.end())
        fail(file, ekey, "an output column name not used before in " + agg.key, "\"" + header + "\"");
      col.stats.push_back(list[k].get<std::string>());
      agg.header.push_back(header);
    }
    agg.stats.push_back(col);
  }
  return agg;
}

SelectSpec parse_select(const ojson& a, size_t i, const KnownTables& tables, const PipelineSpec& spec,
                        const std::string& file) {
  SelectSpec sel;
  sel.key = "select[" + std::to_string(i) + "]";
  if (!a.is_object()) fail(file, sel.key, "an object with csv, from, group_by, at_least and minimize", describe(a));
  check_keys(a, {"csv", "from", "where", "group_by", "at_least", "at_most", "minimize", "agree_on"}, file, sel.key);
  sel.csv = inside_path(a, "csv", file, sel.key);
  if (sel.csv.size() < 5 || sel.csv.substr(sel.csv.size() - 4) != ".csv")
    fail(file, sel.key + ".csv", "a file name ending in .csv (the line goes beside it as .txt)", "\"" + sel.csv + "\"");
  for (const auto& t : tables)
    if (t.first == sel.csv)
      fail(file, sel.key + ".csv", "a file name not used by another table", "\"" + sel.csv + "\"");
  for (const auto& other : spec.selects)
    if (other.csv == sel.csv)
      fail(file, sel.key + ".csv", "a file name not used by another table", "\"" + sel.csv + "\" (also " + other.key + ")");
  sel.from = inside_path(a, "from", file, sel.key);
  const std::vector<std::string>& columns = known_table(tables, sel.from, sel.key, file);
  const ColumnCheck check_column = column_check(columns, sel.from, file);
  sel.where = parse_where(a, sel.key, check_column, file);
  sel.group_by = distinct_columns(a, "group_by", /*allow_empty=*/true, sel.key, check_column, file);
  if (!a.contains("at_least") && !a.contains("at_most"))
    fail(file, sel.key + ".at_least", "an object of column: number (or at_most)", "nothing (one of them is required)");
  for (const bool at_most : {false, true}) {
    const std::string name = at_most ? "at_most" : "at_least";
    if (!a.contains(name)) continue;
    const std::string tkey = sel.key + "." + name;
    const ojson& bounds = a[name];
    if (!bounds.is_object() || bounds.empty()) fail(file, tkey, "a non-empty object of column: number", describe(bounds));
    for (auto it = bounds.begin(); it != bounds.end(); ++it) {
      const std::string key = tkey + "." + it.key();
      check_column(it.key(), key);
      if (!it.value().is_number() || !std::isfinite(it.value().get<double>()))
        fail(file, key, "a finite number", describe(it.value()));
      sel.thresholds.push_back({it.key(), it.value().get<double>(), at_most});
    }
  }
  sel.minimize = distinct_columns(a, "minimize", /*allow_empty=*/false, sel.key, check_column, file);
  if (a.contains("agree_on"))
    sel.agree_on = distinct_columns(a, "agree_on", /*allow_empty=*/false, sel.key, check_column, file);
  sel.header = sel.group_by;
  sel.header.push_back("found");
  for (const auto& c : columns)
    if (std::find(sel.group_by.begin(), sel.group_by.end(), c) == sel.group_by.end()) {
      if (c == "found") fail(file, sel.key + ".from", "a table without a column named found (the output adds it)", "found");
      sel.header.push_back(c);
    }
  return sel;
}

PlotSpec parse_plot(const ojson& p, size_t i, const PipelineSpec& spec, const std::string& file) {
  PlotSpec plot;
  plot.key = "plots[" + std::to_string(i) + "]";
  if (!p.is_object()) fail(file, plot.key, "an object with png, csv and gnuplot", describe(p));
  check_keys(p, {"png", "csv", "gnuplot"}, file, plot.key);
  plot.png = inside_path(p, "png", file, plot.key);
  plot.csv = inside_path(p, "csv", file, plot.key);
  std::vector<std::string> tables = gather_csvs(spec);
  for (const auto& a : spec.aggregates) tables.push_back(a.csv);
  for (const auto& e : spec.selects) tables.push_back(e.csv);
  if (std::find(tables.begin(), tables.end(), plot.csv) == tables.end())
    fail(file, plot.key + ".csv", "one of the gather, aggregate or select tables (" + join(tables, ", ") + ")",
         "\"" + plot.csv + "\"");
  const std::string gkey = plot.key + ".gnuplot";
  if (!p.contains("gnuplot")) fail(file, gkey, "a gnuplot script", "nothing (the key is required)");
  const ojson& text = p["gnuplot"];
  if (text.is_string()) {
    plot.gnuplot = text.get<std::string>();
  } else if (text.is_array() && !text.empty()) {
    for (const auto& line : text) {
      if (!line.is_string()) fail(file, gkey, "a string or a list of strings (lines)", describe(text));
      plot.gnuplot += line.get<std::string>() + "\n";
    }
  } else {
    fail(file, gkey, "a string or a list of strings (lines)", describe(text));
  }
  check_placeholders(plot.gnuplot, plot_builtins, {}, file, gkey);
  // Columns named in the script (column('x'), strcol("x"), stringcolumn('x')) must be the
  // table's: gnuplot would only find out after every run, with "all points undefined".
  std::vector<std::string> header;
  if (const auto g = std::find_if(spec.gather.begin(), spec.gather.end(), [&](const GatherSpec& e) { return e.csv == plot.csv; });
      g != spec.gather.end())
    header = headers(g->columns);
  for (const auto& a : spec.aggregates)
    if (a.csv == plot.csv) header = a.header;
  for (const auto& e : spec.selects)
    if (e.csv == plot.csv) header = e.header;
  static const std::regex named_column(R"(\b(?:column|strcol|stringcolumn)\s*\(\s*(['"])([^'"]*)\1\s*\))");
  for (auto it = std::sregex_iterator(plot.gnuplot.begin(), plot.gnuplot.end(), named_column); it != std::sregex_iterator(); ++it)
    if ((*it)[2].str().find("${") == std::string::npos &&  // a name built from a placeholder is left to gnuplot
        std::find(header.begin(), header.end(), (*it)[2].str()) == header.end())
      fail(file, gkey, "columns of " + plot.csv + " (" + join(header, ", ") + ")", "\"" + (*it)[2].str() + "\"");
  // The runner owns the output file: it writes to a temporary image and renames it.
  static const std::regex sets_output(R"(\bset\s+o(u|ut|utp|utpu|utput)?\b)");
  std::smatch m;
  if (std::regex_search(plot.gnuplot, m, sets_output))
    fail(file, gkey, "a script without set output (the runner writes the image to png)", "\"" + m.str() + "\"");
  return plot;
}

// The "requires" entries, each parsed with the chain of files that led to it. Runs after
// the gather, aggregate and plot entries, whose files an "out" folder must not shadow.
void parse_required(const ojson& list, const std::string& file, const std::vector<fs::path>& required_by,
                    PipelineSpec& spec) {
  if (!list.is_array()) fail(file, "requires", "a list of {pipeline, out}", describe(list));
  std::vector<std::string> own_files = gather_csvs(spec);
  for (const auto& a : spec.aggregates) own_files.push_back(a.csv);
  for (const auto& e : spec.selects) own_files.push_back(e.csv);
  for (const auto& p : spec.plots) own_files.push_back(p.png);
  for (size_t i = 0; i < list.size(); ++i) {
    RequiredPipeline required;
    required.key = "requires[" + std::to_string(i) + "]";
    const ojson& e = list[i];
    if (!e.is_object()) fail(file, required.key, "an object {pipeline, out}", describe(e));
    check_keys(e, {"pipeline", "out"}, file, required.key);
    const std::string out_key = required.key + ".out";
    {
      // A folder of its own: not DIR itself, not outside it, not a name the runner writes.
      const std::string text = required_string(e, "out", file, required.key);
      const fs::path p = fs::path(text).lexically_normal();
      bool bad = p.is_absolute() || p.empty() || p == ".";  // lexically_normal makes "./" and "a/.." "."
      for (const auto& part : p) bad = bad || part == "..";
      const std::string head = p.empty() ? "" : p.begin()->string();
      bad = bad || head == "runs" || head == "shared" || head == "Snakefile" || head == "pipeline.summary.json" ||
            head == "pipeline.log" || head == "provenance.json";
      if (bad)
        fail(file, out_key, "a relative folder inside the output folder (not ., runs, shared, Snakefile, pipeline.log, provenance.json, pipeline.summary.json)",
             "\"" + text + "\"");
      required.out = p.string();
    }
    const auto shadows = [&](const std::string& name) {
      const fs::path a = fs::path(name).lexically_normal(), b = fs::path(required.out);
      // One is the other or lies inside it.
      return std::mismatch(b.begin(), b.end(), a.begin(), a.end()).first == b.end() ||
             std::mismatch(a.begin(), a.end(), b.begin(), b.end()).first == a.end();
    };
    for (const auto& earlier : spec.required)
      if (shadows(earlier.out)) fail(file, out_key, "a folder apart from the other required pipelines'", "\"" + required.out + "\" (also " + earlier.key + ")");
    for (const auto& f : own_files)
      if (shadows(f)) fail(file, out_key, "a folder apart from this pipeline's tables and plots", "\"" + required.out + "\" (and " + f + ")");

    const std::string pipeline_key = required.key + ".pipeline";
    const fs::path target = (spec.pipeline_dir / required_string(e, "pipeline", file, required.key)).lexically_normal();
    // Compared as canonical paths, so that a symbolic link cannot hide a cycle.
    const fs::path identity = fs::weakly_canonical(target);
    if (std::find(required_by.begin(), required_by.end(), identity) != required_by.end()) {
      std::string cycle;
      for (const auto& f : required_by) cycle += f.filename().string() + " -> ";
      fail(file, pipeline_key, "a pipeline that does not require this one", "a cycle " + cycle + target.filename().string());
    }
    std::error_code ec;
    if (!fs::is_regular_file(target, ec)) fail(file, pipeline_key, "an existing pipeline file", "\"" + target.string() + "\"");
    std::vector<fs::path> chain = required_by;
    chain.push_back(identity);
    required.spec = std::make_shared<const PipelineSpec>(
        parse_pipeline(load_pipeline_json(target), target.string(), target.parent_path(), chain));
    spec.required.push_back(std::move(required));
  }
}

}  // namespace

fs::path normalized_dir(const fs::path& dir) {
  fs::path a = fs::absolute(dir).lexically_normal();
  if (!a.has_filename() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
  return a;
}

ojson load_pipeline_json(const fs::path& path) { return read_json_file<ojson>(path, /*comments=*/true); }

PipelineSpec parse_pipeline(const ojson& doc, const std::string& file, const fs::path& pipeline_dir) {
  return parse_pipeline(doc, file, pipeline_dir, {fs::weakly_canonical(normalized_dir(pipeline_dir) / fs::path(file).filename())});
}

PipelineSpec parse_pipeline(const ojson& doc, const std::string& file, const fs::path& pipeline_dir,
                            const std::vector<fs::path>& required_by) {
  if (!doc.is_object()) fail(file, "(top level)", "an object", describe(doc));
  check_keys(doc, {"name", "description", "requires", "variables", "sweep", "shared_steps", "steps", "gather", "aggregate", "select",
                   "plots"},
             file, "");
  PipelineSpec spec;
  spec.file = file;
  spec.pipeline_dir = normalized_dir(pipeline_dir);
  spec.source = doc;
  spec.name = doc.contains("name") ? required_string(doc, "name", file, "") : fs::path(file).stem().string();
  if (doc.contains("description")) {
    if (!doc["description"].is_string()) fail(file, "description", "a string", describe(doc["description"]));
    spec.description = doc["description"].get<std::string>();
  }

  if (doc.contains("variables")) {
    const ojson& vars = doc["variables"];
    if (!vars.is_object()) fail(file, "variables", "an object of name: list of values", describe(vars));
    for (auto it = vars.begin(); it != vars.end(); ++it) spec.variables.push_back(parse_variable(it.key(), it.value(), file));
  }
  if (doc.contains("sweep")) {
    const ojson& s = doc["sweep"];
    if (!s.is_string() || (s != "grid" && s != "zip")) fail(file, "sweep", "\"grid\" or \"zip\"", describe(s));
    spec.sweep = s == "zip" ? SweepKind::zip : SweepKind::grid;
  }
  if (spec.sweep == SweepKind::zip) {
    for (const auto& v : spec.variables)
      if (v.values.size() != spec.variables.front().values.size())
        fail(file, "variables." + v.name,
             std::to_string(spec.variables.front().values.size()) + " values (as many as variables." +
                 spec.variables.front().name + ", sweep zip)",
             std::to_string(v.values.size()));
  } else {
    double runs = 1;
    for (const auto& v : spec.variables) runs *= static_cast<double>(v.values.size());
    if (runs > static_cast<double>(max_runs))
      fail(file, "variables", "at most " + std::to_string(max_runs) + " runs in the grid", format_number(runs));
  }

  if (!doc.contains("steps")) fail(file, "steps", "a list of steps", "nothing (the key is required)");
  const ojson& steps = doc["steps"];
  if (!steps.is_array() || steps.empty()) fail(file, "steps", "a non-empty list of steps", describe(steps));
  for (size_t i = 0; i < steps.size(); ++i) {
    spec.steps.push_back(parse_step(steps[i], i, spec.variables, file));
    for (size_t j = 0; j + 1 < spec.steps.size(); ++j)
      if (spec.steps[j].name == spec.steps.back().name)
        fail(file, spec.steps.back().key + ".name",
             "a step name not used before (set \"name\" when a stage runs twice)",
             "\"" + spec.steps.back().name + "\" (also " + spec.steps[j].key + ")");
  }

  bool share = true;
  if (doc.contains("shared_steps")) {
    if (!doc["shared_steps"].is_boolean()) fail(file, "shared_steps", "true or false", describe(doc["shared_steps"]));
    share = doc["shared_steps"].get<bool>();
  }
  if (share) find_shared_steps(spec);

  if (doc.contains("gather")) {
    const ojson& g = doc["gather"];
    if (!g.is_array()) fail(file, "gather", "a list of tables", describe(g));
    for (size_t i = 0; i < g.size(); ++i) {
      spec.gather.push_back(parse_gather(g[i], i, spec.variables, file));
      // Entries sharing a csv are concatenated under one header, so it must fit them all.
      const GatherSpec& added = spec.gather.back();
      const auto first = std::find_if(spec.gather.begin(), spec.gather.end(),
                                      [&](const GatherSpec& e) { return e.csv == added.csv; });
      if (&*first != &added && headers(first->columns) != headers(added.columns))
        fail(file, added.key + ".columns", "the same columns as " + first->key + " (same csv)",
             join(headers(added.columns), ", ") + " (" + first->key + ": " + join(headers(first->columns), ", ") + ")");
    }
  }
  KnownTables tables;
  for (const auto& csv : gather_csvs(spec)) {
    const auto g = std::find_if(spec.gather.begin(), spec.gather.end(), [&](const GatherSpec& e) { return e.csv == csv; });
    tables.emplace_back(csv, headers(g->columns));
  }
  if (doc.contains("aggregate")) {
    const ojson& a = doc["aggregate"];
    if (!a.is_array()) fail(file, "aggregate", "a list of aggregate tables", describe(a));
    for (size_t i = 0; i < a.size(); ++i) {
      spec.aggregates.push_back(parse_aggregate(a[i], i, tables, spec, file));
      tables.emplace_back(spec.aggregates.back().csv, spec.aggregates.back().header);
    }
  }
  if (doc.contains("select")) {
    const ojson& a = doc["select"];
    if (!a.is_array()) fail(file, "select", "a list of select tables", describe(a));
    for (size_t i = 0; i < a.size(); ++i) spec.selects.push_back(parse_select(a[i], i, tables, spec, file));
  }
  if (doc.contains("plots")) {
    const ojson& p = doc["plots"];
    if (!p.is_array()) fail(file, "plots", "a list of plots", describe(p));
    for (size_t i = 0; i < p.size(); ++i) {
      spec.plots.push_back(parse_plot(p[i], i, spec, file));
      for (size_t j = 0; j + 1 < spec.plots.size(); ++j)
        if (spec.plots[j].png == spec.plots.back().png)
          fail(file, spec.plots.back().key + ".png", "a file name not used before",
               "\"" + spec.plots.back().png + "\" (also " + spec.plots[j].key + ")");
    }
  }
  if (doc.contains("requires")) parse_required(doc["requires"], file, required_by, spec);
  return spec;
}

PipelineSpec load_pipeline(const fs::path& path) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  return parse_pipeline(load_pipeline_json(path), path.string(), absolute.parent_path(), {fs::weakly_canonical(absolute)});
}

std::vector<std::string> gather_csvs(const PipelineSpec& spec) {
  std::vector<std::string> out;
  for (const auto& g : spec.gather)
    if (std::find(out.begin(), out.end(), g.csv) == out.end()) out.push_back(g.csv);
  return out;
}

const std::vector<std::string>& aggregate_stat_names() {
  static const std::vector<std::string> names{"mean", "sd", "min", "max", "median", "count", "true_count"};
  return names;
}

std::vector<ojson> expand_sweep(const std::vector<SweepVariable>& variables, SweepKind sweep) {
  std::vector<ojson> runs;
  if (variables.empty()) return {ojson::object()};
  if (sweep == SweepKind::zip) {
    for (size_t k = 0; k < variables.front().values.size(); ++k) {
      ojson a = ojson::object();
      for (const auto& v : variables) a[v.name] = v.values.at(k);
      runs.push_back(a);
    }
    return runs;
  }
  size_t total = 1;
  for (const auto& v : variables) total *= v.values.size();
  for (size_t index = 0; index < total; ++index) {
    // Mixed-radix digits of index, last variable fastest: the order of nested loops.
    std::vector<size_t> digit(variables.size());
    size_t rest = index;
    for (size_t i = variables.size(); i-- > 0;) {
      digit[i] = rest % variables[i].values.size();
      rest /= variables[i].values.size();
    }
    ojson a = ojson::object();
    for (size_t i = 0; i < variables.size(); ++i) a[variables[i].name] = variables[i].values[digit[i]];
    runs.push_back(a);
  }
  return runs;
}

std::vector<std::string> make_run_ids(const std::vector<ojson>& assignments) {
  auto slug = [](const std::string& s) {
    std::string out;
    bool pending = false;
    for (char c : s) {
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-') {
        if (pending && !out.empty()) out += '-';
        pending = false;
        out += c;
      } else {
        pending = true;
      }
    }
    if (out.size() > 40) out.resize(40);
    return out.empty() ? std::string("empty") : out;
  };
  std::vector<std::string> ids;
  std::set<std::string> used;
  for (const auto& a : assignments) {
    std::string base;
    for (auto it = a.begin(); it != a.end(); ++it)
      base += (base.empty() ? "" : "_") + it.key() + "-" + slug(value_text(it.value()));
    if (base.empty()) base = "single";
    if (base.size() > 200) base.resize(200);  // file names stop at 255 bytes
    std::string id = base;
    for (int n = 2; used.count(id); ++n) id = base + "-" + std::to_string(n);
    used.insert(id);
    ids.push_back(id);
  }
  return ids;
}

Bindings run_bindings(const PipelineSpec& spec, const RunPlan& run, const fs::path& out_dir) {
  Bindings b;
  for (auto it = run.variables.begin(); it != run.variables.end(); ++it) b[it.key()] = it.value();
  b["run_dir"] = run.run_dir.string();
  b["run_id"] = run.run_id;
  b["out_dir"] = normalized_dir(out_dir).string();
  b["pipeline_dir"] = spec.pipeline_dir.string();
  return b;
}

std::vector<RunPlan> expand_runs(const PipelineSpec& spec, const fs::path& out_dir) {
  const fs::path out = normalized_dir(out_dir);
  const auto assignments = expand_sweep(spec.variables, spec.sweep);
  const auto ids = make_run_ids(assignments);
  std::vector<RunPlan> runs;
  for (size_t r = 0; r < assignments.size(); ++r) {
    RunPlan run;
    run.run_id = ids[r];
    run.variables = assignments[r];
    run.run_dir = out / "runs" / run.run_id;
    const Bindings b = run_bindings(spec, run, out);
    for (size_t i = spec.shared_steps; i < spec.steps.size(); ++i) {
      const StepSpec& s = spec.steps[i];
      ResolvedStep step{s.name, s.stage, {}, s.allow_exit};
      for (size_t k = 0; k < s.args.size(); ++k)
        step.args.push_back(substitute(to_shared(s.args[k], spec.shared_outs), b, spec.file,
                                       s.key + ".args[" + std::to_string(k) + "]"));
      run.steps.push_back(step);
    }
    runs.push_back(run);
  }
  return runs;
}

std::optional<RunPlan> shared_run(const PipelineSpec& spec, const fs::path& out_dir) {
  if (spec.shared_steps == 0) return std::nullopt;
  RunPlan run;
  run.run_id = "shared";
  run.run_dir = normalized_dir(out_dir) / "shared";
  const Bindings b = run_bindings(spec, run, out_dir);
  for (size_t i = 0; i < spec.shared_steps; ++i) {
    const StepSpec& s = spec.steps[i];
    ResolvedStep step{s.name, s.stage, {}, s.allow_exit};
    for (size_t k = 0; k < s.args.size(); ++k)
      step.args.push_back(substitute(s.args[k], b, spec.file, s.key + ".args[" + std::to_string(k) + "]"));
    run.steps.push_back(step);
  }
  return run;
}

fs::path run_file(const PipelineSpec& spec, const RunPlan& run, const fs::path& out_dir, const std::string& relative) {
  const std::string rel = fs::path(relative).lexically_normal().string();
  for (const auto& folder : spec.shared_outs)
    if (rel.rfind(folder, 0) == 0 && (rel.size() == folder.size() || rel[folder.size()] == '/'))
      return normalized_dir(out_dir) / "shared" / rel;
  return run.run_dir / relative;
}

std::vector<RunPlan> select_runs(std::vector<RunPlan> runs, const std::vector<std::string>& ids,
                                 const std::string& option) {
  if (ids.empty()) return runs;
  for (const auto& id : ids)
    if (std::none_of(runs.begin(), runs.end(), [&](const RunPlan& r) { return r.run_id == id; }))
      throw InputError(option + ": expected a run id of the pipeline (valve-pipeline list shows them), found \"" + id + "\"");
  runs.erase(std::remove_if(runs.begin(), runs.end(),
                            [&](const RunPlan& r) { return std::find(ids.begin(), ids.end(), r.run_id) == ids.end(); }),
             runs.end());
  return runs;
}

std::string substitute(const std::string& text, const Bindings& bindings, const std::string& file,
                       const std::string& key) {
  std::string out;
  for (const auto& piece : split_placeholders(text, file, key)) {
    if (!piece.placeholder) {
      out += piece.text;
      continue;
    }
    const auto [name, field] = split_reference(piece.text);
    const auto it = bindings.find(name);
    if (it == bindings.end()) fail(file, key, "a known variable", "${" + piece.text + "}");
    const ojson* v = find_path(it->second, field);
    if (!v) fail(file, key, "a field " + field + " in " + name, "${" + piece.text + "}");
    out += value_text(*v);
  }
  return out;
}

std::string value_text(const ojson& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return format_number(v.get<double>());
  if (v.is_number()) return v.dump();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_null()) return "";
  if (v.is_object() && v.contains("label")) return value_text(v["label"]);
  return v.dump();
}

const ojson* find_path(const ojson& root, const std::string& dot_path) {
  const ojson* node = &root;
  if (dot_path.empty()) return node;
  size_t start = 0;
  while (true) {
    const auto dot = dot_path.find('.', start);
    const std::string part = dot_path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (node->is_object()) {
      const auto it = node->find(part);
      if (it == node->end()) return nullptr;
      node = &*it;
    } else if (node->is_array()) {
      if (part.empty() || !std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
          part.size() > 9)
        return nullptr;
      const size_t index = std::stoul(part);
      if (index >= node->size()) return nullptr;
      node = &(*node)[index];
    } else {
      return nullptr;
    }
    if (dot == std::string::npos) return node;
    start = dot + 1;
  }
}

}  // namespace valve
