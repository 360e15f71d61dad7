#pragma once
// Outputs are written to a temporary sibling and renamed into place, so a failed or
// interrupted stage never leaves a half-written file behind.
#include <filesystem>
#include <functional>
#include <string>

namespace valve {

/// Writes `content` to `path` atomically (temp file + rename). Throws Error on failure.
void write_file_atomic(const std::filesystem::path& path, const std::string& content);

/// Calls `writer(temp_path)` and renames temp_path to `path` if it returns normally;
/// removes the temporary file if it throws. For writers that need a file name (VTK).
void write_via_temp(const std::filesystem::path& path,
                    const std::function<void(const std::filesystem::path&)>& writer);

/// Reads a whole file; throws InputError naming the file if it cannot be read.
std::string read_text_file(const std::filesystem::path& path);

/// SHA-256 of a file's bytes as lowercase hex; throws InputError if unreadable.
std::string sha256_file(const std::filesystem::path& path);

/// SHA-256 of a string as lowercase hex.
std::string sha256_text(const std::string& text);

}  // namespace valve
