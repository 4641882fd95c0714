#!/bin/sh
# Set up (packages, build) and run the default example (2D biaxial test).
set -eu
cd "$(dirname "$0")/.."
./scripts/setup.sh build
exec ./build/dembox run "$@"
