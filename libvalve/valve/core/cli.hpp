#pragma once
// The stage command-line contract: `valve-<stage> [--config FILE.json] [--flags] --out DIR`.
// Flags override the config. Exit codes: 0 ok, 2 bad input or config, 3 numerical failure.
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace valve {

/// Thrown by CommandLine when --help or -h is given; run_stage() prints the usage, exit 0.
struct HelpRequested {};
/// Thrown by CommandLine when --xml is given: run_stage() prints the stage's 3D Slicer CLI
/// module description, made from the options the command line accepts, and exits 0.
struct XmlRequested {
  std::vector<std::string> flags, switches;
};

class CommandLine {
 public:
  /// `flags` lists the accepted --options taking a value; `switches` those without one
  /// (--switch or --switch=true|false; has() says whether it is on).
  /// --help or -h anywhere throws HelpRequested before anything else is checked, --xml
  /// XmlRequested. Every stage also takes --progress text|slicer|none (progress_style()).
  /// A flag may repeat (get() returns the last value, get_all() every value in order).
  CommandLine(int argc, char** argv, const std::vector<std::string>& flags, const std::vector<std::string>& switches);
  std::optional<std::string> get(const std::string& flag) const;
  std::vector<std::string> get_all(const std::string& flag) const;
  std::string require(const std::string& flag) const;
  bool has(const std::string& flag) const;
  const std::vector<std::string>& positional() const { return positional_; }
  std::string program() const { return program_; }

 private:
  std::string program_;
  std::map<std::string, std::vector<std::string>> values_;
  std::map<std::string, bool> switch_values_;  // the last --switch[=true|false] of each
  std::vector<std::string> positional_;
};

/// --flag as a plain decimal number in [lo, hi], `fallback` when absent. Hexadecimal ("0x20"),
/// "inf" and "nan", which strtod also reads, are refused with the rest: InputError
/// "--flag: expected a number in [lo, hi], found \"value\"".
double number_flag(const CommandLine& cl, const std::string& flag, double fallback, double lo, double hi);

/// The same, for a whole number ("12.5" is refused as "expected a whole number in [lo, hi]").
long whole_number_flag(const CommandLine& cl, const std::string& flag, long fallback, long lo, long hi);

/// Applies "--set key.path=value" overrides to a JSON config: creates objects along the
/// path; the value is parsed as JSON when it is valid JSON (numbers, true, objects), else
/// kept as a string ("20 kPa"). Throws InputError for a malformed assignment.
void apply_override(nlohmann::json& config, const std::string& assignment, const std::string& where);

/// Collects a stage's summary and writes DIR/<stage>.summary.json atomically.
class StageSummary {
 public:
  StageSummary(std::string stage, std::filesystem::path out_dir);
  void add_input(const std::string& role, const std::filesystem::path& path);
  nlohmann::json& parameters() { return doc_["parameters"]; }
  nlohmann::json& metrics() { return doc_["metrics"]; }
  void set_status(const std::string& status, const std::string& reason = "");
  void write();
  const std::filesystem::path& out_dir() const { return out_; }

 private:
  std::string stage_;
  std::filesystem::path out_;
  nlohmann::json doc_;
  double start_;
};

/// Runs a stage body and maps exceptions to the exit-code contract, printing one line
/// "<program>: error: <message>" on stderr. On HelpRequested prints `usage` on stdout
/// (stages pass kStageUsage, their main.cpp's leading comment) and returns 0; on
/// XmlRequested prints slicer_cli_xml() of the usage and the accepted options.
int run_stage(const std::string& program, const char* usage, const std::function<int()>& body);

/// Replaces non-finite numbers by null, recursively (JSON has no NaN; a summary must
/// never carry one silently). Returns the number of values replaced.
int scrub_non_finite(nlohmann::json& j);

}  // namespace valve
