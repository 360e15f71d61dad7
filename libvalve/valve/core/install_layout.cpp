#include "valve/core/install_layout.hpp"

#include <cstdlib>
#include <system_error>

#ifndef VALVE_INSTALL_CONFIG_DIR
#define VALVE_INSTALL_CONFIG_DIR "/usr/local/share/valve/configs"
#endif

namespace valve {
namespace fs = std::filesystem;

fs::path executable_directory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

fs::path config_directory() {
  if (const char* env = std::getenv("VALVE_CONFIG_DIR"); env && *env) return env;
  const fs::path self = executable_directory();
  if (!self.empty()) {
    const fs::path beside = (self / ".." / "share" / "valve" / "configs").lexically_normal();
    std::error_code ec;
    if (fs::is_directory(beside, ec)) return beside;
  }
  return VALVE_INSTALL_CONFIG_DIR;
}

}  // namespace valve
