#!/bin/bash
# The per-CPU speed figures of docs/performance.md ("The latest figures per
# CPU") in one command: rounds of dembox against LAMMPS gran/hooke/history
# on the same packings, then a Markdown row with the median and range of
# each figure over the rounds.
#
# usage: bench/speed-round.sh [--rounds R] [--data DIR] [--dembox PATH]
#
#   --rounds  how many rounds (default 3)
#   --data    folder of the packings (as bench/peers.sh: default
#             $DEMBOX_BENCH_DATA or ../shared/bench/data next to this
#             repository)
#   --dembox  the dembox binary (default build/dembox of this tree)
#
# A round runs, one after the other (bench/peers.sh --dim 3 --codes
# "dembox lammps-hh"; N = 216000 is the 3375 packing tiled 4 x 4 x 4):
#   N = 3375, 20000 steps; N = 20000, 10000 steps; N = 216000, 3000 steps
#     (one thread against one rank);
#   N = 20000, 5000 steps, two threads against two ranks;
#   `dembox bench --n 20000 --steps 3000 --threads 1,2`: one thread and
#     two by turns, in slices of 100 steps (docs/performance.md);
#   N = 3375, 3000 steps (one thread against one rank), and
#   `dembox bench --boundary periodic --steps 3000` of both packings: the
#     same work per particle at both sizes (below).
# Each case is labelled with `dembox_limits --pingpong` before and after
# (the one-way time of a cache line between CPUs 0 and 1: about 30 ns when
# they share an L3, 160 and more when they do not; docs/parallel.md).
# The summary gives, per figure, the median of the rounds and the range:
#   dembox / LAMMPS at each N (particle-steps per second, back to back);
#   two threads against one at N = 20000 (`dembox bench` by turns);
#   the cost per particle-step at N = 216000 over that at 3375, for dembox
#     and for LAMMPS (issue 14 asks at most 1.2 of dembox);
#   the same over 3000 steps at both sizes: dembox in its periodic cell,
#     whose two samples then list the same pairs per particle (between
#     walls the small one has a third of its particles at a wall, and
#     its 20000 steps loosen it), and LAMMPS, which runs a periodic box
#     (docs/performance-log.md, "The same work per particle at both
#     sizes").
# The logs and peers.sh's work folders (inputs, the tiled packing) go to
# one new folder, printed first. A round takes some 6 minutes on a 2-vCPU
# machine. Run it on an otherwise idle machine: the speed of a virtual
# machine moves by tens of per cent from one hour to the next, so only
# figures measured side by side are compared. Never run by CTest. Exit
# status 1 if a case fails.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
ROUNDS=3
DATA=${DEMBOX_BENCH_DATA:-$here/../../shared/bench/data}
DEMBOX=$here/../build/dembox

die() { echo "speed-round.sh: $*" >&2; exit 1; }
while [ $# -gt 0 ]; do
  case $1 in
    --rounds) ROUNDS=${2:?}; shift 2 ;;
    --data) DATA=${2:?}; shift 2 ;;
    --dembox) DEMBOX=${2:?}; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument $1 (see --help)" ;;
  esac
done
[[ $ROUNDS =~ ^[1-9][0-9]*$ ]] || die "--rounds must be a positive integer"
[ -x "$DEMBOX" ] || die "no dembox binary at $DEMBOX (build first, or --dembox)"
LIMITS=$(dirname "$DEMBOX")/dembox_limits
[ -x "$LIMITS" ] || die "no dembox_limits next to $DEMBOX"
command -v lmp >/dev/null 2>&1 ||
  die "LAMMPS is not installed (apt-get install lammps)"

pp() { "$LIMITS" --pingpong 2>/dev/null |
         sed -n 's/.*: \(.*\) ns per.*/\1/p' | tr ' ' , || echo '?'; }
# particle-steps per second of one code in a peers.sh table (column 9)
pss() { awk -F'|' -v c="$1" '$2 ~ "^ *"c" *$" {gsub(/ /, "", $9); print $9}'; }

out=$(mktemp -d "${TMPDIR:-/tmp}/dembox-speed.XXXXXX")
cpuinfo() { grep -m1 "^$1\s*:" /proc/cpuinfo 2>/dev/null | sed 's/.*: //'; }
cpu="$(cpuinfo 'model name') (family $(cpuinfo 'cpu family'), model $(cpuinfo model))"
echo "# $(date -u +%Y-%m-%dT%H:%MZ)  $(nproc) cores  $cpu"
# the build timed (an old binary would time old code: the row says which)
echo "# $("$DEMBOX" --version)"
echo "# logs in $out"

peers() { # round name args...: one peers.sh case, its figures to $out/name
  local r=$1 name=$2; shift 2
  local a b log=$out/r$r-$name.md
  a=$(pp)
  "$here/peers.sh" --dim 3 --codes "dembox lammps-hh" --data "$DATA" \
    --dembox "$DEMBOX" --work "$out/work-$name" "$@" >"$log" 2>&1 ||
    { cat "$log" >&2; die "peers.sh $* failed"; }
  b=$(pp)
  local d l
  d=$(pss dembox <"$log"); l=$(pss lammps <"$log")
  [ -n "$d" ] && [ -n "$l" ] || die "no figures in $log"
  echo "$d $l" >>"$out/$name"
  printf '  %-8s dembox %s, LAMMPS %s particle-steps/s: %s (ping-pong %s / %s)\n' \
    "$name" "$d" "$l" "$(awk -v d="$d" -v l="$l" 'BEGIN {printf "%.2f", d / l}')" "$a" "$b"
}

# label args...: `dembox bench args --quiet`, its ns per particle-step on
# standard output, a line with the label and the ping-pong times on stderr
bench() {
  local label=$1 a b ns
  shift
  a=$(pp)
  # (the log kept, so that a failing bench says why: in a pipeline
  # under pipefail its status would end the script without a word)
  "$DEMBOX" bench "$@" --quiet >"$out/bench.log" 2>&1 ||
    { cat "$out/bench.log" >&2; die "dembox bench $* failed"; }
  ns=$(sed -n 's/.*, \([0-9.]*\) ns per particle-step.*/\1/p' "$out/bench.log")
  b=$(pp)
  [ -n "$ns" ] || die "dembox bench $* gave no figure"
  echo "$ns"
  echo "  $label: $ns ns per particle-step (ping-pong $a / $b)" >&2
}
# one thread and two by turns at N = 20000 (`dembox bench --threads 1,2`):
# two threads' speed over one's to $out/threads, a line on stderr
turns() {
  local a b log=$out/turns.log v
  a=$(pp)
  "$DEMBOX" bench --data "$DATA/pack3d_20000.data" --steps 3000 \
    --threads 1,2 --quiet >"$log" 2>&1 ||
    { cat "$log" >&2; die "dembox bench --threads 1,2 failed"; }
  b=$(pp)
  v=$(sed -n 's/^by turns.*: 1 thread \([0-9.]*\) ns, 2 threads \([0-9.]*\) ns.*; \([0-9.]*\) times as fast (rounds: \(.*\))$/\1 \2 \3 \4/p' "$log")
  [ -n "$v" ] || die "no figures by turns in $log"
  set -- $v
  echo "$3" >>"$out/threads"
  echo "  turns    1 thread $1 ns, 2 threads $2 ns: $3 (rounds: ${*:4}) (ping-pong $a / $b)" >&2
}
# the same in a periodic cell, 3000 steps, one thread: N = $1, packing $2
cell() {
  bench "cell     N = $1, 3000 steps" --data "$2" --steps 3000 --threads 1 \
    --boundary periodic >>"$out/cell$1"
}

for r in $(seq 1 "$ROUNDS"); do
  echo "== round $r of $ROUNDS, $(date -u +%H:%M:%S)"
  peers "$r" 3375 --n 3375 --steps 20000
  peers "$r" 20000 --n 20000 --steps 10000
  peers "$r" 216000 --n 3375 --replicate 4 --steps 3000
  peers "$r" 20000np2 --n 20000 --steps 5000 --np 2
  turns
  peers "$r" 3375s --n 3375 --steps 3000
  cell 3375 "$DATA/pack3d_3375.data"
  cell 216000 "$out/work-216000/pack3d_216000.data"
done

# median (range) of a column of numbers
stat() { sort -g | awk '{v[NR] = $1} END {
  m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
  printf (NR > 1 ? "%.2f (%.2f\xe2\x80\x93%.2f)" : "%.2f"), m, v[1], v[NR]}'; }
ratio() { awk '{print $1 / $2}' "$out/$1" | stat; }
# cost per particle-step at 216000 over 3375, round by round: column c
# (1 dembox, 2 LAMMPS) of the cases small and large (particle-steps/s)
growth() { paste -d' ' "$out/${2:-3375}" "$out/216000" |
             awk -v c="$1" '{print $c / $(c + 2)}' | stat; }
# the same in the cell (ns per particle-step)
cellgrowth() { paste -d' ' "$out/cell3375" "$out/cell216000" |
                 awk '{print $2 / $1}' | stat; }

echo
echo "| CPU | date | rounds | N = 3375 | 20000 | 216000 | 20000, 2 threads / 2 ranks | 2 threads / 1 at N = 20000 | cost per particle-step 216000 / 3375, dembox | the same, LAMMPS | the same over 3000 steps each: dembox in a periodic cell, between walls | the same, LAMMPS |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
echo "| $cpu | $(date -u +%Y-%m-%d) | $ROUNDS" \
     "| $(ratio 3375) | $(ratio 20000) | $(ratio 216000) | $(ratio 20000np2)" \
     "| $(stat <"$out/threads") | $(growth 1) | $(growth 2)" \
     "| $(cellgrowth), $(growth 1 3375s) | $(growth 2 3375s) |"
