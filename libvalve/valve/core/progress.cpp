#include "valve/core/progress.hpp"

#include <algorithm>
#include <cstdio>

#include "valve/core/error.hpp"

namespace valve {

namespace {
ProgressStyle g_style = ProgressStyle::text;

// Slicer's CLI protocol (SlicerExecutionModel): XML-like tags on stdout, each flushed at once
// because Slicer parses the pipe as it arrives.
void slicer_line(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
}
}  // namespace

void set_progress_style(ProgressStyle style) { g_style = style; }
ProgressStyle progress_style() { return g_style; }

ProgressStyle parse_progress_style(const std::string& value, const std::string& where) {
  if (value == "text") return ProgressStyle::text;
  if (value == "slicer") return ProgressStyle::slicer;
  if (value == "none") return ProgressStyle::none;
  throw InputError(where + ": expected text|slicer|none, found \"" + value + "\"");
}

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)), quiet_(quiet), start_(std::chrono::steady_clock::now()), last_() {
  if (g_style == ProgressStyle::slicer)
    slicer_line("<filter-start>\n<filter-name>" + label_ + "</filter-name>\n<filter-comment>" + label_ +
                "</filter-comment>\n</filter-start>\n");
}

void Progress::update(double fraction, const std::string& detail) {
  if (g_style == ProgressStyle::none || (g_style == ProgressStyle::text && quiet_)) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(500)) return;
  last_ = now;
  fraction = std::clamp(fraction, 0.0, 1.0);
  if (g_style == ProgressStyle::slicer) {
    char line[64];
    std::snprintf(line, sizeof line, "<filter-progress>%.4f</filter-progress>\n", fraction);
    slicer_line(line);
    return;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = fraction > 1e-6 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  if (eta >= 0)
    std::fprintf(stderr, "[%s] %5.1f%% %s, ETA %.1f s\n", label_.c_str(), 100.0 * fraction,
                 detail.c_str(), eta);
  else
    std::fprintf(stderr, "[%s] %s\n", label_.c_str(), detail.c_str());
}

void Progress::finish(const std::string& detail) {
  if (g_style == ProgressStyle::none || (g_style == ProgressStyle::text && quiet_)) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (g_style == ProgressStyle::slicer) {
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", elapsed);
    slicer_line("<filter-progress>1</filter-progress>\n<filter-end>\n<filter-name>" + label_ +
                "</filter-name>\n<filter-time>" + time + "</filter-time>\n</filter-end>\n");
    return;
  }
  std::fprintf(stderr, "[%s] done in %.2f s: %s\n", label_.c_str(), elapsed, detail.c_str());
}

}  // namespace valve
