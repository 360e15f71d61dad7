#pragma once
// The memory the system can give a process now, for limits that follow the machine.
#include <filesystem>

namespace valve {

/// MemAvailable of /proc/meminfo (or of another file in its "Key: value kB" form), in bytes;
/// 0 when the file or the key is missing.
double available_memory_bytes(const std::filesystem::path& meminfo = "/proc/meminfo");

}  // namespace valve
