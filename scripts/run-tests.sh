#!/bin/sh
# The README's test command: installs missing packages, builds with warnings as errors and runs
# every test (labels unit, integration, target; fuzz and soak in their short version). The long
# soak and fuzz runs are opt-in:
#   SLAMMTT_LONG_TESTS=1 scripts/run-tests.sh
set -eu
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh -DSLAMMTT_WERROR=ON
cd build
if [ "${SLAMMTT_LONG_TESTS:-0}" = "1" ]; then
  export SLAMMTT_LONG_TESTS=1
fi
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
