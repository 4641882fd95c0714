#!/bin/sh
# Set up (packages, build) and run every test:
#   1. Release build in build/ (warnings are errors), ctest;
#   2. AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/,
#      the same ctest there (skip with DEM_TEST_ASAN=0);
#   3. the libFuzzer harnesses for FUZZ_SECONDS each (default 20) on the
#      committed corpus (skip with FUZZ_SECONDS=0).
# This is what CI (.ci/run) runs.
set -eu
cd "$(dirname "$0")/.."
FUZZ_SECONDS=${FUZZ_SECONDS:-20}
case $FUZZ_SECONDS in
'' | *[!0-9]*)
    echo "test.sh: FUZZ_SECONDS=$FUZZ_SECONDS is not a whole number" >&2
    exit 1
    ;;
esac
J=$(nproc)
t0=$(date +%s)

./scripts/setup.sh build
(cd build && ctest --output-on-failure -j "$J")
t1=$(date +%s)
echo "test.sh: release build and tests: $((t1 - t0)) s"

if [ "${DEM_TEST_ASAN:-1}" != 0 ]; then
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DDEM_SANITIZE=ON -DDEM_WERROR=ON >/dev/null
    cmake --build build-asan -j "$J"
    # Any sanitizer report fails the test that triggered it (the tests set
    # LSAN_OPTIONS to tests/lsan.supp themselves).
    (cd build-asan && UBSAN_OPTIONS=print_stacktrace=1 \
        ctest --output-on-failure -j "$J")
    t2=$(date +%s)
    echo "test.sh: sanitizer build and tests: $((t2 - t1)) s"
    t1=$t2
fi

if [ "$FUZZ_SECONDS" -gt 0 ]; then
    ./scripts/fuzz.sh "$FUZZ_SECONDS"
    t2=$(date +%s)
    echo "test.sh: fuzzing: $((t2 - t1)) s"
fi
echo "test.sh: all tests passed in $(($(date +%s) - t0)) s"
