#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, stage and pipeline tests), then the unit
# and pipeline tests under the address and undefined-behaviour sanitizers (.ci/sanitize.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
cd build
# Two test processes share two cores: keep BLAS single-threaded so they do not oversubscribe.
export OPENBLAS_NUM_THREADS=1
ctest -j2 --output-on-failure --timeout 900
# libvalve's unit and pipeline tests again under AddressSanitizer and UndefinedBehaviorSanitizer: a second
# build of libvalve (about 7 minutes on 2 cores), run when the set-up, build and suite above
# left it room in CI's 30 minutes ($SECONDS counts from this script's start).
cd ..
if [ "$SECONDS" -lt 1080 ] || [ "${VALVE_SANITIZE_ALWAYS:-0}" = 1 ]; then
  bash .ci/sanitize.sh
else
  echo "sanitizer run skipped: the suite took ${SECONDS} s of the 30 minutes (run bash .ci/sanitize.sh)"
fi
