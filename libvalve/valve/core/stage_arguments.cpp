#include "valve/core/stage_arguments.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {
namespace {

std::string key_of(const std::string& flag) {
  std::string k = flag;
  std::replace(k.begin(), k.end(), '-', '_');
  return k;
}

bool parse_double(const std::string& s, double* x) {
  char* end = nullptr;
  *x = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0';
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) parts.push_back(item);
  return parts;
}

// A point given as [x, y, z] (JSON) or "x,y,z" (command line).
bool parse_point(const nlohmann::json& item, Vec3* v) {
  bool ok = false;
  if (item.is_array() && item.size() == 3 && item[0].is_number() && item[1].is_number() && item[2].is_number()) {
    *v = Vec3(item[0].get<double>(), item[1].get<double>(), item[2].get<double>());
    ok = true;
  } else if (item.is_string()) {
    const auto parts = split(item.get<std::string>(), ',');
    ok = parts.size() == 3 && parse_double(parts[0], &v->x()) && parse_double(parts[1], &v->y()) && parse_double(parts[2], &v->z());
  }
  return ok && v->allFinite();
}

std::string shown(const nlohmann::json& j) { return j.is_string() ? "\"" + j.get<std::string>() + "\"" : j.dump(); }

}  // namespace

std::vector<std::string> stage_flags(const std::vector<std::string>& leading, const std::vector<std::string>& config_keys,
                                     const std::vector<std::string>& trailing) {
  std::vector<std::string> flags = leading;
  for (std::string key : config_keys) {
    std::replace(key.begin(), key.end(), '_', '-');
    flags.push_back(key);
  }
  flags.insert(flags.end(), trailing.begin(), trailing.end());
  return flags;
}

StageArguments::StageArguments(const CommandLine& cl, const std::vector<std::string>& config_keys)
    : cl_(cl), program_(cl.program()) {
  if (const auto file = cl.get("config")) {
    config_file_ = *file;
    config_ = read_json_file<nlohmann::json>(*file);
    if (!config_.is_object()) throw_input_error(*file, "", "a JSON object", config_.type_name());
    for (auto it = config_.begin(); it != config_.end(); ++it)
      if (std::find(config_keys.begin(), config_keys.end(), it.key()) == config_keys.end()) {
        std::string known;
        for (const auto& k : config_keys) known += (known.empty() ? "" : "|") + k;
        throw_input_error(*file, it.key(), "one of " + known, "an unknown key");
      }
  }
}

std::string StageArguments::where(const std::string& flag) const {
  if (cl_.has(flag)) return program_ + ": --" + flag;
  return config_file_ + ": " + key_of(flag);
}

std::optional<nlohmann::json> StageArguments::raw(const std::string& flag) const {
  if (const auto v = cl_.get(flag)) return nlohmann::json(*v);
  const std::string key = key_of(flag);
  if (config_.contains(key)) return config_[key];
  return std::nullopt;
}

bool StageArguments::has(const std::string& flag) const { return raw(flag).has_value(); }

std::string StageArguments::text(const std::string& flag, const std::string& fallback) {
  const auto r = raw(flag);
  std::string v = fallback;
  if (r) {
    if (r->is_number()) v = r->dump();  // "threshold": 300 and --threshold 300 alike
    else if (r->is_string()) v = r->get<std::string>();
    else throw InputError(where(flag) + ": expected a string, found " + shown(*r));
  }
  used_[key_of(flag)] = v;
  return v;
}

std::string StageArguments::choice(const std::string& flag, const std::string& fallback, const std::vector<std::string>& choices) {
  const std::string v = text(flag, fallback);
  if (std::find(choices.begin(), choices.end(), v) == choices.end()) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : "|") + c;
    throw InputError(where(flag) + ": expected " + list + ", found \"" + v + "\"");
  }
  return v;
}

double StageArguments::number(const std::string& flag, double fallback, double lo, double hi) {
  const auto r = raw(flag);
  double x = fallback;
  if (r) {
    const bool ok = r->is_number() ? (x = r->get<double>(), true) : (r->is_string() && parse_double(r->get<std::string>(), &x));
    if (!ok || !(x >= lo && x <= hi)) {
      std::ostringstream e;
      e << where(flag) << ": expected a number in [" << lo << ", " << hi << "], found " << shown(*r);
      throw InputError(e.str());
    }
  }
  used_[key_of(flag)] = x;
  return x;
}

long long StageArguments::integer(const std::string& flag, long long fallback, long long lo, long long hi) {
  const double x = number(flag, double(fallback), double(lo), double(hi));
  if (x != std::floor(x)) throw InputError(where(flag) + ": expected a whole number, found " + std::to_string(x));
  used_[key_of(flag)] = static_cast<long long>(x);
  return static_cast<long long>(x);
}

double StageArguments::length_mm(const std::string& flag, double fallback, double lo, double hi) {
  const auto r = raw(flag);
  double x = fallback;
  if (r) {
    bool ok = false;
    if (r->is_number()) {
      x = r->get<double>();
      ok = true;
    } else if (r->is_string()) {
      std::string s = r->get<std::string>();
      double scale = 1;
      for (const auto& [unit, factor] : {std::pair<std::string, double>{"mm", 1.0}, {"cm", 10.0}, {"um", 1e-3}, {"m", 1e3}})
        if (s.size() > unit.size() && s.compare(s.size() - unit.size(), unit.size(), unit) == 0) {
          s = s.substr(0, s.size() - unit.size());
          while (!s.empty() && s.back() == ' ') s.pop_back();
          scale = factor;
          break;
        }
      ok = parse_double(s, &x);
      x *= scale;
    }
    if (!ok || !(x >= lo && x <= hi)) {
      std::ostringstream e;
      e << where(flag) << ": expected a length in [" << lo << ", " << hi << "] mm, found " << shown(*r);
      throw InputError(e.str());
    }
  }
  used_[key_of(flag)] = x;
  return x;
}

std::optional<Vec3> StageArguments::vector3(const std::string& flag) {
  const auto r = raw(flag);
  if (!r) return std::nullopt;
  Vec3 v;
  if (!parse_point(*r, &v)) throw InputError(where(flag) + ": expected three numbers x,y,z, found " + shown(*r));
  used_[key_of(flag)] = {v.x(), v.y(), v.z()};
  return v;
}

std::vector<Vec3> StageArguments::points(const std::string& flag) {
  std::vector<Vec3> out;
  nlohmann::json items = nlohmann::json::array();
  if (cl_.has(flag)) {
    for (const auto& s : cl_.get_all(flag)) items.push_back(s);
  } else if (config_.contains(key_of(flag))) {
    items = config_[key_of(flag)];
    if (!items.is_array()) throw InputError(where(flag) + ": expected a list of [x, y, z] points, found " + shown(items));
  }
  nlohmann::json record = nlohmann::json::array();
  for (const auto& item : items) {
    Vec3 v;
    if (!parse_point(item, &v)) throw InputError(where(flag) + ": expected points x,y,z, found " + shown(item));
    out.push_back(v);
    record.push_back({v.x(), v.y(), v.z()});
  }
  used_[key_of(flag)] = record;
  return out;
}

std::optional<std::vector<double>> StageArguments::numbers(const std::string& flag, size_t count) {
  const auto r = raw(flag);
  if (!r) return std::nullopt;
  std::vector<double> out;
  bool ok = true;
  if (r->is_string()) {
    for (const auto& p : split(r->get<std::string>(), ',')) {
      double x = 0;
      ok = ok && parse_double(p, &x) && std::isfinite(x);
      out.push_back(x);
    }
  } else if (r->is_array()) {
    for (const auto& it : *r) {
      ok = ok && it.is_number();
      out.push_back(it.is_number() ? it.get<double>() : 0.0);
    }
  } else {
    ok = false;
  }
  if (!ok || out.size() != count)
    throw InputError(where(flag) + ": expected " + std::to_string(count) + " numbers a,b,..., found " + shown(*r));
  used_[key_of(flag)] = out;
  return out;
}

std::vector<int> StageArguments::integers(const std::string& flag, const std::vector<int>& fallback) {
  const auto r = raw(flag);
  std::vector<int> out = fallback;
  if (r) {
    out.clear();
    nlohmann::json items = *r;
    if (r->is_string()) {
      items = nlohmann::json::array();
      for (const auto& p : split(r->get<std::string>(), ',')) {
        double x;
        if (!parse_double(p, &x)) throw InputError(where(flag) + ": expected integers a,b,..., found " + shown(*r));
        items.push_back(x);
      }
    } else if (r->is_number()) {
      items = nlohmann::json::array({*r});
    }
    for (const auto& it : items) {
      if (!it.is_number() || it.get<double>() != std::floor(it.get<double>()))
        throw InputError(where(flag) + ": expected integers, found " + shown(*r));
      out.push_back(it.get<int>());
    }
    if (out.empty()) throw InputError(where(flag) + ": expected at least one integer, found none");
  }
  used_[key_of(flag)] = out;
  return out;
}

}  // namespace valve
