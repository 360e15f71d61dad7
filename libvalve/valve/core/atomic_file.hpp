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

/// The files written through write_via_temp / write_file_atomic so far in this process.
/// run_stage removes them when a stage fails with an exception: a stage that stops half way
/// leaves none of its outputs (each file alone is already atomic; this makes the set so).
/// valve-pipeline opts out with keep_written_files_on_failure(): its log and tables explain
/// the failure, and its stages' outputs are theirs.
void discard_written_files();
void keep_written_files_on_failure();
/// Adds `path` to the files discard_written_files() removes, written or not yet (a stage's
/// summary, so that an earlier run's does not outlive this run's failure).
void discard_on_failure(const std::filesystem::path& path);

/// Reads a whole file; throws InputError naming the file if it cannot be read.
std::string read_text_file(const std::filesystem::path& path);

/// SHA-256 of a file's bytes as lowercase hex; throws InputError if unreadable.
std::string sha256_file(const std::filesystem::path& path);

/// SHA-256 of a string as lowercase hex.
std::string sha256_text(const std::string& text);

}  // namespace valve
