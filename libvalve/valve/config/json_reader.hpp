#pragma once
// Validating reader for one JSON object of a config. Every key read is checked for
// type and range, defaults are filled in, the values actually used are recorded (for
// the stage summary), and finish() rejects keys nobody asked for (typos).
// Errors are one line: "<file>: <path.key>: expected ..., found ...".
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "valve/core/units.hpp"

namespace valve {

using json = nlohmann::json;

/// Parses a JSON file; malformed JSON becomes an InputError naming file and line.
json load_json_file(const std::filesystem::path& path);

/// One key a reader is asked for, as a key table in the docs lists it.
struct KeySpec {
  std::string path;           // e.g. "solver.bdf2.max_step"
  std::string type;           // e.g. "time", "number", "one of a|b", "list of numbers"
  std::string default_value;  // e.g. "50 ms", "required", or how a derived default is found
  std::string range;          // e.g. "[1e-12 mm, 100 mm]"; empty when any value is accepted
};

/// While one lives, every JsonReader of this thread reading `file` notes each key it is asked
/// for, with the type, default and range the reading code passes. The docs' key tables are
/// made so from the parser itself. The first note of a path wins; JsonReader::document()
/// fills in what a reader cannot see (raw keys, defaults derived from other keys).
class KeySpecRecorder {
 public:
  explicit KeySpecRecorder(std::string file);
  ~KeySpecRecorder();
  KeySpecRecorder(const KeySpecRecorder&) = delete;
  KeySpecRecorder& operator=(const KeySpecRecorder&) = delete;

  const std::vector<KeySpec>& keys() const { return keys_; }
  const std::string& file() const { return file_; }
  /// Adds `spec`, or for a path already noted overwrites the fields `spec` gives (non-empty).
  void note(const KeySpec& spec, bool overwrite);
  /// The recorder of this thread, or null.
  static KeySpecRecorder* active();

 private:
  std::string file_;
  std::vector<KeySpec> keys_;
  KeySpecRecorder* previous_;
};

class JsonReader {
 public:
  /// `file` names the source for messages; `path` is the key path of `object` in it.
  JsonReader(const json& object, std::string file, std::string path = "");
  /// The reader keeps a reference to `object`: a temporary would dangle.
  JsonReader(json&& object, std::string file, std::string path = "") = delete;

  bool has(const std::string& key) const;

  double number(const std::string& key, std::optional<double> fallback = std::nullopt,
                double min = -1e300, double max = 1e300);
  int integer(const std::string& key, std::optional<int> fallback = std::nullopt,
              int min = -2147483647, int max = 2147483647);
  bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt);
  std::string string(const std::string& key, std::optional<std::string> fallback = std::nullopt);
  /// A string that must be one of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices,
                     std::optional<std::string> fallback = std::nullopt);
  /// A physical quantity "<number> <unit>"; `fallback` is text too, e.g. "80 mmHg".
  /// Bare numbers are rejected: the unit would be ambiguous. `min` and `max` are in internal units.
  double quantity(const std::string& key, Dimension dim,
                  std::optional<std::string> fallback = std::nullopt, double min = -1e300,
                  double max = 1e300);
  /// The same with a default already in internal units (e.g. taken from another key); the
  /// record shows it in the internal unit ("0.65 mm").
  double quantity(const std::string& key, Dimension dim, double fallback_internal, double min, double max);
  std::vector<double> number_list(const std::string& key,
                                  std::optional<std::vector<double>> fallback = std::nullopt);
  std::vector<int> integer_list(const std::string& key,
                                std::optional<std::vector<int>> fallback = std::nullopt);
  std::vector<std::string> string_list(const std::string& key,
                                       std::optional<std::vector<std::string>> fallback = std::nullopt);
  /// A sub-object (empty if absent). Record its values with record(key, child.finish()).
  JsonReader object(const std::string& key);
  /// The raw value (marked as read) for callers that parse it themselves.
  const json& raw(const std::string& key);

  /// For the key tables (KeySpecRecorder): what a raw key holds, or how a default derived
  /// from other keys is found. Empty fields leave what the reading call noted.
  void document(const std::string& key, const std::string& type, const std::string& default_value) const;

  /// Records a derived value in the "used" record without reading it.
  void record(const std::string& key, const json& value) { used_[key] = value; }
  /// Throws on any key that was not read. Returns the values used (after defaults).
  json finish() const;
  /// Values used so far.
  const json& used() const { return used_; }

  [[noreturn]] void fail(const std::string& key, const std::string& expected,
                         const std::string& found) const;
  std::string key_path(const std::string& key) const;
  const std::string& file() const { return file_; }

 private:
  const json* find(const std::string& key);
  // Tells the active KeySpecRecorder (if it records this file) about a key asked for.
  void note(const std::string& key, const std::string& type, const std::string& default_value,
            const std::string& range) const;
  double quantity_from_text(const std::string& key, Dimension dim, const std::string* fallback_text, double min,
                            double max);
  // A list whose elements `accept` admits; messages say `what` (the list) and `element_what`.
  template <class T, class Accept>
  std::vector<T> list(const std::string& key, std::optional<std::vector<T>> fallback, const char* what,
                      const char* element_what, Accept accept);

  const json& object_;
  std::string file_, path_;
  std::set<std::string> read_;
  json used_ = json::object();
};

/// Short description of a JSON value's type and content for "found ..." messages.
std::string describe_json(const json& value);

}  // namespace valve
