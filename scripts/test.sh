#!/bin/sh
# Set up (packages, build) and run every test.
set -eu
cd "$(dirname "$0")/.."
./scripts/setup.sh build
cd build && ctest --output-on-failure -j "$(nproc)"
