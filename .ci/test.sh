#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, stage and pipeline tests).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
cd build
ctest -j2 --output-on-failure --timeout 900
