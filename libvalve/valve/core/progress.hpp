#pragma once
// Progress of long work (fraction, step, ETA): text lines on stderr, silenced by --quiet, or
// 3D Slicer's CLI protocol on stdout (--progress slicer), which Slicer reads to drive the
// progress bar of a module run from its GUI.
#include <chrono>
#include <string>

namespace valve {

enum class ProgressStyle { text, slicer, none };

/// How every Progress of the process reports (CommandLine sets it from --progress).
void set_progress_style(ProgressStyle style);
ProgressStyle progress_style();
/// "text", "slicer" or "none"; InputError naming `where` otherwise.
ProgressStyle parse_progress_style(const std::string& value, const std::string& where);

class Progress {
 public:
  /// `quiet` silences the text style only: the Slicer protocol is asked for explicitly.
  Progress(std::string label, bool quiet);
  /// Reports at most a few times per second; `fraction` in [0,1].
  void update(double fraction, const std::string& detail);
  void finish(const std::string& detail);

 private:
  std::string label_;
  bool quiet_;
  std::chrono::steady_clock::time_point start_, last_;
};

/// Wall-clock seconds since construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace valve
