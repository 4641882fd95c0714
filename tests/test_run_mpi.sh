#!/bin/sh
# `mpirun dembox run`: a run split over 2 and 4 ranks (4 oversubscribe two
# cores) by domain decomposition (docs/parallel.md) gives the serial
# run's outputs to round-off: the same files, every timeseries column and
# every final particle within 1e-8 of the column's scale over 3000 steps
# (biaxial2d, 500 discs, walls servo-controlled). A split run stopped at
# step 1500 leaves a checkpoint that resumes at 4 ranks and without MPI,
# each to the same outputs. A box that shrinks until its ranks have no
# room stops with a checkpoint that resumes on fewer ranks. Too many
# ranks for the box: one line from rank 0, status 1, no outputs. A
# warning of the config is said once.
# Status 77 (skipped): no mpirun, or it cannot start two ranks here.
set -eu
BIN=${DEMBOX_BIN:?run through ctest}
. "$(dirname "$0")/mpi_env.sh"
T=$(mktemp -d "${TMPDIR:-/tmp}/dembox-test-run-mpi.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$T"
mpi() { np=$1; shift; "$MPIRUN" -np "$np" $(mpi_opts "$np") "$BIN" "$@"; }

R="biaxial2d --max-steps 3000 --threads 1 --quiet --set output.snapshot_interval=0.001"
"$BIN" run $R -o serial > log 2>&1 || fail "serial: $(tail -3 log)"
mpi 2 run $R -o np2 > log2 2>&1 || fail "2 ranks: $(tail -3 log2)"
mpi 4 run $R -o np4 > log4 2>&1 || fail "4 ranks: $(tail -3 log4)"
# (--quiet: but that the run is cut short)
[ -z "$(grep -v 'cut short' log2)" ] || fail "2 ranks, --quiet, said: $(cat log2)"
# a warning of the config (every rank reads it) is said once, by rank 0
mpi 2 run biaxial2d --max-steps 10 --threads 1 --quiet \
    --set time_step=1.0e-6 -o warned > logw 2>&1 || fail "warned: $(tail -3 logw)"
[ "$(grep -c 'warning: .*t_c/10' logw)" -eq 1 ] &&
    [ "$(grep -vc 'cut short' logw)" -eq 1 ] ||
    fail "2 ranks, one warning, said: $(cat logw)"

# a file against the serial run's: the same rows and columns, every value
# within tol of the largest magnitude in its column (NaN only where NaN)
close() {
    awk -F, -v tol=1e-8 -v what="$2" '
        NR == FNR { if (FNR > 1) for (k = 1; k <= NF; k++) {
                        a[FNR, k] = $k; v = $k < 0 ? -$k : $k
                        if (v > m[k]) m[k] = v }
                    n = FNR; nf = NF; next }
        FNR == 1 { next }
        { if (NF != nf) { print what ": " NF " columns"; bad = 1; exit }
          for (k = 1; k <= NF; k++) {
              if (($k "") == (a[FNR, k] "")) continue
              d = $k - a[FNR, k]; d = d < 0 ? -d : d
              if (d > tol * m[k] || ($k "" ~ /nan/) != (a[FNR, k] "" ~ /nan/)) {
                  print what ": row " FNR " column " k ": " $k " against " a[FNR, k]
                  bad = 1; exit } } }
        END { if (!bad && FNR != n) { print what ": " FNR " rows, " n " serial"; bad = 1 }
              exit bad }' "${4:-serial}/$1" "$3/$1"
}
same() {
    (cd serial && ls | grep -v '^plots$' | sort) > files.serial
    (cd "$1" && ls | grep -v '^plots$' | sort) > "files.$1"
    cmp -s files.serial "files.$1" || fail "$1: other files: $(diff files.serial "files.$1" | head -5)"
    for f in timeseries.csv particles_final.csv forces_final.csv; do
        close "$f" "$1/$f" "$1" || fail "$1/$f differs"
    done
    [ "$(wc -l < "$1/contacts_final.csv")" -eq "$(wc -l < serial/contacts_final.csv)" ] ||
        fail "$1: other number of contacts"
}
same np2
same np4

# stopped at step 1500 over 2 ranks, resumed over 4 and without MPI
set +e
DEMBOX_STOP_AFTER_STEP=1500 mpi 2 run $R -o cut > logc 2>&1; rc=$?
set -e
[ $rc -eq 130 ] || fail "stop: status $rc: $(cat logc)"
[ -f cut/checkpoint.bin ] && [ -f cut/timeseries.csv.part ] && [ ! -e cut/timeseries.csv ] ||
    fail "stop: no checkpoint, or a complete-looking timeseries"
cp -r cut cut1
mpi 4 run --resume cut --threads 1 --quiet > logr 2>&1 || fail "resume over 4 ranks: $(cat logr)"
same cut
"$BIN" run --resume cut1 --threads 1 --quiet > logr1 2>&1 || fail "resume without MPI: $(cat logr1)"
same cut1

# more ranks than cores, one thread each: the ranks of a split run wait on
# each other in MPI and spin; warned of once (it was not, at one thread:
# a review of MPI, session 115), but not with mpi_yield_when_idle
cores=$(getconf _NPROCESSORS_ONLN)
over=$((cores + 1))
"$MPIRUN" -np $over --oversubscribe "$BIN" run biaxial2d --max-steps 10 \
    --threads 1 --quiet -o over > logo 2>&1 || fail "$over ranks: $(cat logo)"
[ "$(grep -c "warning: $over ranks on $cores cores: ranks waiting in MPI spin" logo)" -eq 1 ] ||
    fail "$over ranks: $(cat logo)"
"$MPIRUN" -np $over --oversubscribe --mca mpi_yield_when_idle 1 "$BIN" run \
    biaxial2d --max-steps 10 --threads 1 --quiet -o overy > logy 2>&1 ||
    fail "$over ranks, yielding: $(cat logy)"
! grep -q "ranks waiting in MPI" logy || fail "$over ranks, yielding: $(cat logy)"

# SIGTERM to mpirun between samples far apart (here 0.05 s of simulated
# time, many seconds of steps): Open MPI passes the signal on and kills
# the ranks a second or two later, so the ranks must stop and checkpoint
# between samples (they waited for the next sample, and lost everything
# since the last checkpoint: a review of MPI, session 115)
"$MPIRUN" -np 2 $(mpi_opts 2) "$BIN" run biaxial2d --threads 1 --quiet \
    --set output.interval=0.05 --set output.checkpoint_interval=0 \
    -o termed > logt 2>&1 &
pid=$!
k=0
while [ ! -e termed/timeseries.csv.part ] && [ $k -lt 600 ]; do
    sleep 0.1; k=$((k + 1))
done
sleep 1
kill -TERM $pid
set +e
wait $pid; rc=$?
set -e
[ $rc -ne 0 ] && [ -f termed/checkpoint.bin ] && [ ! -e termed/timeseries.csv ] ||
    fail "SIGTERM between samples: status $rc, $(ls termed): $(cat logt)"
grep -q "resume with: dembox run --resume termed" logt ||
    fail "SIGTERM between samples: $(cat logt)"

# a box that shrinks until its 8 ranks have no grid of subdomains wider
# than the ghost range: one line and a checkpoint before the rebuild that
# would fail, and the checkpoint resumed on 2 ranks gives the serial run
K="biaxial2d --set particles.count=24 --max-steps 30000 --threads 1 --quiet"
"$BIN" run $K -o kserial > logks 2>&1 || fail "24 serial: $(tail -3 logks)"
set +e
mpi 8 run $K -o cramped > logk 2>&1; rc=$?
set -e
[ $rc -ne 0 ] && [ "$(grep -c '^dembox: ' logk)" -eq 1 ] &&
    grep -q "ranks can no longer cut it into subdomains" logk ||
    fail "cramped: status $rc: $(cat logk)"
[ -f cramped/checkpoint.bin ] && [ ! -e cramped/timeseries.csv ] ||
    fail "cramped: no checkpoint, or a complete-looking timeseries"
mpi 2 run --resume cramped --threads 1 --quiet > logkr 2>&1 ||
    fail "cramped, resumed over 2 ranks: $(cat logkr)"
for f in timeseries.csv particles_final.csv; do
    close "$f" "cramped/$f" cramped kserial || fail "cramped/$f differs"
done

# too many ranks for the box: refused before any output
set +e
mpi 16 run biaxial2d --set particles.count=8 --max-steps 10 --quiet -o many > logm 2>&1; rc=$?
set -e
[ $rc -ne 0 ] || fail "16 ranks: status 0"
[ "$(grep -c "narrower than the ghost range" logm)" -eq 1 ] || fail "16 ranks: $(cat logm)"
[ ! -e many ] || fail "16 ranks: outputs written: $(ls many)"
# a rank that fails on its own before the split (a config, particle file
# or packing only some nodes see; here each rank given its own command)
# stops every rank with one line from rank 0, instead of leaving the
# others waiting in the split's first collective for ever
lone() {
    name=$1
    set +e
    # shellcheck disable=SC2086 # (the two commands' words)
    timeout 120 "$MPIRUN" --oversubscribe -np 1 "$BIN" $2 : \
        -np 1 "$BIN" $3 > "log.$name" 2>&1; rc=$?
    set -e
    [ $rc -ne 0 ] && [ $rc -ne 124 ] || fail "$name: status $rc: $(cat "log.$name")"
    [ "$(grep -c '^dembox: ' "log.$name")" -eq 1 ] &&
        grep -q "another MPI rank could not" "log.$name" ||
        fail "$name: $(cat "log.$name")"
}
printf 'x,y,radius\n0.01,0.01,0.004\n0.03,0.01,0.004\n' > p.csv
F="run biaxial2d --max-steps 10 --quiet -o lone1 --set particles.placement=file --set box.size=[0.04,0.04,0.0]"
lone particle-file "$F --set particles.file=p.csv" "$F --set particles.file=nosuch.csv"
[ ! -e lone1/timeseries.csv ] || fail "particle file: outputs written"
C="run biaxial2d --max-steps 10 --quiet -o lone2"
lone config "$C" "$C --set nosuch.key=1"
[ ! -e lone2 ] || fail "config: outputs written"
B="bench --steps 20 --threads 1 --quiet --cache-dir $T/cache"
lone bench "$B --n 300" "$B --n 300 --data nosuch.data"
lone bench-header "$B --n 300" "$B --data nosuch.data"
echo "split runs over 2 and 4 ranks as serial; stop and resume across rank counts; a cramped box checkpointed; refusals"
