#include "valve/core/progress.hpp"

#include <cstdio>

namespace valve {

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)), quiet_(quiet), start_(std::chrono::steady_clock::now()), last_() {}

void Progress::update(double fraction, const std::string& detail) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(500)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = fraction > 1e-6 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  if (eta >= 0)
    std::fprintf(stderr, "[%s] %5.1f%% %s, ETA %.1f s\n", label_.c_str(), 100.0 * fraction,
                 detail.c_str(), eta);
  else
    std::fprintf(stderr, "[%s] %s\n", label_.c_str(), detail.c_str());
}

void Progress::finish(const std::string& detail) {
  if (quiet_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "[%s] done in %.2f s: %s\n", label_.c_str(), elapsed, detail.c_str());
}

}  // namespace valve
