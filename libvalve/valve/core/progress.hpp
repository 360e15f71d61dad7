#pragma once
// Progress on stderr (fraction, step, ETA) for long work; silenced by --quiet.
#include <chrono>
#include <string>

namespace valve {

class Progress {
 public:
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
