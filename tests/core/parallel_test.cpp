// Split loops (core/parallel.hpp): every index once, in chunks fixed by the range alone.
#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "valve/core/parallel.hpp"

using namespace valve;

TEST_CASE("for_each_chunk visits every index once, in chunks that tile the range in order", "[core][parallel]") {
  for (const std::size_t n : {0, 1, 7, 1000, 100003}) {
    for (const std::size_t chunks : {1, 3, 64}) {
      std::vector<std::atomic<int>> visits(n);
      std::vector<std::pair<std::size_t, std::size_t>> ranges(chunks, {0, 0});
      std::atomic<std::size_t> calls{0};
      for_each_chunk(n, chunks, [&](std::size_t c, std::size_t begin, std::size_t end) {
        ranges[c] = {begin, end};
        ++calls;
        for (std::size_t k = begin; k < end; ++k) ++visits[k];
      });
      INFO("n " << n << ", chunks " << chunks);
      int wrong = 0;
      for (auto& v : visits) wrong += v != 1;
      CHECK(wrong == 0);
      // min(chunks, n) ranges (one empty one for n = 0), each starting where the last ended,
      // of lengths n / chunks rounded either way: fixed by n and chunks, not by the threads.
      const std::size_t used = std::max<std::size_t>(1, std::min(chunks, n));
      CHECK(calls == used);
      std::size_t next = 0;
      for (std::size_t c = 0; c < used; ++c) {
        CHECK(ranges[c].first == next);
        CHECK(ranges[c].first == n * c / used);
        next = ranges[c].second;
      }
      CHECK(next == n);
    }
  }
}

TEST_CASE("chunks_for keeps short loops in one chunk and cuts long ones by their length", "[core][parallel]") {
  CHECK(chunks_for(0) == 1);
  CHECK(chunks_for(3999) == 1);        // below two chunks of 2,000
  CHECK(chunks_for(4000) == 2);
  CHECK(chunks_for(30000) == 15);      // the sample mitral closure's candidate pairs
  CHECK(chunks_for(10000000) == 64);   // at most 64
  CHECK(chunks_for(63, 32) == 1);
  CHECK(chunks_for(1000, 32) == 31);
  CHECK(worker_threads() >= 1);
}

TEST_CASE("for_each_chunk rethrows the lowest chunk's error once every chunk has run", "[core][parallel]") {
  std::atomic<int> ran{0};
  try {
    for_each_chunk(64, 8, [&](std::size_t c, std::size_t, std::size_t) {
      ++ran;
      if (c == 5 || c == 2) throw std::runtime_error("chunk " + std::to_string(c));
    });
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) == "chunk 2");
  }
  CHECK(ran == 8);
}
