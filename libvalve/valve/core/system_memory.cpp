#include "valve/core/system_memory.hpp"

#include <fstream>
#include <string>

namespace valve {

double available_memory_bytes(const std::filesystem::path& meminfo) {
  std::ifstream in(meminfo);
  std::string key, unit;
  double kb = 0;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return 0;
}

}  // namespace valve
