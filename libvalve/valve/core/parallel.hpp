#pragma once
// Loops that split their work over the machine's cores, with results that do not depend on how
// many threads ran them: the range is cut into chunks by its length alone, each chunk's output
// is kept apart, and callers gather the chunks in order. A contact closure then lands on the
// same iterates bit for bit with one thread or two, so a run's answer never depends on the
// machine it ran on.
#include <cstddef>
#include <functional>
#include <vector>

namespace valve {

/// Threads a split loop may use: VALVE_THREADS when set (a whole number from 1 to 9999, else
/// InputError), else every core the process may run on. valve-pipeline gives the stages it runs
/// side by side their share of the cores (its own count over --jobs), so that they do not compete.
int worker_threads();

/// Runs body(chunk, begin, end) over [0, n) cut into `chunks` ranges of near-equal length (fewer
/// when n is small), on up to worker_threads() threads. The ranges depend on n and `chunks`
/// only. Each call to body touches its own chunk's data. If body throws, the lowest chunk's
/// exception is rethrown once every thread has finished.
void for_each_chunk(std::size_t n, std::size_t chunks, const std::function<void(std::size_t, std::size_t, std::size_t)>& body);

/// Appends each chunk's output to `out`, in chunk order.
template <class T>
void append_chunks(std::vector<T>& out, const std::vector<std::vector<T>>& chunks) {
  std::size_t total = out.size();
  for (const auto& c : chunks) total += c.size();
  out.reserve(total);
  for (const auto& c : chunks) out.insert(out.end(), c.begin(), c.end());
}

/// Chunks for a loop of n items, `per_chunk` to a chunk (the default suits a pair distance
/// each); one chunk below two chunks' worth, where starting a thread costs more than it saves.
std::size_t chunks_for(std::size_t n, std::size_t per_chunk = 2000);

}  // namespace valve
