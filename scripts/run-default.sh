#!/bin/sh
# Set up (packages, build) and run the default example (2D biaxial test);
# arguments go to `dembox run`, relative paths from the folder this was
# called in.
set -eu
HERE=$(pwd)
cd "$(dirname "$0")/.."
ROOT=$(pwd)
./scripts/setup.sh build dembox # (the program alone: the tests take minutes)
cd "$HERE"
exec "$ROOT/build/dembox" run "$@"
