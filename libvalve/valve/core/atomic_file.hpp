#pragma once
// Outputs are written to a temporary sibling and renamed into place, so a failed or
// interrupted stage never leaves a half-written file behind.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>

#include "valve/core/error.hpp"

namespace valve {

/// Writes `content` to `path` atomically (temp file + rename). Throws Error on failure.
void write_file_atomic(const std::filesystem::path& path, const std::string& content);

/// Calls `writer(temp_path)` and renames temp_path to `path` if it returns normally;
/// removes the temporary file if it throws. For writers that need a file name (VTK).
void write_via_temp(const std::filesystem::path& path,
                    const std::function<void(const std::filesystem::path&)>& writer);

/// The process's file-creation mask (umask), read without changing it: the permissions a
/// temporary made by mkstemp or mkdtemp (0600, 0700) must get to be like any new file's.
unsigned file_creation_mask();

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

/// Parses a JSON file (nlohmann::json or ordered_json; with // and /* */ comments when
/// `comments`). Throws InputError naming the file and, for a syntax error, its line.
template <class Json>
Json read_json_file(const std::filesystem::path& path, bool comments = false) {
  const std::string text = read_text_file(path);
  try {
    return Json::parse(text, nullptr, true, comments);
  } catch (const typename Json::parse_error& e) {
    // Turn the byte offset into a line number: people open files by line.
    const size_t offset = std::min<size_t>(e.byte, text.size());
    const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + offset, '\n'));
    throw InputError(path.string() + ": line " + std::to_string(line) +
                     ": expected valid JSON, found a syntax error (" + e.what() + ")");
  } catch (const typename Json::out_of_range& e) {
    // A number too large for a double (1e999) fails after the syntax check, without a position.
    throw InputError(path.string() + ": expected numbers a double can hold, found " + e.what());
  }
}

/// SHA-256 of a file's bytes as lowercase hex; throws InputError if unreadable.
std::string sha256_file(const std::filesystem::path& path);

/// SHA-256 of a string as lowercase hex.
std::string sha256_text(const std::string& text);

}  // namespace valve
