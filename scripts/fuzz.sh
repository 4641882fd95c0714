#!/bin/sh
# Build the libFuzzer harnesses (fuzz/*.c) with clang into build-fuzz and
# run each for SECONDS (default 600), all at once, on the committed seed
# corpus. New interesting inputs go to build-fuzz/corpus/NAME (the seeds in
# fuzz/corpus/NAME are only read); a crash, leak, hang or sanitizer report
# is saved as build-fuzz/artifacts/NAME-* and makes the script fail.
#
# fuzz_config explores without leak checks: libconfig 1.5 leaks on most
# syntax errors (tests/lsan.supp), which would make LeakSanitizer scan the
# heap after nearly every input and cut the speed by 7x. Instead, every
# input of its corpus (seeds and all it found) is run once more with leak
# checks at the end.
# Usage: scripts/fuzz.sh [SECONDS]
#   FUZZ_BUILD=DIR builds elsewhere; FUZZ_HARNESSES="fuzz_config" runs one.
set -eu
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-600}
B=${FUZZ_BUILD:-build-fuzz}
CC_FUZZ=${CC_FUZZ:-$(command -v clang-14 || command -v clang)}
HARNESSES=${FUZZ_HARNESSES:-fuzz_config fuzz_particles_csv fuzz_checkpoint
                           fuzz_lammps_data fuzz_run_folder
                           fuzz_sweep_collect}
# (the path quoted: the sanitizers' option parser splits at spaces)
export LSAN_OPTIONS="suppressions='$PWD/tests/lsan.supp':print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1"

CC=$CC_FUZZ cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DDEM_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
# shellcheck disable=SC2086
cmake --build "$B" -j "$(nproc)" --target $HARNESSES >/dev/null

mkdir -p "$B/artifacts"
for h in $HARNESSES; do
    name=${h#fuzz_}
    mkdir -p "$B/corpus/$name"
    leaks=1
    [ "$h" = fuzz_config ] && leaks=0
    # -timeout: one input running longer than 10 s counts as a hang. The
    # library's documented warnings (time step near t_c) are left out of
    # the log, which they would otherwise fill.
    (
        rc=0
        "$B/$h" -max_total_time="$SECONDS_EACH" -timeout=10 -max_len=16384 \
            -detect_leaks=$leaks -print_final_stats=1 \
            -artifact_prefix="$B/artifacts/$h-" \
            "$B/corpus/$name" "fuzz/corpus/$name" 2>&1 || rc=$?
        echo "$rc" >"$B/$h.rc"
    ) | { grep -av '^dembox: warning' || true; } >"$B/$h.log" &
done
wait

status=0
for h in $HARNESSES; do
    name=${h#fuzz_}
    rc=$(cat "$B/$h.rc")
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$B/$h.log" | tail -n 1)
    secs=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$B/$h.log" | tail -n 1)
    cov=$(grep -ao 'cov: [0-9]*' "$B/$h.log" | tail -n 1)
    echo "$h: ${runs:-?} executions in ${secs:-?} s, ${cov:-cov: ?}," \
         "$(ls "$B/corpus/$name" | wc -l) corpus inputs found, exit $rc"
    if [ "$rc" -eq 0 ] && [ "$h" = fuzz_config ]; then
        # the harness's status, not grep's (sh has no pipefail: through
        # the pipe a leak passed as exit 0)
        (
            lrc=0
            "$B/$h" -runs=0 -detect_leaks=1 "$B/corpus/$name" \
                "fuzz/corpus/$name" 2>&1 || lrc=$?
            echo "$lrc" >"$B/$h.leaks.rc"
        ) | grep -av '^dembox: warning' >"$B/$h.leaks.log" || true
        rc=$(cat "$B/$h.leaks.rc")
        n=$(($(ls "$B/corpus/$name" | wc -l) + $(ls "fuzz/corpus/$name" | wc -l)))
        echo "$h: leak check of $n corpus inputs, exit $rc"
        [ "$rc" -eq 0 ] || cat "$B/$h.leaks.log" >>"$B/$h.log"
    fi
    if [ "$rc" -ne 0 ]; then
        status=1
        echo "$h: FAILED; report ($B/$h.log):"
        grep -aE 'ERROR|SUMMARY|runtime error|Test unit written|deadly|leak' \
            "$B/$h.log" | head -n 20
    fi
done
exit $status
