#!/bin/bash
# Check that a change leaves every output of every built-in example byte
# for byte as it was: builds REV (default HEAD, i.e. the last commit) in
# a worktree, runs each example a few hundred steps with that build and
# with ./build/dembox (the working tree), and compares the folders.
#
# usage: scripts/same-outputs.sh [REV] [STEPS]
#
# Each example runs STEPS steps (default 600) on one thread; its first
# stage is cut to a third of them (stages.0.max_time) so that the second
# stage runs too, with a timeseries row every 5 steps and a snapshot every
# 100. Outputs compared: config.cfg, timeseries.csv, the snapshots,
# particles_final.csv, forces_final.csv, summary.json and the plots' data,
# scripts and pictures. Exit status 0 when all are identical.
set -eu
REV=${1:-HEAD}
STEPS=${2:-600}
cd "$(dirname "$0")/.."
ROOT=$(pwd)
WORK=$ROOT/build-same
SHA=$(git rev-parse --short "$REV")
BASE=$WORK/src-$SHA

if [ ! -x "$WORK/build-$SHA/dembox" ]; then
    rm -rf "$BASE"
    git worktree prune
    git worktree add --detach "$BASE" "$REV" > /dev/null
    cmake -S "$BASE" -B "$WORK/build-$SHA" -DCMAKE_BUILD_TYPE=Release \
        > /dev/null
    cmake --build "$WORK/build-$SHA" --target dembox -j 2 > /dev/null
    git worktree remove --force "$BASE"
fi
./scripts/setup.sh build > /dev/null

status=0
examples=$(./build/dembox examples | awk '{print $1}')
[ -n "$examples" ] || { echo "same-outputs.sh: no examples listed" >&2; exit 1; }
for ex in $examples; do
    # the step the example runs at: "auto" resolved by a run of one step
    # (a guess would cut its stages at the wrong times: biaxial2d's step
    # is 1.5e-7 s, and with 1e-5 its loading never began)
    rm -rf "$WORK/dt/$ex"
    ./build/dembox run "$ex" --max-steps 1 --threads 1 --quiet \
        -o "$WORK/dt/$ex" > /dev/null 2>&1 || true
    dt=$(sed -n 's/^time_step *= *\([0-9.eE+-]*\);.*/\1/p' \
        "$WORK/dt/$ex/config.cfg" 2> /dev/null || true)
    if [ -z "$dt" ]; then
        echo "$ex: no time step read from a run of one step ($WORK/dt/$ex)"
        status=1
        continue
    fi
    args=(--max-steps "$STEPS" --threads 1 --quiet
        --set "stages.0.max_time=$(awk -v d="$dt" -v n="$STEPS" 'BEGIN{print d*n/3}')"
        --set "output.interval=$(awk -v d="$dt" 'BEGIN{print 5*d}')"
        --set "output.snapshot_interval=$(awk -v d="$dt" 'BEGIN{print 100*d}')")
    for b in base new; do
        bin=./build/dembox
        [ $b = new ] || bin=$WORK/build-$SHA/dembox
        rm -rf "$WORK/out-$b/$ex"
        if ! "$bin" run "$ex" "${args[@]}" -o "$WORK/out-$b/$ex" > /dev/null 2>&1; then
            echo "$ex: the $b build failed (see $WORK/out-$b/$ex)"
            status=1
        fi
    done
    # gnuplot.log may name the folder, timing.txt has the times: compare
    # everything else
    if diff -r -x gnuplot.log -x timing.txt "$WORK/out-base/$ex" "$WORK/out-new/$ex" > /dev/null; then
        echo "$ex: identical ($(find "$WORK/out-new/$ex" -type f | wc -l) files)"
    else
        echo "$ex: DIFFERENT:"
        diff -r -q -x gnuplot.log -x timing.txt "$WORK/out-base/$ex" "$WORK/out-new/$ex" | sed 's/^/    /'
        status=1
    fi
done
exit $status
