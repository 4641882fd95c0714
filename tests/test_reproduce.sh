#!/bin/sh
# scripts/reproduce.sh, checked without the long runs: --list adds up the
# parts and their wall time, bad input is refused with a message and
# status 2, two parts run in --smoke mode (300 steps per run) and give
# their sweep.json, the numbers are copied, a second call skips the
# finished runs, `dembox sweep --collect` analyses them again without
# running anything, and a folder of another mode is refused.
set -eu
SRC=${DEMBOX_SOURCE_DIR:?run through ctest}
BIN=${DEMBOX_BIN:?run through ctest}
T=$(mktemp -d "${TMPDIR:-/tmp}/dembox-test-reproduce.XXXXXX")
trap 'rm -rf "$T"' EXIT
R="$SRC/scripts/reproduce.sh"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$R" --paper --list --jobs 2 > "$T/list" || fail "--list"
grep -q "^cyclic-mu " "$T/list" || fail "--paper --list lacks cyclic-mu"
grep -q "CPU minutes in all" "$T/list" || fail "--list gives no total"
# the wall time: a part's runs go min(runs, jobs) at once, each with its
# own threads (cyclic-t10: 65 CPU minutes in one run of one thread;
# cyclic-t10-full: 200 in one run of two threads)
# (the script's status checked, then its output: through a pipe into
# grep its own failure passed unseen)
"$R" --paper --list --jobs 2 --only cyclic-t10 > "$T/l1" || fail "--list --only"
grep -q "65 minutes with 2 jobs" "$T/l1" ||
    fail "--list: one run does not go faster with more jobs"
"$R" --paper --list --jobs 1 --only cyclic-t10-full > "$T/l2" || fail "--list --only"
grep -q "100 minutes with 1 jobs" "$T/l2" ||
    fail "--list: a part's --threads are not counted"

set +e
"$R" --only bogus "$T/x" 2> "$T/err"; rc=$?
set -e
[ $rc -eq 2 ] || fail "--only bogus: status $rc"
grep -q "no part 'bogus'" "$T/err" || fail "--only bogus: $(cat "$T/err")"

out="$T/quick"
DEMBOX=$BIN "$R" --quick --smoke --jobs 2 --only pressure,cyclic \
    --numbers "$T/numbers" "$out" > "$T/log" 2>&1 || fail "smoke run: $(tail -5 "$T/log")"
for p in pressure cyclic; do
    [ -s "$out/$p/sweep.json" ] || fail "no $p/sweep.json"
    [ -s "$T/numbers/$p/sweep.json" ] || fail "--numbers did not copy $p"
done
ls "$T/numbers/pressure/runs"/*/summary.json > /dev/null || fail "no summaries copied"
DEMBOX=$BIN "$R" --quick --smoke --jobs 2 --only pressure,cyclic "$out" \
    > "$T/log2" 2>&1 || fail "second call: $(tail -5 "$T/log2")"
grep -q "skipped\|already finished" "$T/log2" || fail "second call did not skip: $(cat "$T/log2")"

# dembox sweep --collect, with the sweep's own arguments, analyses what is
# there and runs nothing; without its --set, no run is the sweep's
rm "$out/pressure/sweep.json"
"$BIN" sweep biaxial2d --param stages.0.pressure,stages.1.pressure=250,500,1000 \
    --set output.checkpoint_interval=120 \
    -o "$out/pressure" --collect > "$T/log3" 2>&1 || fail "--collect: $(cat "$T/log3")"
[ -s "$out/pressure/sweep.json" ] || fail "--collect wrote no sweep.json"
grep -q '"runs_finished": 3' "$out/pressure/sweep.json" || fail "--collect: runs not read"
grep -q "started" "$T/log3" && fail "--collect ran something: $(cat "$T/log3")"
"$BIN" sweep biaxial2d --param stages.0.pressure,stages.1.pressure=250,500,1000 \
    -o "$out/pressure" --collect > "$T/log4" 2>&1 || fail "--collect: $(cat "$T/log4")"
grep -q '"runs_finished": 0' "$out/pressure/sweep.json" ||
    fail "--collect without the sweep's --set read its runs"
grep -q "is not this point's config" "$out/pressure/sweep.json" ||
    fail "--collect without the sweep's --set: no reason"

set +e
DEMBOX=$BIN "$R" --paper --only cyclic-mu "$out" 2> "$T/err"; rc=$?
set -e
[ $rc -eq 2 ] || fail "another mode in the same folder: status $rc"
grep -q "made by another command" "$T/err" || fail "$(cat "$T/err")"
echo "test_reproduce: ok"
