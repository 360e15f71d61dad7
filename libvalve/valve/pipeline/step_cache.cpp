#include "valve/pipeline/step_cache.hpp"

#include <algorithm>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

fs::path resolve_in(const fs::path& run_dir, const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() ? path : run_dir / path;
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// The hash of a file now, or nothing if it is gone or unreadable.
std::optional<std::string> current_hash(const fs::path& p) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return std::nullopt;
  try {
    return sha256_file(p);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<nlohmann::json> read_json(const fs::path& p) {
  if (!is_file(p)) return std::nullopt;
  try {
    return nlohmann::json::parse(read_text_file(p));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::vector<StepInput> stamp_inputs(const nlohmann::json& stamp) {
  std::vector<StepInput> inputs;
  if (!stamp.contains("inputs") || !stamp["inputs"].is_array()) return inputs;
  for (const auto& in : stamp["inputs"])
    if (in.contains("path") && in.contains("sha256"))
      inputs.push_back({in["path"].get<std::string>(), in["sha256"].get<std::string>()});
  return inputs;
}

}  // namespace

std::string step_cache_key(const std::string& executable_sha256, const ResolvedStep& step) {
  std::string text = executable_sha256 + '\0' + step.stage;
  for (const auto& a : step.args) text += '\0' + a;
  return sha256_text(text);
}

fs::path step_stamp_path(const fs::path& run_dir, const std::string& step) {
  return run_dir / ".valve-cache" / (step + ".json");
}

std::optional<fs::path> step_out_dir(const ResolvedStep& step, const fs::path& run_dir) {
  for (size_t i = 0; i + 1 < step.args.size(); ++i)
    if (step.args[i] == "--out") return resolve_in(run_dir, step.args[i + 1]).lexically_normal();
  return std::nullopt;
}

std::vector<StepInput> step_inputs(const fs::path& run_dir, const ResolvedStep& step) {
  std::vector<StepInput> inputs;
  auto add = [&](const fs::path& p) {
    const std::string key = p.lexically_normal().string();
    if (std::any_of(inputs.begin(), inputs.end(), [&](const StepInput& s) { return s.path == key; })) return;
    if (const auto h = current_hash(p)) inputs.push_back({key, *h});
  };
  const auto out = step_out_dir(step, run_dir);
  for (const auto& a : step.args) {
    const fs::path p = resolve_in(run_dir, a);
    // A file the step wrote into its own output folder is not an input.
    if (out && p.lexically_normal().string().rfind(out->string() + "/", 0) == 0) continue;
    if (!a.empty() && a[0] != '-' && is_file(p)) add(p);
  }
  if (out) {
    std::string stage = step.stage;
    if (stage.rfind("valve-", 0) == 0) stage = stage.substr(6);
    if (const auto summary = read_json(*out / (stage + ".summary.json")))
      if (summary->contains("inputs") && (*summary)["inputs"].is_array())
        for (const auto& in : (*summary)["inputs"])
          if (in.contains("path") && in["path"].is_string()) add(resolve_in(run_dir, in["path"].get<std::string>()));
  }
  return inputs;
}

std::vector<StepInput> write_step_stamp(const fs::path& run_dir, const ResolvedStep& step, const std::string& key) {
  const auto inputs = step_inputs(run_dir, step);
  nlohmann::json j = {{"step", step.name}, {"stage", step.stage}, {"key", key}, {"inputs", nlohmann::json::array()}};
  for (const auto& in : inputs) j["inputs"].push_back({{"path", in.path}, {"sha256", in.sha256}});
  const fs::path stamp = step_stamp_path(run_dir, step.name);
  fs::create_directories(stamp.parent_path());
  write_file_atomic(stamp, j.dump(2) + "\n");
  return inputs;
}

std::vector<StepInput> read_step_stamp_inputs(const fs::path& run_dir, const std::string& step) {
  const auto j = read_json(step_stamp_path(run_dir, step));
  return j ? stamp_inputs(*j) : std::vector<StepInput>{};
}

std::optional<std::string> step_rerun_reason(const fs::path& run_dir, const ResolvedStep& step, const std::string& key) {
  const auto j = read_json(step_stamp_path(run_dir, step.name));
  if (!j) return std::string("never ran");
  if (!j->contains("key") || (*j)["key"] != key) return std::string("command or stage changed");
  for (const auto& in : stamp_inputs(*j)) {
    const auto h = current_hash(in.path);
    if (!h) return "input " + in.path + " is gone";
    if (*h != in.sha256) return "input " + in.path + " changed";
  }
  return std::nullopt;
}

void clear_step_outputs(const fs::path& run_dir, const ResolvedStep& step) {
  std::error_code ec;
  fs::remove(step_stamp_path(run_dir, step.name), ec);
  const auto out = step_out_dir(step, run_dir);
  const std::string root = run_dir.lexically_normal().string() + "/";
  if (out && out->string().rfind(root, 0) == 0 && out->string().size() > root.size()) fs::remove_all(*out, ec);
}

}  // namespace valve
