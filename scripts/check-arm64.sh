#!/bin/sh
# dembox on 64-bit Arm, checked on an x86-64 Debian machine: installs the
# cross compiler and the arm64 libraries (multiarch), cross-builds into
# build-arm64 (cmake/aarch64-linux-gnu.cmake), and runs biaxial2d and
# triaxial3d 400 steps under qemu-aarch64 with each force pass (gathers,
# records, ring). Every run must write the same timeseries.csv,
# particles_final.csv and forces_final.csv as the others and as
# ./build/dembox on this machine, byte for byte. One thread only: threads
# under Debian 12's qemu-aarch64 hang before they start (a bare
# pthread_create does). Exit status 0 when all are identical.
#
# usage: scripts/check-arm64.sh   (root or sudo for the packages; about
# 6 minutes on 2 cores, most of it the build)
set -eu
cd "$(dirname "$0")/.."
ROOT=$(pwd)
[ -x build/dembox ] || { echo "check-arm64: build ./build first" >&2; exit 2; }
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
PKGS="gcc-aarch64-linux-gnu qemu-user libconfig-dev:arm64 libcairo2-dev:arm64"
missing=""
for p in $PKGS; do
    # installed, not merely known (a removed package keeps its status)
    dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed" ||
        missing="$missing $p"
done
if [ -n "$missing" ]; then
    $SUDO dpkg --add-architecture arm64
    $SUDO apt-get update -qq
    # (through env: sudo drops a variable set before it)
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $missing \
        > /dev/null
fi
cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
    -DCMAKE_BUILD_TYPE=Release -DDEM_NATIVE=OFF -DDEM_WERROR=ON > /dev/null
cmake --build build-arm64 -j "$(nproc)" --target dembox > /dev/null
T=$(mktemp -d "${TMPDIR:-/tmp}/dembox-arm64.XXXXXX")
trap 'rm -rf "$T"' EXIT
cd "$T"
bad=0
for cfg in biaxial2d triaxial3d; do
    "$ROOT/build/dembox" run "$cfg" -o "$cfg-x86" --threads 1 --quiet \
        --max-steps 400 > /dev/null
    for p in gathers records ring; do
        DEMBOX_PASS=$p qemu-aarch64 -L /usr/aarch64-linux-gnu \
            "$ROOT/build-arm64/dembox" run "$cfg" -o "$cfg-$p" --threads 1 \
            --quiet --max-steps 400 > /dev/null
        for f in timeseries.csv particles_final.csv forces_final.csv; do
            if cmp -s "$cfg-x86/$f" "$cfg-$p/$f"; then
                echo "$cfg, arm64 $p: $f identical"
            else
                echo "$cfg, arm64 $p: $f DIFFERS" && bad=1
            fi
        done
    done
done
exit $bad
