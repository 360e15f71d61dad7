#include "valve/pipeline/process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "valve/core/error.hpp"
#include "valve/core/install_layout.hpp"

extern char** environ;

namespace valve {
namespace fs = std::filesystem;

namespace {

bool is_executable_file(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
}

void write_all(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // a log that cannot be written must not stop the run
    done += static_cast<size_t>(n);
  }
}

ProcessExit decode_status(int status, const struct rusage& ru) {
  ProcessExit exit;
  exit.cpu_time_s = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                    1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  if (WIFEXITED(status)) {
    exit.code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    exit.signal = WTERMSIG(status);
    exit.code = 128 + exit.signal;
    exit.error = "killed by signal " + std::to_string(exit.signal) + " (" + strsignal(exit.signal) + ")";
  }
  return exit;
}

}  // namespace

std::vector<fs::path> default_stage_dirs(const std::vector<fs::path>& extra) {
  std::vector<fs::path> dirs = extra;
  const fs::path self = executable_directory();
  if (!self.empty()) {
    // In the build tree the stages directory is both: list it once (it is shown in errors).
    for (const fs::path& d : {self, (self / ".." / "stages").lexically_normal()})
      if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
  }
  return dirs;
}

std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    const auto colon = dirs.find(':', start);
    std::string dir = dirs.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
    if (dir.empty()) dir = ".";  // an empty PATH entry means the current directory
    const fs::path candidate = fs::path(dir) / name;
    if (is_executable_file(candidate)) return fs::absolute(candidate);
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  return std::nullopt;
}

std::optional<fs::path> find_stage(const std::string& name, const std::vector<fs::path>& dirs) {
  for (const auto& dir : dirs) {
    const fs::path candidate = dir / name;
    if (is_executable_file(candidate)) return fs::absolute(candidate).lexically_normal();
  }
  return find_on_path(name);
}

std::string shell_quote(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) {
    if (!out.empty()) out += ' ';
    const bool plain = !w.empty() && w.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                        "0123456789_-+=/.,:@%") == std::string::npos;
    if (plain) {
      out += w;
      continue;
    }
    out += '\'';
    for (char c : w) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

pid_t spawn_process(const fs::path& executable, const std::vector<std::string>& args, const fs::path& cwd,
                    const fs::path& log, std::string& error) {
  // O_CLOEXEC: with several runs in parallel, one child must not inherit another's log.
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = log.string() + ": cannot open the log: " + std::strerror(errno);
    return -1;
  }
  std::vector<std::string> words{executable.string()};
  words.insert(words.end(), args.begin(), args.end());
  write_all(fd, "# cd " + shell_quote({cwd.string()}) + " && " + shell_quote(words) + "\n");

  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fd, STDERR_FILENO);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    error = "cannot start " + executable.string() + ": " + std::strerror(rc);
    write_all(fd, "# valve-pipeline: " + error + "\n");
    ::close(fd);
    return -1;
  }
  ::close(fd);
  return pid;
}

pid_t wait_any_child(ProcessExit& exit) {
  int status = 0;
  struct rusage ru {};
  pid_t pid;
  do {
    pid = ::wait4(-1, &status, 0, &ru);
  } while (pid < 0 && errno == EINTR);
  if (pid < 0) return -1;
  exit = decode_status(status, ru);
  return pid;
}

ProcessExit run_process(const fs::path& executable, const std::vector<std::string>& args, const fs::path& cwd,
                        const fs::path& log) {
  ProcessExit exit;
  const pid_t pid = spawn_process(executable, args, cwd, log, exit.error);
  if (pid < 0) {
    exit.code = 127;
    return exit;
  }
  int status = 0;
  struct rusage ru {};
  pid_t got;
  do {
    got = ::wait4(pid, &status, 0, &ru);
  } while (got < 0 && errno == EINTR);
  if (got < 0) throw Error("cannot wait for " + executable.string() + ": " + std::strerror(errno));
  return decode_status(status, ru);
}

}  // namespace valve
