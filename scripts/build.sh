#!/bin/sh
# Configures and builds slammtt into build/ (Release; every program in build/bin).
# Extra arguments go to CMake's configure step, e.g. scripts/build.sh -DSLAMMTT_WERROR=ON
set -eu
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build --parallel "$(nproc)"
