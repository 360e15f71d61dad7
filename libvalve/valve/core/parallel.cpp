#include "valve/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <sched.h>

#include "valve/core/error.hpp"

namespace valve {

namespace {

int cores_available() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace

int worker_threads() {
  static const int threads = [] {
    const char* v = std::getenv("VALVE_THREADS");
    if (!v) return cores_available();
    const std::string text(v);
    const bool digits = !text.empty() && text.size() <= 4 &&
                        std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    const int n = digits ? std::stoi(text) : 0;
    if (n < 1) throw InputError("VALVE_THREADS: expected a whole number of threads from 1 to 9999, found \"" + text + "\"");
    return n;
  }();
  return threads;
}

std::size_t chunks_for(std::size_t n, std::size_t per_chunk) {
  // A thread's start costs tens of microseconds; 2,000 distance queries take about 300 (0.15 µs
  // each in the aortic closure's candidate list). More chunks than threads even out chunks whose
  // pairs cost unevenly (a lower bound settles some at once, others need the exact distance).
  constexpr std::size_t kMostChunks = 64;
  per_chunk = std::max<std::size_t>(per_chunk, 1);
  if (n < 2 * per_chunk) return 1;
  return std::min(kMostChunks, n / per_chunk);
}

void for_each_chunk(std::size_t n, std::size_t chunks, const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
  chunks = std::max<std::size_t>(1, std::min(chunks, n));
  auto range = [&](std::size_t c) { return std::pair<std::size_t, std::size_t>{n * c / chunks, n * (c + 1) / chunks}; };
  const std::size_t threads = std::min<std::size_t>(static_cast<std::size_t>(worker_threads()), chunks);
  if (threads <= 1) {
    for (std::size_t c = 0; c < chunks; ++c) {
      const auto [b, e] = range(c);
      body(c, b, e);
    }
    return;
  }
  // An error in a chunk (bad_alloc) is kept until every thread has finished, and the lowest
  // chunk's is rethrown, as the serial loop would have thrown it first. A helper thread that
  // cannot start (a process limit) leaves its chunks to the others.
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(chunks);
  auto work = [&] {
    for (std::size_t c; (c = next.fetch_add(1)) < chunks;) {
      const auto [b, e] = range(c);
      try {
        body(c, b, e);
      } catch (...) {
        errors[c] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> helpers;
  helpers.reserve(threads - 1);
  for (std::size_t t = 1; t < threads; ++t) {
    try {
      helpers.emplace_back(work);
    } catch (const std::system_error&) {
      break;
    }
  }
  work();
  for (auto& h : helpers) h.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace valve
