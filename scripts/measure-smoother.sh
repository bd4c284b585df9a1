#!/bin/sh
# The smoother beside the filter on a shipped scenario, seed by seed (docs/smoother.md, "In the
# stack"): slammtt-world -> slammtt-replay with a `smoother:` section -> slammtt-eval and
# slammtt-timing; one line per seed: filter ATE, smoothed ATE (the live SMOOTHED_POSE), filter
# and smoothed landmark RMSE (m), the smoother's per-scan time p50 / p99 (us), and the ATE of the
# final smoothed trajectory (the last SMOOTHED_TRAJECTORY: every keyframe as estimated at the end).
# Usage: scripts/measure-smoother.sh OUTDIR [SCENARIO [FIRST_SEED [LAST_SEED [SMOOTHER_YAML]]]]
#   SMOOTHER_YAML: lines of the `smoother:` section (default: none, the defaults).
set -eu
out=$1
scenario=${2:-s1-crossing}
first=${3:-1}
last=${4:-10}
extra=${5:-}
bin=$(cd "$(dirname "$0")/.." && pwd)/build/bin
config_in=$(cd "$(dirname "$0")/.." && pwd)/estimator/config/$scenario.yaml
mkdir -p "$out"
config=$out/$scenario-smoother.yaml
cp "$config_in" "$config"
if [ -n "$extra" ]; then
  printf 'smoother:\n%s\n' "$extra" >> "$config"
else
  echo 'smoother: {}' >> "$config"
fi
echo "seed filter_ate_m smoothed_ate_m filter_landmark_rmse_m smoothed_landmark_rmse_m" \
  "smoother_p50_us smoother_p99_us final_smoothed_ate_m"
seed=$first
while [ "$seed" -le "$last" ]; do
  w=$out/$scenario-seed$seed.lcm
  r=$out/$scenario-seed$seed-replay.lcm
  j=$out/$scenario-seed$seed.json
  "$bin/slammtt-world" --scenario "$scenario" --seed "$seed" --log "$w" >/dev/null 2>&1
  "$bin/slammtt-replay" "$w" -o "$r" --config "$config" >/dev/null 2>&1
  "$bin/slammtt-eval" "$r" --config "$config" --json "$j" >/dev/null 2>&1 || true
  timing=$("$bin/slammtt-timing" "$r.timing.lcm" | awk '$1 == "smoother" {print $3, $5}')
  python3 - "$j" "$seed" "$timing" <<'PY'
import json
import sys
report = json.load(open(sys.argv[1]))
def figure(key):
    return "null" if report[key] is None else "%.3f" % report[key]
print(sys.argv[2], figure("ate_rmse_m"), figure("smoothed_ate_rmse_m"),
      figure("landmark_rmse_m"), figure("smoothed_landmark_rmse_m"), sys.argv[3],
      figure("final_smoothed_ate_rmse_m"))
PY
  seed=$((seed + 1))
done
