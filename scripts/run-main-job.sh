#!/bin/sh
# The README's main job: installs missing packages, builds, and runs the stack on a shipped
# scenario. For now: the synthetic world writes a log of s1-crossing (seed 7) into out/.
set -eu
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
build/bin/slammtt-world --scenario s1-crossing --seed 7 --log out/s1-crossing-seed7.lcm
echo "main job: log written to out/s1-crossing-seed7.lcm"
