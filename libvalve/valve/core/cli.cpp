#include "valve/core/cli.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"
#include "valve/core/parallel.hpp"
#include "valve/core/progress.hpp"
#include "valve/core/slicer_cli.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
// A stage's wall time counts from its start (static initialization), not from when its
// summary object is made, which stages do once the work is done.
const double process_start = now_seconds();
}  // namespace

CommandLine::CommandLine(int argc, char** argv, const std::vector<std::string>& flags,
                         const std::vector<std::string>& switches) {
  program_ = argc > 0 ? fs::path(argv[0]).filename().string() : "valve";
  auto is_in = [](const std::vector<std::string>& v, const std::string& s) {
    for (const auto& x : v)
      if (x == s) return true;
    return false;
  };
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") throw HelpRequested{};
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--xml") throw XmlRequested{flags, switches};
  // Every stage reports progress the same way, so the option is common rather than listed.
  std::vector<std::string> accepted = flags;
  accepted.push_back("progress");
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0) {
      positional_.push_back(a);
      continue;
    }
    std::string value;
    const auto eq = a.find('=');
    if (eq != std::string::npos) {
      value = a.substr(eq + 1);
      a = a.substr(0, eq);
    }
    const std::string name = a.substr(2);
    if (is_in(switches, name)) {
      // A bare switch is on; --switch=false (or 0, no, off) turns it off.
      bool on = true;
      if (eq != std::string::npos) {
        if (value == "true" || value == "1" || value == "yes" || value == "on") on = true;
        else if (value == "false" || value == "0" || value == "no" || value == "off") on = false;
        else throw InputError("--" + name + ": expected true or false, found \"" + value + "\"");
      }
      switch_values_[name] = on;
    } else if (is_in(accepted, name)) {
      if (eq == std::string::npos) {
        if (i + 1 >= argc) throw InputError("--" + name + ": expected a value, found the end of the command line");
        value = argv[++i];
      }
      values_[name].push_back(value);
    } else {
      std::string known;
      for (const auto& f : accepted) known += " --" + f;
      for (const auto& f : switches) known += " --" + f;
      throw InputError(a + ": expected one of" + known + ", found an unknown option (--help prints the usage)");
    }
  }
  if (const auto style = get("progress")) set_progress_style(parse_progress_style(*style, "--progress"));
}

std::optional<std::string> CommandLine::get(const std::string& flag) const {
  auto it = values_.find(flag);
  if (it == values_.end()) return std::nullopt;
  return it->second.back();
}

std::vector<std::string> CommandLine::get_all(const std::string& flag) const {
  auto it = values_.find(flag);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

double number_flag(const CommandLine& cl, const std::string& flag, double fallback, double lo, double hi) {
  const auto v = cl.get(flag);
  if (!v) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  const bool plain = v->find_first_of("xXnN") == std::string::npos;
  if (!plain || end == v->c_str() || *end != '\0' || !(x >= lo && x <= hi))
    throw InputError("--" + flag + ": expected a number in [" + format_number(lo) + ", " + format_number(hi) + "], found \"" +
                     *v + "\"");
  return x;
}

long whole_number_flag(const CommandLine& cl, const std::string& flag, long fallback, long lo, long hi) {
  const double x = number_flag(cl, flag, static_cast<double>(fallback), static_cast<double>(lo), static_cast<double>(hi));
  if (x != std::floor(x))
    throw InputError("--" + flag + ": expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], found \"" + *cl.get(flag) + "\"");
  return static_cast<long>(x);
}

void apply_override(nlohmann::json& config, const std::string& assignment, const std::string& where) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(where + ": --set: expected key.path=value, found \"" + assignment + "\"");
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  nlohmann::json* node = &config;
  size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (key.empty()) throw InputError(where + ": --set: expected key.path=value, found an empty key in \"" + path + "\"");
    if (!node->is_object()) *node = nlohmann::json::object();
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  const auto parsed = nlohmann::json::parse(text, nullptr, false);
  *node = parsed.is_discarded() ? nlohmann::json(text) : parsed;
}

std::string CommandLine::require(const std::string& flag) const {
  auto v = get(flag);
  if (!v) throw InputError("--" + flag + ": expected a value, found nothing (the option is required)");
  if (v->empty()) throw InputError("--" + flag + ": expected a value, found an empty string");
  return *v;
}

bool CommandLine::has(const std::string& flag) const {
  const auto on = switch_values_.find(flag);
  return on != switch_values_.end() ? on->second : values_.count(flag) > 0;
}

StageSummary::StageSummary(std::string stage, fs::path out_dir)
    : stage_(std::move(stage)), out_(std::move(out_dir)), start_(process_start) {
  // Made here, before any output, so that an unusable --out is a bad input (exit 2) rather
  // than a filesystem error half way through the writing.
  if (out_.empty()) throw InputError("--out: expected a directory, found an empty path");
  std::error_code ec;
  if (fs::exists(out_, ec) && !fs::is_directory(out_, ec))
    throw_input_error(out_.string(), "--out", "a directory", "a file that is not one");
  fs::create_directories(out_, ec);
  if (ec) throw_input_error(out_.string(), "--out", "a directory that can be created", ec.message());
  const fs::path probe = out_ / (".write_probe" + std::to_string(::getpid()));
  {
    std::ofstream test(probe);
    if (!test) throw_input_error(out_.string(), "--out", "a writable directory", "not writable");
  }
  fs::remove(probe, ec);
  // An earlier run's summary would otherwise outlive a failure of this one and still say ok.
  discard_on_failure(out_ / (stage_ + ".summary.json"));
  doc_ = {{"stage", stage_}, {"status", "ok"}, {"inputs", nlohmann::json::array()},
          {"parameters", nlohmann::json::object()}, {"metrics", nlohmann::json::object()}};
}

void StageSummary::add_input(const std::string& role, const fs::path& path) {
  doc_["inputs"].push_back({{"role", role}, {"path", path.string()}, {"sha256", sha256_file(path)}});
}

void StageSummary::set_status(const std::string& status, const std::string& reason) {
  doc_["status"] = status;
  if (!reason.empty()) doc_["reason"] = reason;
}

int scrub_non_finite(nlohmann::json& j) {
  int n = 0;
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    j = nullptr;
    return 1;
  }
  if (j.is_structured())
    for (auto& e : j) n += scrub_non_finite(e);
  return n;
}

void StageSummary::write() {
  doc_["wall_time_s"] = now_seconds() - start_;
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) doc_["peak_memory_mb"] = usage.ru_maxrss / 1024.0;  // Linux: kB
  const int replaced = scrub_non_finite(doc_);
  if (replaced > 0) doc_["non_finite_values_replaced_by_null"] = replaced;
  write_file_atomic(out_ / (stage_ + ".summary.json"), doc_.dump(2) + "\n");
}

int run_stage(const std::string& program, const char* usage, const std::function<int()>& body) {
  try {
    worker_threads();  // a bad VALVE_THREADS is refused before anything runs
    return body();
  } catch (const HelpRequested&) {
    std::printf("%s", usage);
    return 0;
  } catch (const XmlRequested& x) {
    std::printf("%s", slicer_cli_xml(program, usage, x.flags, x.switches).c_str());
    return 0;
  } catch (const InputError& e) {
    discard_written_files();
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return 2;
  } catch (const NumericalError& e) {
    discard_written_files();
    std::fprintf(stderr, "%s: numerical failure: %s\n", program.c_str(), e.what());
    return 3;
  } catch (const std::exception& e) {
    discard_written_files();
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return 1;
  }
}

}  // namespace valve
