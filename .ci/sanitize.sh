#!/usr/bin/env bash
# Builds libvalve's unit tests and the pipeline's with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ (-O1, so the tests run in seconds) and runs them;
# any sanitizer report or failed assertion fails.
# With --stages it also builds every stage and runs the stage.* tests (a build of everything,
# about twice the unit tests' build, then about 90 s of tests).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -DVALVE_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
      -DCMAKE_C_FLAGS_DEBUG="-O1 -g1" >/dev/null
export OPENBLAS_NUM_THREADS=1
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
if [ "${1:-}" = "--stages" ]; then
  cmake --build build-asan -j"$(nproc)"
  cd build-asan
  # The stage.* tests: each stage's bad-input contract, --help, --xml and small samples. (The
  # imaging chain's tests stop in ITK 5.2's own neighborhood iterator, which offsets a null
  # pointer: itkConstNeighborhoodIterator.hxx:705.)
  ctest -j2 --output-on-failure -R "^stage\." -E "^stage\.render\." --timeout 900
  # valve-render goes through Mesa's OpenGL driver, which keeps 240 bytes it never frees in a
  # module it unloads at exit (LeakSanitizer cannot name it): memory errors only there.
  ASAN_OPTIONS=detect_leaks=0:halt_on_error=1 ctest -j2 --output-on-failure -R "^stage\.render\." --timeout 900
else
  cmake --build build-asan -j"$(nproc)" --target valve_unit_tests valve_pipeline_tests
  ./build-asan/tests/valve_unit_tests
  ./build-asan/tests/pipeline/valve_pipeline_tests
fi
