// The available memory read from a meminfo file.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "valve/core/system_memory.hpp"

using namespace valve;
namespace fs = std::filesystem;

TEST_CASE("available memory is MemAvailable in bytes, 0 when unknown", "[core]") {
  const fs::path file = fs::temp_directory_path() / "valve_meminfo_test";
  std::ofstream(file) << "MemTotal:       16000000 kB\nMemFree:         1000000 kB\nMemAvailable:    8000000 kB\n";
  CHECK(available_memory_bytes(file) == 8000000.0 * 1024);
  std::ofstream(file) << "MemTotal:       16000000 kB\n";
  CHECK(available_memory_bytes(file) == 0);
  fs::remove(file);
  CHECK(available_memory_bytes(file) == 0);
  CHECK(available_memory_bytes() > 0);  // this machine's /proc/meminfo
}
