#!/bin/sh
# `dembox run` ends with one line on where its time went
# (docs/outputs.md): the steps it took, the particles, ns per
# particle-step and the phases' shares, each in [0, 100] %. A run stopped
# and resumed reports each part's own steps, which add up to the whole;
# --quiet says nothing on the terminal. OUTDIR/timing.txt records each
# part's line.
set -eu
BIN=${DEMBOX_BIN:?run through ctest}
T=$(mktemp -d "${TMPDIR:-/tmp}/dembox-test-timing.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$T"
line() { grep "steps of .* particles in" "$1" || true; }
# the steps of a log's line, after checking it: one line, 500 particles,
# five shares (no MPI) each in [0, 100] % (prints "bad" otherwise)
check() {
    l=$(line "$1")
    n=$(printf '%s\n' "$l" | grep -c .)
    good=$(printf '%s\n' "$l" | grep -o '[0-9.]* %' |
        awk '$1 >= 0 && $1 <= 100 { k++ } END { print k + 0 }')
    if [ "$n" -eq 1 ] && [ "$good" -eq 5 ] &&
        printf '%s\n' "$l" | grep -q "of 500 particles"; then
        printf '%s\n' "$l" | sed 's/^dembox: \([0-9]*\) steps.*/\1/'
    else
        echo bad
    fi
}
DEMBOX_TRIALS_LOG=a.trials "$BIN" run biaxial2d --max-steps 3000 --threads 1 \
    -o a > /dev/null 2> a.log || fail "run: $(tail -3 a.log)"
[ "$(check a.log)" = 3000 ] || fail "a.log: $(line a.log)"
set +e
DEMBOX_STOP_AFTER_STEP=1500 "$BIN" run biaxial2d --max-steps 3000 --threads 1 \
    -o b > /dev/null 2> b.log
rc=$?
set -e
[ $rc -eq 130 ] || fail "stop: status $rc: $(tail -3 b.log)"
# a step that is not a whole number is refused before anything is written
# (atol read 1.5e3 as step 1)
set +e
DEMBOX_STOP_AFTER_STEP=1.5e3 "$BIN" run biaxial2d --max-steps 3000 \
    --threads 1 -o c > /dev/null 2> c.log
rc=$?
set -e
[ $rc -eq 1 ] && [ ! -e c ] && [ "$(wc -l < c.log)" -eq 1 ] &&
    grep -q DEMBOX_STOP_AFTER_STEP c.log ||
    fail "DEMBOX_STOP_AFTER_STEP=1.5e3: status $rc: $(cat c.log)"
"$BIN" run --resume b --threads 1 > /dev/null 2> b2.log ||
    fail "resume: $(tail -3 b2.log)"
s1=$(check b.log)
s2=$(check b2.log)
[ "$s1" != bad ] || fail "b.log: $(line b.log)"
[ "$s2" != bad ] || fail "b2.log: $(line b2.log)"
[ "$s1" -ge 1500 ] && [ $((s1 + s2)) -eq 3000 ] ||
    fail "stopped $s1 + resumed $s2 steps, not 3000"
# the line ends with the force pass's compilations: the trials each won,
# adding up to the trials run (then the changes of variant their second
# trials confirmed, if a trial proposed one), or the one forced by
# DEMBOX_PASS
tally=$(line a.log | sed -n 's/.*; force pass \(.*\)$/\1/p' |
    sed 's/ ([0-9]* of [0-9]* changes confirmed)$//')
[ -n "$tally" ] || fail "no force pass in: $(line a.log)"
case "$tally" in
*" trials")
    won=$(printf '%s\n' "$tally" | sed 's/ of [0-9]* trials$//' |
        tr ',' '\n' | awk '{ k += $2 } END { print k + 0 }')
    all=$(printf '%s\n' "$tally" | sed 's/.* of \([0-9]*\) trials$/\1/')
    [ "$won" -ge 1 ] && [ "$won" -eq "$all" ] ||
        fail "trials won ($won) do not add up to $all: $tally"
    # DEMBOX_TRIALS_LOG: a line per trial, the tally's and the first
    # trials that proposed a change; passes rising; a second trial just
    # after each proposal (of a variant not in use), and only then; the
    # variant after a trial the one in use before the next; a time > 0 us
    # for each variant in it
    proposed=$(line a.log |
        sed -n 's/.* of \([0-9]*\) changes confirmed)$/\1/p')
    awk -v want=$((all + ${proposed:-0})) '
        NF < 8 || NF % 2 || $2 <= p || (NR > 1 && $4 != after) ||
            ($3 == "second") != (NR > 1 && prop != "-") ||
            ($3 != "second" && $3 != "first") ||
            ($6 != "-" && $6 == $5) { bad = bad " " NR }
        { for (k = 7; k < NF; k += 2) if ($(k + 1) <= 0) bad = bad " " NR
          p = $2; after = $5; prop = $6 }
        END { if (NR != want || bad != "") {
            print NR " lines, " want " wanted; bad:" bad; exit 1 } }
    ' a.trials || fail "DEMBOX_TRIALS_LOG: $(cat a.trials)" ;;
*) [ "$(printf '%s\n' "$tally" | wc -w)" -eq 1 ] ||
    fail "force pass: $tally" ;;
esac
DEMBOX_PASS=gathers "$BIN" run biaxial2d --max-steps 300 --threads 1 -o f \
    > /dev/null 2> f.log || fail "forced pass: $(tail -3 f.log)"
line f.log | grep -q "; force pass gathers$" ||
    fail "DEMBOX_PASS=gathers: $(line f.log)"
# the variant with the threads' own blocks, forced where it has none (one
# thread), says that all its passes ran as the records pass (builds
# without the records compilations refuse the name)
if DEMBOX_PASS=blocks "$BIN" run biaxial2d --max-steps 300 --threads 1 -o g \
    > /dev/null 2> g.log; then
    want="; force pass blocks (as records in 301 of 301 passes)$"
    line g.log | grep -q "$want" ||
        fail "DEMBOX_PASS=blocks, one thread: $(line g.log)"
else
    grep -q "DEMBOX_PASS: 'blocks' is not a force pass of this build" g.log ||
        fail "DEMBOX_PASS=blocks: $(tail -3 g.log)"
fi
"$BIN" run biaxial2d --max-steps 50 --threads 1 --quiet -o c 2> c.log ||
    fail "quiet run failed"
[ -z "$(line c.log)" ] || fail "--quiet printed: $(line c.log)"
# a run cut short says so (here and in timing.txt, summary.json)
grep -q "warning: stopped by --max-steps after 50 steps, in stage 0 (isotropic)" \
    c.log || fail "cut short, not said: $(cat c.log)"
grep -q '"complete": false' c/summary.json ||
    fail "cut short, summary.json: $(head -5 c/summary.json)"
# OUTDIR/timing.txt keeps the same line for each part of a run, after
# when it ended, how, its steps, build, threads, CPU and vectors; a quiet run
# keeps it too, and a new run in the folder starts the record anew
# and the build that ran it
build=$("$BIN" --version | sed -n \
    's/^dembox \([^ ]*\) (\(source [0-9a-f]\{12\}, cc [^;]*\);.*/dembox \1, \2/p')
[ -n "$build" ] || fail "no source id in: $("$BIN" --version)"
rec() { # lines of $1/timing.txt that say "$3, steps $4, $build, 1 thread, "
         # and end with log $2's line
    awk -v h="Z $3, steps $4, $build, 1 thread, " \
        -v b=": $(line "$2" | sed 's/^dembox: //')" '
        index($0, h) && substr($0, length($0) - length(b) + 1) == b { k++ }
        END { print k + 0 }' "$1/timing.txt"
}
[ "$(wc -l < a/timing.txt)" -eq 1 ] &&
    [ "$(rec a a.log "stopped by --max-steps" "0 to 3000")" = 1 ] ||
    fail "a/timing.txt: $(cat a/timing.txt)"
[ "$(wc -l < b/timing.txt)" -eq 2 ] &&
    [ "$(rec b b.log interrupted "0 to $s1")" = 1 ] &&
    [ "$(rec b b2.log "stopped by --max-steps" "$s1 to 3000")" = 1 ] ||
    fail "b/timing.txt: $(cat b/timing.txt)"
grep -q "Z stopped by --max-steps, steps 0 to 50, $build, 1 thread, .*: 50 steps of 500 " \
    c/timing.txt || fail "quiet run: c/timing.txt: $(cat c/timing.txt)"
"$BIN" run biaxial2d --max-steps 20 --threads 1 --quiet -o a 2> /dev/null ||
    fail "second run in a"
grep -q "^[0-9T:-]*Z stopped by --max-steps, steps 0 to 20, " a/timing.txt &&
    [ "$(wc -l < a/timing.txt)" -eq 1 ] ||
    fail "a new run in a: a/timing.txt: $(cat a/timing.txt)"
echo "ok: 3000 steps; stopped $s1 + resumed $s2; force pass $tally"
