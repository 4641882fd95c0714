#!/bin/sh
# Install the Debian packages dembox needs (when missing) and build it.
# Usage: scripts/setup.sh [BUILD_DIR [TARGET]]
#   TARGET: build only that (e.g. dembox: the program without the tests)
set -eu
cd "$(dirname "$0")/.."
BUILD=${1:-build}
TARGET=${2:-}
# (qemu-user: the tests run the build on an emulated older CPU, which it
# must refuse with one line, tests/test_machine.c; locales: a locale with a
# decimal comma made by localedef, under which the library must write the
# same files, tests/test_run.c)
PKGS="build-essential cmake pkg-config libconfig-dev libcairo2-dev libcmocka-dev libomp-dev gnuplot-nox clang libclang-rt-14-dev python3 python3-numpy libopenmpi-dev openmpi-bin qemu-user locales"
missing=""
for p in $PKGS; do
    # (installed, not only known: a package removed but not purged has a
    # dpkg status too)
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' ||
        missing="$missing $p"
done
if [ -n "$missing" ]; then
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO=sudo
    $SUDO apt-get update -qq
    # (env: sudo would drop the variable, and a debconf question would
    # wait unseen)
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $missing >/dev/null
fi
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DDEM_WERROR=ON >/dev/null
cmake --build "$BUILD" -j "$(nproc)" ${TARGET:+--target "$TARGET"}
