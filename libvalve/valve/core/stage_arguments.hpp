#pragma once
// Typed access to a stage's settings: a --flag, else the same key in the --config JSON
// (flag "gaussian-sigma" <-> key "gaussian_sigma"), else the default. Flags override the
// config. Every problem is one line naming the flag or key, what was expected and what was
// found (InputError, exit code 2). Every value read is recorded for the stage summary.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "valve/core/cli.hpp"
#include "valve/core/types.hpp"

namespace valve {

/// A stage's --flags: `leading`, then the flag of each config key ("gaussian_sigma" ->
/// "gaussian-sigma"), then `trailing`. The order is the one --xml lists them in.
std::vector<std::string> stage_flags(const std::vector<std::string>& leading, const std::vector<std::string>& config_keys,
                                     const std::vector<std::string>& trailing = {});

class StageArguments {
 public:
  /// Reads --config FILE.json if the command line has it; unknown config keys are refused.
  StageArguments(const CommandLine& cl, const std::vector<std::string>& config_keys);

  bool has(const std::string& flag) const;
  std::string text(const std::string& flag, const std::string& fallback);
  /// One of `choices`.
  std::string choice(const std::string& flag, const std::string& fallback, const std::vector<std::string>& choices);
  double number(const std::string& flag, double fallback, double lo, double hi);
  long long integer(const std::string& flag, long long fallback, long long lo, long long hi);
  /// A length in mm: a number, or a string "<number> mm|cm|um".
  double length_mm(const std::string& flag, double fallback, double lo, double hi);
  /// "x,y,z" on the command line, [x, y, z] in the config.
  std::optional<Vec3> vector3(const std::string& flag);
  /// Repeatable flag "x,y,z" / config array of [x, y, z].
  std::vector<Vec3> points(const std::string& flag);
  /// Exactly `count` numbers "a,b" / [a, b]; nothing when unset.
  std::optional<std::vector<double>> numbers(const std::string& flag, size_t count);
  /// A list of integers "1,2" / [1, 2].
  std::vector<int> integers(const std::string& flag, const std::vector<int>& fallback);

  /// Every value read, after defaults, keyed by config key.
  const nlohmann::json& used() const { return used_; }
  const std::string& program() const { return program_; }

 private:
  std::optional<nlohmann::json> raw(const std::string& flag) const;  // flag (as string) or config value
  std::string where(const std::string& flag) const;
  const CommandLine& cl_;
  std::string program_;
  std::string config_file_;
  nlohmann::json config_ = nlohmann::json::object();
  nlohmann::json used_ = nlohmann::json::object();
};

}  // namespace valve
