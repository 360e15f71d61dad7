#pragma once
// Child processes for the pipeline runner: stage lookup, spawning without a shell, waiting.
//
// Stage lookup: "valve-xyz" is searched, in order, in the extra directories the caller
// gives (valve-pipeline --stage-dir), in the directory of the running executable
// (/proc/self/exe), in its sibling ../stages/ (a build tree), and then on PATH. The first
// regular executable file wins.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace valve {

/// The default stage directories after `extra`: the executable's directory and ../stages.
std::vector<std::filesystem::path> default_stage_dirs(const std::vector<std::filesystem::path>& extra);

/// An executable `name` on PATH, or nothing.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

/// The executable of stage `name` in `dirs`, then on PATH, or nothing.
std::optional<std::filesystem::path> find_stage(const std::string& name,
                                                const std::vector<std::filesystem::path>& dirs);

/// How a child ended. `code` is the exit status, or 128 + signal when a signal killed it
/// (the shell's convention), or 127 when it could not be started (`error` says why).
struct ProcessExit {
  int code = 0;
  int signal = 0;
  double cpu_time_s = 0;  ///< user + system time of the child
  std::string error;
};

/// Starts `executable` with arguments `args` (argv[0] is the executable path) in working
/// directory `cwd`, stdin from /dev/null, stdout and stderr both into `log` (truncated; its
/// first line is the command, shell-quoted, to re-run it by hand). No shell is involved.
/// Returns the pid, or -1 with `error` set when it could not be started (the reason is also
/// appended to the log).
pid_t spawn_process(const std::filesystem::path& executable, const std::vector<std::string>& args,
                    const std::filesystem::path& cwd, const std::filesystem::path& log, std::string& error);

/// Waits for any child; returns its pid (or -1 when there is none) and fills `exit`.
pid_t wait_any_child(ProcessExit& exit);

/// spawn_process + wait for that child.
ProcessExit run_process(const std::filesystem::path& executable, const std::vector<std::string>& args,
                        const std::filesystem::path& cwd, const std::filesystem::path& log);

/// A command line as a POSIX shell would need it quoted, for logs and dry runs.
std::string shell_quote(const std::vector<std::string>& words);

}  // namespace valve
