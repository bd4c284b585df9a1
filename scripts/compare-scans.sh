#!/usr/bin/env bash
# Runs scripts/compare-scans.py in a venv of its own (build/venv-compare-scans) with the pinned
# rosbags version, which reads ROS 1 and ROS 2 bags. Arguments are passed on.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="$root/build/venv-compare-scans"
if [[ ! -x "$venv/bin/python" ]]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet rosbags==0.11.9
fi
exec "$venv/bin/python" "$root/scripts/compare-scans.py" "$@"
