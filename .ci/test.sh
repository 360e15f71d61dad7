#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, stage and pipeline tests), then the unit
# tests under the address and undefined-behaviour sanitizers (.ci/sanitize.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
cd build
# Two test processes share two cores: keep BLAS single-threaded so they do not oversubscribe.
export OPENBLAS_NUM_THREADS=1
ctest -j2 --output-on-failure --timeout 900
# libvalve's unit tests again under AddressSanitizer and UndefinedBehaviorSanitizer.
cd ..
bash .ci/sanitize.sh
