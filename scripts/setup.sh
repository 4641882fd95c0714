#!/bin/sh
# Install the Debian packages dembox needs (when missing) and build it.
# Usage: scripts/setup.sh [BUILD_DIR]
set -eu
cd "$(dirname "$0")/.."
BUILD=${1:-build}
# (qemu-user: the tests run the build on an emulated older CPU, which it
# must refuse with one line, tests/test_machine.c; locales: a locale with a
# decimal comma made by localedef, under which the library must write the
# same files, tests/test_run.c)
PKGS="build-essential cmake pkg-config libconfig-dev libcairo2-dev libcmocka-dev libomp-dev gnuplot-nox clang libclang-rt-14-dev python3 python3-numpy libopenmpi-dev openmpi-bin qemu-user locales"
missing=""
for p in $PKGS; do
    dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO=sudo
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing >/dev/null
fi
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DDEM_WERROR=ON >/dev/null
cmake --build "$BUILD" -j "$(nproc)"
