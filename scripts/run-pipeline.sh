#!/bin/sh
# run-pipeline.sh SCENARIO SEED OUTDIR [RATE_FACTOR]
#
# Runs the live stack on a scenario of the synthetic world, over LCM, exactly as the processes
# run on the robot (the world stands in for the base and the laser):
#
#   slammtt-world --LASER_SCAN--> slammtt-segmenter --FEATURES--> slammtt-estimator
#                 --ODOMETRY-------------------------------------> |
#                           slammtt-smoother <--SMOOTHER_INPUT------+
#
# (the smoother publishes SMOOTHED_POSE and SMOOTHED_MAP with the options of the configuration's
# `smoother:` section, its defaults without one) while lcm-logger records the bus; then
# slammtt-eval scores the recording against the world's GROUND_TRUTH (the smoothed trajectory
# and map beside the filter's) and draws it, and slammtt-timing shows where the time went. The
# world runs RATE_FACTOR times faster than real time (default 5). The stack configuration is the
# scenario's own (estimator/config/SCENARIO.yaml: the simulated sensor's mount and field of view).
#
# Outputs in OUTDIR: SCENARIO-seedSEED.lcm (the recording), report.json, plots/*.svg, timing.txt.
set -eu
if [ "$#" -lt 3 ]; then
  echo "usage: run-pipeline.sh SCENARIO SEED OUTDIR [RATE_FACTOR]" >&2
  exit 2
fi
scenario=$1
seed=$2
out=$3
rate=${4:-5}
cd "$(dirname "$0")/.."
bin=build/bin
config=estimator/config/$scenario.yaml
mkdir -p "$out"
log="$out/$scenario-seed$seed.lcm"
rm -f "$log"

pids=""
stop_all() {
  for pid in $pids; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in $pids; do wait "$pid" 2>/dev/null || true; done
  pids=""
}
trap stop_all EXIT
trap 'stop_all; exit 130' INT TERM

lcm-logger --force "$log" >"$out/lcm-logger.txt" 2>&1 &
pids="$pids $!"
"$bin/slammtt-segmenter" --config "$config" &
pids="$pids $!"
"$bin/slammtt-estimator" --config "$config" &
pids="$pids $!"
"$bin/slammtt-smoother" --config "$config" &
pids="$pids $!"
sleep 1  # let every process subscribe before the world starts talking

"$bin/slammtt-world" --scenario "$scenario" --seed "$seed" --output scans \
  --rate-factor "$rate"
sleep 1  # let the last scan travel through segmenter, estimator and smoother into the log
stop_all

"$bin/slammtt-timing" "$log" | tee "$out/timing.txt"
"$bin/slammtt-eval" "$log" --json "$out/report.json" --plots "$out/plots"
echo "recording: $log"
echo "report:    $out/report.json"
echo "pictures:  $out/plots/"
