#include "valve/pipeline/snakemake_export.hpp"

#include <cctype>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"
#include "valve/pipeline/process.hpp"
#include "valve/pipeline/runner.hpp"
#include "valve/pipeline/step_cache.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

// A Python string literal (JSON's escapes are Python's).
std::string py(const std::string& s) { return nlohmann::json(s).dump(); }

// A rule's file list, one per line, as snakemake's parser wants it after "input:" or "output:".
std::string py_list(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ",\n        " : "\n        ") + py(items[i]);
  return out;
}

// snakemake formats a shell command with str.format, so the command's own braces (JSON in
// --set arguments) are doubled.
std::string format_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    out += c;
    if (c == '{' || c == '}') out += c;
  }
  return out;
}

std::string identifier(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "s_" + out;
  return out;
}

bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }

// Whether `text` names the folder `dir` or a path inside it.
bool names_folder(const std::string& text, const std::string& dir) {
  for (size_t at = text.find(dir); at != std::string::npos; at = text.find(dir, at + 1)) {
    const size_t end = at + dir.size();
    if (end == text.size() || !is_name_char(text[end])) return true;
  }
  return false;
}

bool inside(const fs::path& p, const fs::path& dir) {
  const std::string d = dir.string() + "/";
  return p.string().rfind(d, 0) == 0;
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

struct Producer {
  std::string out;    // the step's --out folder
  std::string stamp;  // its rule's output
};

class SnakefileWriter {
 public:
  SnakefileWriter(const fs::path& root, const std::vector<fs::path>& stage_dirs, const fs::path& pipeline_exe)
      : root_(root), stage_dirs_(stage_dirs), pipeline_exe_(pipeline_exe) {}

  // Adds the rules of `spec` (and of the pipelines it requires) writing into `out`; returns
  // the files that mark it done: its tables, or every stamp when it has none.
  std::vector<std::string> add_pipeline(const PipelineSpec& spec, const fs::path& out, const std::string& prefix) {
    std::vector<std::string> upstream;
    for (const auto& r : spec.required) {
      const auto done = add_pipeline(*r.spec, out / r.out, prefix + identifier(r.out) + "__");
      upstream.insert(upstream.end(), done.begin(), done.end());
    }
    const auto exes = resolve_stages(spec, default_stage_dirs(stage_dirs_));
    for (size_t i = 0; i < spec.steps.size(); ++i) stages_[spec.steps[i].stage] = exes[i].string();
    const std::string file = fs::absolute(spec.file).lexically_normal().string();

    std::vector<std::string> stamps;
    auto add_run = [&](const RunPlan& run, size_t first_step, std::vector<Producer> producers) {
      for (size_t s = 0; s < run.steps.size(); ++s) {
        const ResolvedStep& step = run.steps[s];
        // Each argument as written, and as the paths it names (itself, or after KEY=) resolved
        // against the run folder, where the stage runs: "m/x.vtp" there is <run>/m/x.vtp.
        std::vector<std::string> texts;
        std::vector<fs::path> paths;
        for (const auto& a : step.args) {
          texts.push_back(a);
          const auto eq = a.find('=');
          for (const std::string& c : {a, eq == std::string::npos ? std::string() : a.substr(eq + 1)}) {
            if (c.empty() || c[0] == '-') continue;
            paths.push_back((fs::path(c).is_absolute() ? fs::path(c) : run.run_dir / c).lexically_normal());
            texts.push_back(paths.back().string());
          }
        }
        std::vector<std::string> inputs = upstream;
        for (const auto& p : producers)
          if (std::any_of(texts.begin(), texts.end(), [&](const std::string& t) { return names_folder(t, p.out); }))
            inputs.push_back(p.stamp);
        for (const auto& path : paths)
          if (!inside(path, root_) && is_file(path) && std::find(inputs.begin(), inputs.end(), path.string()) == inputs.end())
            inputs.push_back(path.string());
        const std::string stamp = step_stamp_path(run.run_dir, step.name).string();
        const auto out_dir = step_out_dir(step, run.run_dir);
        add_step_rule(prefix + identifier(step.name) + "__" + identifier(run.run_id), spec.steps[first_step + s],
                      step, run, out_dir, file, out, inputs, stamp);
        if (out_dir) producers.push_back({out_dir->string(), stamp});
        stamps.push_back(stamp);
      }
      return producers;
    };
    std::vector<Producer> shared;
    if (const auto plan = shared_run(spec, out)) shared = add_run(*plan, 0, {});
    for (const auto& run : expand_runs(spec, out)) add_run(run, spec.shared_steps, shared);

    std::vector<std::string> tables;
    for (const auto& csv : gather_csvs(spec)) tables.push_back((out / csv).string());
    for (const auto& a : spec.aggregates) tables.push_back((out / a.csv).string());
    // A plot is promised only where gnuplot is now; without it the native runner skips plots too.
    if (find_on_path("gnuplot"))
      for (const auto& p : spec.plots) tables.push_back((out / p.png).string());
    if (tables.empty()) return stamps;
    std::vector<std::string> words{pipeline_exe_.string(), "tables", file, "--out", out.string(), "--quiet"};
    for (const auto& d : stage_dirs_) {
      words.push_back("--stage-dir");
      words.push_back(d.string());
    }
    const std::string name = unique(prefix + "tables");
    local_rules_.push_back(name);
    text_ << "rule " << name << ":\n"
          << "    input:" << py_list(stamps) << "\n"
          << "    output:" << py_list(tables) << "\n"
          << "    shell: " << py(format_escaped(shell_quote(words))) << "\n\n";
    return tables;
  }

  std::string text(const PipelineSpec& spec, const std::vector<std::string>& targets) const {
    std::ostringstream head;
    head << "# Snakefile of the pipeline " << spec.name << " (" << fs::absolute(spec.file).lexically_normal().string()
         << "),\n"
         << "# written by valve-pipeline export --snakemake. It runs the steps the native runner runs\n"
         << "# (valve-pipeline run ... --out " << root_.string() << "), with the same executables and arguments,\n"
         << "# into the same folders, and writes the same cache stamps and tables. See docs/pipelines.md,\n"
         << "# \"Cluster route\". Export again after changing the pipeline file.\n"
         << "import hashlib\n\n"
         << "workdir: " << py(root_.string()) << "\n\n"
         << "STAGES = {\n";
    for (const auto& [stage, exe] : stages_) head << "    " << py(stage) << ": " << py(exe) << ",\n";
    head << "}\n\n"
         << "_stage_sha256 = {}\n\n"
         << "def stage_sha256(stage):\n"
         << "    \"\"\"The stage executable's hash, read now: a rebuilt stage changes the params of its rules.\"\"\"\n"
         << "    if stage not in _stage_sha256:\n"
         << "        digest = hashlib.sha256()\n"
         << "        with open(STAGES[stage], \"rb\") as f:\n"
         << "            for block in iter(lambda: f.read(1 << 20), b\"\"):\n"
         << "                digest.update(block)\n"
         << "        _stage_sha256[stage] = digest.hexdigest()\n"
         << "    return _stage_sha256[stage]\n\n";
    std::vector<std::string> local{"all"};
    local.insert(local.end(), local_rules_.begin(), local_rules_.end());
    head << "localrules: ";
    for (size_t i = 0; i < local.size(); ++i) head << (i ? ", " : "") << local[i];
    head << "\n\nrule all:\n    input:" << py_list(targets) << "\n\n";
    return head.str() + text_.str();
  }

  size_t step_rules() const { return step_rules_; }

 private:
  std::string unique(std::string name) {
    const std::string base = name;
    for (int k = 2; !names_.insert(name).second; ++k) name = base + "_" + std::to_string(k);
    return name;
  }

  void add_step_rule(const std::string& rule, const StepSpec& spec_step, const ResolvedStep& step, const RunPlan& run,
                     const std::optional<fs::path>& out_dir, const std::string& pipeline_file, const fs::path& out,
                     const std::vector<std::string>& inputs, const std::string& stamp) {
    const std::string run_dir = run.run_dir.string();
    std::string cmd = "mkdir -p " + shell_quote({run_dir}) + " && cd " + shell_quote({run_dir});
    // As the native runner clears a step's --out folder (when inside the run folder) before it runs.
    if (out_dir && inside(*out_dir, run.run_dir)) cmd += " && rm -rf -- " + shell_quote({out_dir->string()});
    std::vector<std::string> words{stages_.at(step.stage)};
    words.insert(words.end(), step.args.begin(), step.args.end());
    cmd += " && code=0 && ";
    // The stage's split loops (core/parallel.hpp) take the rule's threads, not every core.
    const std::string stage_cmd =
        shell_quote(words) + " > " + shell_quote({(run.run_dir / (step.name + ".log")).string()}) + " 2>&1 || code=$?; " +
        shell_quote({pipeline_exe_.string(), "stamp", pipeline_file, "--out", out.string(), "--run", run.run_id,
                     "--step", step.name}) +
        " --exit-code \"$code\"";
    text_ << "rule " << unique(rule) << ":\n";
    if (!inputs.empty()) text_ << "    input:" << py_list(inputs) << "\n";
    text_ << "    output: " << py(stamp) << "\n"
          << "    params: stage_sha256=stage_sha256(" << py(step.stage) << ")\n"
          << "    threads: " << spec_step.resources.threads << "\n"
          << "    resources: mem_mb=" << spec_step.resources.mem_mb << ", runtime=" << spec_step.resources.runtime_min
          << "\n"
          << "    shell: "
          << py(format_escaped(cmd) + "VALVE_THREADS={threads} " + format_escaped(stage_cmd) +
                " --stage-sha256 {params.stage_sha256}")
          << "\n\n";
    ++step_rules_;
  }

  fs::path root_;
  std::vector<fs::path> stage_dirs_;
  fs::path pipeline_exe_;
  std::map<std::string, std::string> stages_;
  std::set<std::string> names_{"all"};
  std::vector<std::string> local_rules_;
  std::ostringstream text_;
  size_t step_rules_ = 0;
};

}  // namespace

std::string snakefile_text(const PipelineSpec& spec, const fs::path& out_dir, const std::vector<fs::path>& stage_dirs,
                           const fs::path& pipeline_exe, size_t* step_rules) {
  const fs::path root = normalized_dir(out_dir);
  SnakefileWriter writer(root, stage_dirs, pipeline_exe);
  const auto targets = writer.add_pipeline(spec, root, "");
  if (step_rules) *step_rules = writer.step_rules();
  return writer.text(spec, targets);
}

SnakemakeExport export_snakemake(const PipelineSpec& spec, const fs::path& out_dir,
                                 const std::vector<fs::path>& stage_dirs, const fs::path& pipeline_exe) {
  SnakemakeExport result;
  const std::string text = snakefile_text(spec, out_dir, stage_dirs, pipeline_exe, &result.step_rules);
  result.snakefile = normalized_dir(out_dir) / "Snakefile";
  std::error_code ec;
  if (fs::exists(out_dir, ec) && !fs::is_directory(out_dir, ec))
    throw_input_error(out_dir.string(), "--out", "a folder", "a file");
  fs::create_directories(out_dir, ec);
  if (ec) throw_input_error(out_dir.string(), "--out", "a folder that can be created", ec.message());
  write_file_atomic(result.snakefile, text);
  return result;
}

}  // namespace valve
