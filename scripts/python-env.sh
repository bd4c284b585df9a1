#!/bin/sh
# Makes the venv of slammtt's Python tools (slammtt-import, the log reader, their tests):
#   scripts/python-env.sh [VENV]        (default: build/venv of the checkout)
# 1. python3 -m venv VENV (python3 and python3-venv from Debian if missing; $PYTHON chooses
#    another interpreter, 3.10 or newer);
# 2. the pinned PyPI versions of python/requirements.txt, then python/requirements-no-deps.txt
#    without their declared dependencies (again only when either file changed);
# 3. the Python LCM types, generated from lcmtypes/*.lcm by the lcm-gen of PyPI's lcm package
#    (Debian's lcm-gen 1.3.1 turns boolean arrays into a map iterator) into the venv's
#    site-packages as package slammtt_msgs, every time (never committed);
# 4. the slammtt package (python/), editable, with its programs slammtt-import, slammtt-export
#    and slammtt-foxglove in VENV/bin.
# Nothing else of the repository needs the venv; build/bin/slammtt-import, slammtt-export and
# slammtt-foxglove (written by CMake) run the venv's programs.
set -eu
venv=${1:-}
case "$venv" in
  "") ;;
  /*) ;;
  *) venv="$(pwd)/$venv" ;;   # relative to where it was called from
esac
cd "$(dirname "$0")/.."
root=$(pwd)
venv=${venv:-$root/build/venv}
python=${PYTHON:-python3}

new_python() {
  command -v "$python" >/dev/null 2>&1 &&
    "$python" -c 'import sys; sys.exit(sys.version_info < (3, 10))' >/dev/null 2>&1
}
if [ ! -x "$venv/bin/python" ]; then
  echo "python-env: creating $venv" >&2
  mkdir -p "$(dirname "$venv")"
  # Debian's python3 makes venvs only with python3-venv installed.
  if ! new_python || ! "$python" -m venv "$venv" >/dev/null 2>&1; then
    rm -rf "$venv"
    scripts/install-deps.sh --python
    python=python3
    if ! new_python; then
      echo "python-env: error: python3 3.10 or newer is needed" >&2
      exit 1
    fi
    "$python" -m venv "$venv"
  fi
fi
vpython="$venv/bin/python"

stamp="$venv/.slammtt-requirements"
if ! cat python/requirements.txt python/requirements-no-deps.txt | cmp -s - "$stamp"; then
  echo "python-env: installing python/requirements.txt into $venv" >&2
  "$vpython" -m pip install --quiet --disable-pip-version-check -r python/requirements.txt
  "$vpython" -m pip install --quiet --disable-pip-version-check --no-deps \
    -r python/requirements-no-deps.txt
  cat python/requirements.txt python/requirements-no-deps.txt > "$stamp"
fi

site=$("$vpython" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
generated="$venv/.slammtt-types"
rm -rf "$generated"
mkdir -p "$generated"
"$venv/bin/lcm-gen" --python --ppath "$generated" lcmtypes/*.lcm
rm -rf "$site/slammtt_msgs"
mv "$generated/slammtt_msgs" "$site/slammtt_msgs"
rm -rf "$generated"

if ! "$vpython" -c 'import slammtt.importer.cli' >/dev/null 2>&1 ||
   [ ! -x "$venv/bin/slammtt-import" ] || [ ! -x "$venv/bin/slammtt-export" ] ||
   [ ! -x "$venv/bin/slammtt-foxglove" ] ||
   [ "$("$vpython" -c 'import slammtt, os; print(os.path.dirname(slammtt.__file__))')" != \
     "$root/python/slammtt" ]; then
  echo "python-env: installing python/ (editable) into $venv" >&2
  "$vpython" -m pip install --quiet --disable-pip-version-check --no-deps \
    --no-build-isolation -e python/
fi
echo "python-env: $venv ready ($("$venv/bin/slammtt-import" --version))" >&2
