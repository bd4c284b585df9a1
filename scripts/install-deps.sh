#!/bin/sh
# Installs the Debian/Ubuntu packages slammtt needs, if any is missing. Runs apt-get as root or
# through sudo. Safe to run again: does nothing when everything is there.
#   scripts/install-deps.sh            the C++ build's packages, and Java's for the types' jar
#                                      and slammtt-lcm-spy (docs/tools.md)
#   scripts/install-deps.sh --python   python3 and its venv module, for scripts/python-env.sh
set -eu
PACKAGES="cmake ninja-build g++ pkg-config iproute2 util-linux
liblcm-dev liblcm-bin libglib2.0-dev libeigen3-dev libsuitesparse-dev libserialport-dev
libyaml-cpp-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev libssl-dev
default-jdk-headless liblcm-java libjchart2d-java default-jre xvfb xauth"
# Java: javac and jar build the message types' jar against liblcm-java's lcm.jar; lcm-spy's
# charts need jchart2d; its window needs AWT's X11 library, which only the full JRE has (the
# headless one cannot open a window); xvfb (and xauth for xvfb-run) gives it a display without a
# screen, as in its test.
if [ "${1:-}" = "--python" ]; then
  PACKAGES="python3 python3-venv"
fi

missing=""
for p in $PACKAGES; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0

echo "install-deps: installing:$missing" >&2
if [ "$(id -u)" = "0" ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1; then
  SUDO="sudo"
else
  echo "install-deps: error: missing packages ($missing) and neither root nor sudo" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
# shellcheck disable=SC2086
$SUDO apt-get install -y -q --no-install-recommends $missing
