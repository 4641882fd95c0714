#!/bin/sh
# dembox under MPI (docs/parallel.md).
#
# Built with MPI: a sweep over 2 ranks, and over 4 ranks with 2 jobs each
# (oversubscribing this machine's cores), gives the same sweep.json and
# the same runs byte for byte as the local sweep; a second call under MPI
# skips what is finished and reruns a run whose summary is gone, again
# with the same result; `mpirun dembox analyze` and a bad --param are refused
# by rank 0 alone, with one line and a non-zero status, and so is a
# benchmark split into subdomains narrower than the ghost range.
# Built without MPI: a launch by mpirun (its environment) is refused with
# one line from rank 0, and nothing runs.
set -eu
BIN=${DEMBOX_BIN:?run through ctest}
T=$(mktemp -d "${TMPDIR:-/tmp}/dembox-test-mpi.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$T"

if "$BIN" --version | grep -q "without MPI"; then
    set +e
    OMPI_COMM_WORLD_RANK=0 OMPI_COMM_WORLD_SIZE=2 "$BIN" run biaxial2d \
        -o out > log 2> err0; rc0=$?
    OMPI_COMM_WORLD_RANK=1 OMPI_COMM_WORLD_SIZE=2 "$BIN" run biaxial2d \
        -o out > log 2> err1; rc1=$?
    set -e
    [ $rc0 -ne 0 ] && [ $rc1 -ne 0 ] || fail "status $rc0 $rc1"
    grep -q "built without MPI" err0 || fail "rank 0 said: $(cat err0)"
    [ "$(wc -l < err0)" -eq 1 ] || fail "rank 0 said more: $(cat err0)"
    [ ! -s err1 ] || fail "rank 1 spoke: $(cat err1)"
    [ ! -e out ] || fail "a refused launch wrote outputs"
    echo "without MPI: launch refused"
    exit 0
fi

MPIRUN=${MPIEXEC:-mpirun}
command -v "$MPIRUN" > /dev/null || { echo "no $MPIRUN: skipped"; exit 77; }
# as root (CI), in containers without a shared-memory single copy, and
# with more ranks than cores
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=1
# a machine whose MPI launcher cannot start two processes at all (no
# network interface, a container without /dev/shm) is not dembox's
# failure: skipped, with what mpirun said
if ! "$MPIRUN" -np 2 true > probe.log 2>&1; then
    echo "$MPIRUN -np 2 true failed here, skipped:"; head -5 probe.log
    exit 77
fi

S="sweep triaxial3d --param contact.mu=0.1,0.3,0.5 --param seed=1,2 --max-steps 1500 --quiet"
"$BIN" $S -o local || fail "local sweep"
"$MPIRUN" -np 2 "$BIN" $S -o np2 > log2 2>&1 || fail "2 ranks: $(tail -5 log2)"
"$MPIRUN" -np 4 "$BIN" $S --jobs 2 -o np4 > log4 2>&1 || fail "4 ranks: $(tail -5 log4)"
same() { # the sweep.json and every run's files but run.log and timing.txt
    cmp "local/sweep.json" "$1/sweep.json" || fail "$1: sweep.json differs"
    x="-x run.log -x timing.txt"
    # shellcheck disable=SC2086 # $x is split on purpose
    diff -r $x local/runs "$1/runs" > /dev/null ||
        fail "$1: runs differ: $(diff -rq $x local/runs "$1/runs" | head -3)"
}
same np2
same np4
# ranks > 0 say nothing of a sweep that went well
[ ! -s log2 ] || fail "2 ranks, --quiet: $(cat log2)"

# restart: finished runs are skipped, a run without summary runs again
rm "np2/runs/contact.mu=0.3_seed=2/summary.json"
"$MPIRUN" -np 2 "$BIN" ${S% --quiet} -o np2 > log2b 2>&1 || fail "restart: $(tail -5 log2b)"
grep -q "5 of 6 runs already finished" log2b || fail "restart: $(cat log2b)"
grep -q "1 made now" log2b || fail "restart ran more than one: $(cat log2b)"
same np2

# --collect over ranks: rank 0 alone writes the same sweep.json
rm np4/sweep.json
"$MPIRUN" -np 4 "$BIN" $S --collect -o np4 > logc 2>&1 || fail "--collect: $(tail -5 logc)"
cmp local/sweep.json np4/sweep.json || fail "--collect over 4 ranks: sweep.json differs"

# refused: a command that does not run over ranks, a bad --param (one
# line, from rank 0)
set +e
"$MPIRUN" -np 2 "$BIN" analyze np2/runs > logr 2>&1; rc=$?
set -e
[ $rc -ne 0 ] || fail "mpirun dembox analyze: status 0"
[ "$(grep -c "only \`dembox run\`, \`dembox sweep\` and \`dembox bench\` run over MPI ranks" logr)" -eq 1 ] ||
    fail "mpirun dembox analyze: $(cat logr)"
set +e
"$MPIRUN" -np 2 "$BIN" sweep biaxial2d --param bogus.key=1,2 -o bad > logb 2>&1; rc=$?
set -e
[ $rc -ne 0 ] || fail "bad --param: status 0"
[ "$(grep -c "bogus.key" logb)" -eq 1 ] || fail "bad --param: $(cat logb)"
[ ! -e bad/runs ] || fail "bad --param: runs started"
# a benchmark split over more ranks than its box has room for: one line
# from rank 0 naming the ghost range, status 1
set +e
"$MPIRUN" -np 16 --oversubscribe --mca mpi_yield_when_idle 1 "$BIN" bench \
    --dim 2 --n 20 --steps 2 --threads 1 --quiet --cache-dir cache \
    > logd 2>&1; rc=$?
set -e
[ $rc -ne 0 ] || fail "bench over 16 ranks: status 0"
[ "$(grep -c "narrower than the ghost range" logd)" -eq 1 ] ||
    fail "bench over 16 ranks: $(cat logd)"
echo "MPI sweeps: 2 and 4 ranks as local; restart; refusals"
