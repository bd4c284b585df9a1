#!/bin/sh
# Runs scripts/compare-scans.py with the project's Python venv (scripts/python-env.sh: build/venv
# with the pinned rosbags, which reads ROS 1 and ROS 2 bags). Arguments are passed on.
set -eu
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/python-env.sh" >&2
exec "$root/build/venv/bin/python" "$root/scripts/compare-scans.py" "$@"
