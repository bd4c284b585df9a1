#!/bin/sh
# The README's main job: installs missing packages, builds, then
#  1. the synthetic world writes the paper's crossing scenario (s1-crossing, seed 7, point
#     features as in the paper) into a log, as fast as it can, byte-identical on every run;
#  2. slammtt-replay runs the estimator and the smoother (slammtt-smoother: sparse least squares
#     over every keyframe and static landmark) on that log deterministically; slammtt-timing and
#     slammtt-eval show where the time went and how good the result is (the smoothed trajectory
#     and map scored beside the filter's), with pictures;
#  3. the office scenario (rooms, walls, furniture, people on two legs, an RPLIDAR A2 with its
#     artefacts) through the whole pipeline: world scans -> segmenter (line, point and person
#     features) -> estimator, replayed deterministically, scored and drawn, with a picture of
#     one scan as perception sees it (out/office-seed1-pictures/scan.svg);
#  4. the live stack runs over LCM on the real robot's setting (rplidar-a2: 360-degree scans ->
#     slammtt-segmenter -> slammtt-estimator -> slammtt-smoother), recorded by lcm-logger,
#     evaluated and drawn.
#     It runs in a private network namespace (tests/support/netns-run), so it works on a
#     machine without a network and never disturbs a robot stack on the same host;
#  5. the office run's log (step 3) exported to an MCAP file in Foxglove's schemas
#     (out/office-seed1.mcap: open it in Foxglove), with the Python tools' venv.
# Everything lands in out/. The README's pictures (docs/images) come from steps 2 and 3, made
# by scripts/make-readme-pictures.sh.
set -eu
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
bin=build/bin
mkdir -p out

echo "== 1. world: s1-crossing, seed 7 -> out/s1-crossing-seed7.lcm"
"$bin/slammtt-world" --scenario s1-crossing --seed 7 --log out/s1-crossing-seed7.lcm

echo "== 2. deterministic replay (estimator and smoother), timing and evaluation"
"$bin/slammtt-replay" out/s1-crossing-seed7.lcm -o out/s1-crossing-seed7-replay.lcm \
  --config estimator/config/s1-crossing.yaml --smoother
"$bin/slammtt-timing" out/s1-crossing-seed7-replay.lcm.timing.lcm
"$bin/slammtt-eval" out/s1-crossing-seed7-replay.lcm --json out/s1-crossing-seed7-report.json \
  --plots out/s1-crossing-seed7-pictures

echo "== 3. office, seed 1: scans -> segmenter -> estimator (replay), evaluation and pictures"
"$bin/slammtt-world" --scenario office --seed 1 --log out/office-seed1.lcm
"$bin/slammtt-replay" out/office-seed1.lcm -o out/office-seed1-replay.lcm \
  --config estimator/config/office.yaml
"$bin/slammtt-timing" out/office-seed1-replay.lcm.timing.lcm
"$bin/slammtt-eval" out/office-seed1-replay.lcm --config estimator/config/office.yaml \
  --json out/office-seed1-report.json --plots out/office-seed1-pictures

echo "== 4. live stack over LCM: rplidar-a2, seed 7"
tests/support/netns-run scripts/run-pipeline.sh rplidar-a2 7 out/rplidar-a2-live 5

echo "== 5. the office run for Foxglove -> out/office-seed1.mcap"
scripts/python-env.sh build/venv
"$bin/slammtt-export" out/office-seed1-replay.lcm --config estimator/config/office.yaml \
  --mcap out/office-seed1.mcap
