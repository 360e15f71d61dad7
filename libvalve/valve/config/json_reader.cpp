#include "valve/config/json_reader.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {

json load_json_file(const std::filesystem::path& path) { return read_json_file<json>(path); }

std::string describe_json(const json& v) {
  std::string dump = v.dump();
  if (dump.size() > 60) dump = dump.substr(0, 57) + "...";
  return std::string(v.type_name()) + " " + dump;
}

namespace {
thread_local KeySpecRecorder* active_recorder = nullptr;

// A range bound for the key tables: 1e+12 reads better there as 1e12.
std::string bound_text(double x) {
  if (x == static_cast<long long>(x) && std::fabs(x) < 1e6) return format_number(x);
  std::string text = format_shortest_general(x);
  for (const char* noise : {"e+0", "e+", "e-0"}) {
    const auto at = text.find(noise);
    if (at != std::string::npos) {
      text.replace(at, std::string(noise).size(), noise[1] == '-' ? "e-" : "e");
      break;
    }
  }
  return text;
}

// "[min, max]", "≥ min" or "≤ max" with each bound formatted by `text`; empty without bounds.
template <class T, class Text>
std::string range_text(T min, T max, T no_min, T no_max, Text text) {
  if (min > no_min && max < no_max) return "[" + text(min) + ", " + text(max) + "]";
  if (min > no_min) return "≥ " + text(min);
  if (max < no_max) return "≤ " + text(max);
  return "";
}
}  // namespace

KeySpecRecorder::KeySpecRecorder(std::string file) : file_(std::move(file)), previous_(active_recorder) {
  active_recorder = this;
}
KeySpecRecorder::~KeySpecRecorder() { active_recorder = previous_; }
KeySpecRecorder* KeySpecRecorder::active() { return active_recorder; }

void KeySpecRecorder::note(const KeySpec& spec, bool overwrite) {
  for (auto& k : keys_) {
    if (k.path != spec.path) continue;
    if (overwrite) {
      if (!spec.type.empty()) k.type = spec.type;
      if (!spec.default_value.empty()) k.default_value = spec.default_value;
      if (!spec.range.empty()) k.range = spec.range;
    }
    return;
  }
  keys_.push_back(spec);
}

void JsonReader::note(const std::string& key, const std::string& type, const std::string& default_value,
                      const std::string& range) const {
  if (active_recorder && active_recorder->file() == file_)
    active_recorder->note({key_path(key), type, default_value, range}, false);
}

void JsonReader::document(const std::string& key, const std::string& type, const std::string& default_value) const {
  if (active_recorder && active_recorder->file() == file_)
    active_recorder->note({key_path(key), type, default_value, ""}, true);
}

JsonReader::JsonReader(const json& object, std::string file, std::string path)
    : object_(object), file_(std::move(file)), path_(std::move(path)) {
  if (!object_.is_object()) throw_input_error(file_, path_.empty() ? "(top level)" : path_, "an object", describe_json(object_));
}

std::string JsonReader::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonReader::fail(const std::string& key, const std::string& expected,
                      const std::string& found) const {
  throw_input_error(file_, key_path(key), expected, found);
}

bool JsonReader::has(const std::string& key) const { return object_.contains(key); }

const json* JsonReader::find(const std::string& key) {
  read_.insert(key);
  auto it = object_.find(key);
  if (it == object_.end() || it->is_null()) return nullptr;
  return &*it;
}

double JsonReader::number(const std::string& key, std::optional<double> fallback, double min,
                          double max) {
  note(key, "number", fallback ? format_number(*fallback) : "required",
       range_text(min, max, -1e300, 1e300, bound_text));
  const json* v = find(key);
  double x;
  if (!v) {
    if (!fallback) fail(key, "a number", "nothing (the key is required)");
    x = *fallback;
  } else {
    if (!v->is_number()) fail(key, "a number", describe_json(*v));
    x = v->get<double>();
  }
  if (!std::isfinite(x) || x < min || x > max) {
    std::ostringstream range;
    range << "a number in [" << min << ", " << max << "]";
    fail(key, range.str(), std::to_string(x));
  }
  used_[key] = x;
  return x;
}

int JsonReader::integer(const std::string& key, std::optional<int> fallback, int min, int max) {
  note(key, "integer", fallback ? std::to_string(*fallback) : "required",
       range_text(min, max, -2147483647, 2147483647, [](int x) { return bound_text(x); }));
  const json* v = find(key);
  long long x;
  if (!v) {
    if (!fallback) fail(key, "an integer", "nothing (the key is required)");
    x = *fallback;
  } else {
    if (!v->is_number_integer()) fail(key, "an integer", describe_json(*v));
    x = v->get<long long>();
  }
  if (x < min || x > max)
    fail(key, "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]",
         std::to_string(x));
  used_[key] = x;
  return static_cast<int>(x);
}

bool JsonReader::boolean(const std::string& key, std::optional<bool> fallback) {
  note(key, "true or false", fallback ? (*fallback ? "true" : "false") : "required", "");
  const json* v = find(key);
  bool x;
  if (!v) {
    if (!fallback) fail(key, "true or false", "nothing (the key is required)");
    x = *fallback;
  } else {
    if (!v->is_boolean()) fail(key, "true or false", describe_json(*v));
    x = v->get<bool>();
  }
  used_[key] = x;
  return x;
}

std::string JsonReader::string(const std::string& key, std::optional<std::string> fallback) {
  note(key, "string", fallback ? json(*fallback).dump() : "required", "");
  const json* v = find(key);
  std::string x;
  if (!v) {
    if (!fallback) fail(key, "a string", "nothing (the key is required)");
    x = *fallback;
  } else {
    if (!v->is_string()) fail(key, "a string", describe_json(*v));
    x = v->get<std::string>();
  }
  used_[key] = x;
  return x;
}

std::string JsonReader::choice(const std::string& key, const std::vector<std::string>& choices,
                               std::optional<std::string> fallback) {
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : "|") + c;
  note(key, "one of " + list, fallback ? *fallback : "required", "");
  const std::string x = string(key, std::move(fallback));
  for (const auto& c : choices)
    if (c == x) return x;
  fail(key, "one of " + list, "\"" + x + "\"");
}

double JsonReader::quantity(const std::string& key, Dimension dim,
                            std::optional<std::string> fallback, double min, double max) {
  return quantity_from_text(key, dim, fallback ? &*fallback : nullptr, min, max);
}

double JsonReader::quantity(const std::string& key, Dimension dim, double fallback_internal, double min, double max) {
  const std::string text = format_quantity(fallback_internal, dim);
  return quantity_from_text(key, dim, &text, min, max);
}

double JsonReader::quantity_from_text(const std::string& key, Dimension dim, const std::string* fallback, double min,
                                      double max) {
  note(key, to_string(dim), fallback ? *fallback : "required",
       range_text(min, max, -1e300, 1e300, [dim](double x) { return bound_text(x) + " " + internal_unit(dim); }));
  const json* v = find(key);
  std::string text;
  if (!v) {
    if (!fallback) fail(key, "a " + to_string(dim) + " with a unit", "nothing (the key is required)");
    text = *fallback;
  } else {
    if (!v->is_string())
      fail(key, "a " + to_string(dim) + " as a string with a unit, e.g. \"" +
                    (accepted_units(dim).empty() ? std::string() : "1 " + accepted_units(dim)[0]) + "\"",
           describe_json(*v));
    text = v->get<std::string>();
  }
  const double x = parse_quantity(text, dim, file_ + ": " + key_path(key));
  if (x < min || x > max) {
    std::ostringstream range;
    range << "a value in [" << min << ", " << max << "] (internal units: mm, g, ms, N, MPa)";
    fail(key, range.str(), text);
  }
  used_[key] = text;
  return x;
}

template <class T, class Accept>
std::vector<T> JsonReader::list(const std::string& key, std::optional<std::vector<T>> fallback, const char* what,
                                const char* element_what, Accept accept) {
  note(key, std::string(what).substr(2), fallback ? json(*fallback).dump() : "required", "");
  const json* v = find(key);
  std::vector<T> out;
  if (!v) {
    if (!fallback) fail(key, what, "nothing (the key is required)");
    out = *fallback;
  } else {
    if (!v->is_array()) fail(key, what, describe_json(*v));
    for (const auto& e : *v) {
      if (!accept(e)) fail(key, element_what, describe_json(*v));
      out.push_back(e.get<T>());
    }
  }
  used_[key] = out;
  return out;
}

std::vector<double> JsonReader::number_list(const std::string& key, std::optional<std::vector<double>> fallback) {
  return list<double>(key, std::move(fallback), "a list of numbers", "a list of finite numbers",
                      [](const json& e) { return e.is_number() && std::isfinite(e.get<double>()); });
}

std::vector<std::string> JsonReader::string_list(const std::string& key, std::optional<std::vector<std::string>> fallback) {
  return list<std::string>(key, std::move(fallback), "a list of strings", "a list of strings",
                           [](const json& e) { return e.is_string(); });
}

std::vector<int> JsonReader::integer_list(const std::string& key, std::optional<std::vector<int>> fallback) {
  return list<int>(key, std::move(fallback), "a list of integers", "a list of integers",
                   [](const json& e) { return e.is_number_integer(); });
}

JsonReader JsonReader::object(const std::string& key) {
  read_.insert(key);
  auto it = object_.find(key);
  static const json empty = json::object();
  if (it == object_.end() || it->is_null()) return JsonReader(empty, file_, key_path(key));
  if (!it->is_object()) fail(key, "an object", describe_json(*it));
  return JsonReader(*it, file_, key_path(key));
}

const json& JsonReader::raw(const std::string& key) {
  read_.insert(key);
  auto it = object_.find(key);
  if (it == object_.end()) fail(key, "a value", "nothing (the key is required)");
  used_[key] = *it;
  return *it;
}

json JsonReader::finish() const {
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (read_.count(it.key()) == 0) {
      std::string known;
      for (const auto& k : read_) known += (known.empty() ? "" : ", ") + k;
      fail(it.key(), "a known key (" + known + ")", "an unknown key");
    }
  }
  return used_;
}

}  // namespace valve
