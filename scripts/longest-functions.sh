#!/bin/sh
# longest-functions.sh [N] [FOLDER...]
#
# The N longest C++ functions (default 10) of the given folders (default: every source folder
# of the project), longest first: lines from the signature to the closing brace, lines of code
# without comments and blank lines (NLOC), file:line and name. Measured by lizard
# (https://github.com/terryyin/lizard), installed at a pinned version into a venv of its own
# (build/venv-lizard, created on first use; needs python3 with venv and access to PyPI).
set -eu
cd "$(dirname "$0")/.."
count=${1:-10}
[ "$#" -gt 0 ] && shift
if [ "$#" -eq 0 ]; then
  # Every top-level folder with C++ sources that git tracks, so that no folder is left out;
  # outside a git checkout, a fixed list.
  folders=$(git ls-files '*.cc' '*.h' '*.cpp' '*.hpp' 2>/dev/null | sed -n 's|/.*||p' | sort -u)
  if [ -z "$folders" ]; then
    folders="cmake common drivers estimator perception runtime smoother tools tests"
  fi
  # shellcheck disable=SC2086
  set -- $folders
fi
venv=build/venv-lizard
if [ ! -x "$venv/bin/lizard" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet lizard==1.24.3
fi
"$venv/bin/lizard" --languages cpp --csv "$@" | python3 -c '
import csv, sys
count = int(sys.argv[1])
# lizard --csv: NLOC, CCN, tokens, parameters, length, location, file, name, long name, start, end
rows = sorted(csv.reader(sys.stdin), key=lambda r: (-int(r[4]), r[6], int(r[9])))
print("| lines | NLOC | where | function |")
print("|---|---|---|---|")
for r in rows[:count]:
    print(f"| {r[4]} | {r[0]} | {r[6]}:{r[9]} | `{r[7]}` |")
' "$count"
