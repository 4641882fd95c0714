#!/bin/bash
# What a force pass does per particle-step at N = 3375 and at 216000 (the
# 3375 packing tiled 4 x 4 x 4), counted by valgrind's cachegrind: the
# instructions, data reads and writes, mispredicted branches, L1 misses,
# and the lines that come from beyond the L2 and beyond the L3. For CPUs
# whose virtual machines give no hardware counters (docs/performance-log.md,
# "Counted by cachegrind", session 94).
#
# usage: bench/cache-counts.sh [--data DIR] [--lines K] [--build DIR]
#
#   --data   folder of the packings (as bench/peers.sh: default
#            $DEMBOX_BENCH_DATA or ../shared/bench/data next to this
#            repository)
#   --lines  also list the K source lines that take the most lines from
#            beyond the L2 at N = 216000 (default 0: none); a line in an
#            intrinsics header (avxintrin.h, ...) is a vector load or
#            store the pass inlined from it
#   --build  the folder of the build for valgrind (default: a new one in
#            the output folder). valgrind 3.19 knows AVX2, not AVX-512,
#            so the build is for x86-64-v3 with -g, no dispatch, no MPI:
#            the 8-lane pass, the same source.
#
# Both sizes run the same case: the periodic cell, one thread, the ring
# pass forced (the pass large samples run), the first list only (no build
# within the counted steps, 4.45 listed pairs per particle at both). Each
# size runs twice, at two step counts (3375: 100 and 700; 216000: 10 and
# 40), and the difference of the two, per particle-step, leaves out the
# start-up and the list build. The caches simulated are this CPU's, from
# /sys (sizes rounded down to a power of two of sets, as cachegrind
# needs): its L1 data cache, and as the last level once its L2 and once
# its L3. cachegrind simulates LRU caches without prefetchers and does
# not count the write-backs of dirty lines: the counts are what each size
# asks of the memory, not how long it waits. Prints a Markdown table.
# Takes some 6 minutes on 2 vCPUs with its build (the two step counts of
# a size run side by side). Never run by CTest; exit status 1 if a step
# fails.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
DATA=${DEMBOX_BENCH_DATA:-$here/../../shared/bench/data}
LINES=0 BUILD=

die() { echo "cache-counts.sh: $*" >&2; exit 1; }
while [ $# -gt 0 ]; do
  case $1 in
    --data) DATA=${2:?}; shift 2 ;;
    --lines) LINES=${2:?}; shift 2 ;;
    --build) BUILD=${2:?}; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument $1 (see --help)" ;;
  esac
done
[[ $LINES =~ ^[0-9]+$ ]] || die "--lines must be a whole number"
[ -r "$DATA/pack3d_3375.data" ] || die "no packing $DATA/pack3d_3375.data"
command -v valgrind >/dev/null 2>&1 ||
  die "valgrind is not installed (apt-get install valgrind)"
command -v python3 >/dev/null 2>&1 || die "python3 is not installed"
[ -z "$BUILD" ] || [ -x "$BUILD/dembox" ] || die "no dembox in $BUILD"

out=$(mktemp -d "${TMPDIR:-/tmp}/dembox-cache.XXXXXX")
cpuinfo() { grep -m1 "^$1\s*:" /proc/cpuinfo 2>/dev/null | sed 's/.*: //'; }
echo "# $(date -u +%Y-%m-%dT%H:%MZ)  $(cpuinfo 'model name')" \
     "(family $(cpuinfo 'cpu family'), model $(cpuinfo model))"
echo "# logs in $out"

# cache geometry "size,ways,line" of cpu0's cache of a level and type,
# the size rounded down so that the sets are a power of two
geometry() {
  local d s w l sets p=1
  for d in /sys/devices/system/cpu/cpu0/cache/index*; do
    [ "$(cat "$d/level")" = "$1" ] || continue
    [ "$(cat "$d/type")" = "$2" ] || continue
    s=$(cat "$d/size"); w=$(cat "$d/ways_of_associativity")
    l=$(cat "$d/coherency_line_size")
    case $s in *K) s=$(( ${s%K} * 1024 )) ;; *M) s=$(( ${s%M} << 20 )) ;; esac
    sets=$(( s / (w * l) ))
    while [ $(( p * 2 )) -le "$sets" ]; do p=$(( p * 2 )); done
    echo "$(( p * w * l )),$w,$l"
    return
  done
  die "no level-$1 $2 cache in /sys/devices/system/cpu/cpu0/cache"
}
D1=$(geometry 1 Data); L2=$(geometry 2 Unified); L3=$(geometry 3 Unified)
echo "# simulated: L1d $D1, L2 $L2, L3 $L3 (bytes, ways, line)"

if [ -z "$BUILD" ]; then
  BUILD=$out/build
  echo "# building for valgrind in $BUILD"
  cmake -S "$here/.." -B "$BUILD" -DDEM_NATIVE=OFF -DDEM_DISPATCH=OFF \
    -DDEM_MPI=OFF -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_FLAGS="-march=x86-64-v3 -g" >"$out/cmake.log" 2>&1 ||
    { cat "$out/cmake.log" >&2; die "cmake failed"; }
  cmake --build "$BUILD" --target dembox -j "$(nproc)" >>"$out/cmake.log" 2>&1 ||
    { tail -20 "$out/cmake.log" >&2; die "the build failed"; }
fi
[ -x "$BUILD/dembox" ] || die "no dembox in $BUILD"

# the tiled packing, as bench/peers.sh writes it (one short dembox run)
"$here/peers.sh" --dim 3 --n 3375 --replicate 4 --steps 10 --codes dembox \
  --data "$DATA" --dembox "$BUILD/dembox" --work "$out/tile" \
  >"$out/tile.log" 2>&1 || { cat "$out/tile.log" >&2; die "tiling failed"; }
BIG=$out/tile/pack3d_216000.data
[ -r "$BIG" ] || die "peers.sh wrote no $BIG"

# tag cache steps args...: one cachegrind run
count() {
  local tag=$1 ll=$2 steps=$3
  shift 3
  DEMBOX_PASS=ring valgrind --tool=cachegrind --cache-sim=yes \
    --branch-sim=yes --D1="$D1" --LL="$ll" \
    --cachegrind-out-file="$out/cg.$tag.$steps" \
    "$BUILD/dembox" bench "$@" --steps "$steps" --boundary periodic \
    --threads 1 --quiet >"$out/log.$tag.$steps" 2>&1 ||
    { tail -5 "$out/log.$tag.$steps" >&2; die "valgrind $tag, $steps steps failed"; }
}
# each size and its two step counts (the counts' difference)
SIZES=("3375 100 700" "216000 10 40")
for level in L2 L3; do
  ll=${!level}
  echo "== last level $level, $(date -u +%H:%M:%S)"
  # the two step counts of a size side by side, one on each core
  for c in "${SIZES[@]}"; do
    read -r size s0 s1 <<<"$c"
    f=$BIG; [ "$size" = 3375 ] && f=$DATA/pack3d_3375.data
    pids=()
    for steps in "$s0" "$s1"; do
      count "$level.$size" "$ll" "$steps" --data "$f" & pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
  done
done

python3 - "$out" "$LINES" "${SIZES[@]}" <<'EOF'
import collections, sys

out, top = sys.argv[1], int(sys.argv[2])
# size: (particles, the two step counts), from the SIZES of the script
runs = {}
for c in sys.argv[3:]:
    size, s0, s1 = c.split()
    runs[size] = (int(size), int(s0), int(s1))

def load(name):
    """events and {(file, line): counts} of a cachegrind output file"""
    events, acc, fl = None, collections.defaultdict(list), '?'
    for line in open(name):
        if line.startswith('events:'):
            events = line.split()[1:]
        elif line.startswith('fl='):
            fl = line[3:].strip().split('/')[-1]
        elif line[:1].isdigit():
            p = [int(x) for x in line.split()]
            a = acc[(fl, p[0])]
            a.extend([0] * (len(events) - len(a)))
            for k, v in enumerate(p[1:]):
                a[k] += v
    return events, acc

def per_step(level, size):
    """{(file, line): {event: count per particle-step}}, the difference
    of the two step counts"""
    n, s0, s1 = runs[size]
    ev, a = load(f'{out}/cg.{level}.{size}.{s0}')
    _, b = load(f'{out}/cg.{level}.{size}.{s1}')
    d = n * (s1 - s0)
    return {k: {e: (v[i] - a.get(k, [0] * len(ev))[i]) / d
                for i, e in enumerate(ev)} for k, v in b.items()}

c = {(lv, s): per_step(lv, s) for lv in ('L2', 'L3') for s in runs}
def total(lv, s, *events):
    return sum(sum(v.get(e, 0) for e in events) for v in c[lv, s].values())

rows = [('instructions', 'L2', ('Ir',)),
        ('data reads', 'L2', ('Dr',)),
        ('data writes', 'L2', ('Dw',)),
        ('mispredicted branches', 'L2', ('Bcm', 'Bim')),
        ('L1 data misses (read + write)', 'L2', ('D1mr', 'D1mw')),
        ('lines from beyond the L2 (read + write)', 'L2', ('DLmr', 'DLmw')),
        ('lines from beyond the L3 (read + write)', 'L3', ('DLmr', 'DLmw'))]
print()
print('| per particle-step | N = 3375 | N = 216000 | 216000 / 3375 |')
print('|---|---|---|---|')
for name, lv, ev in rows:
    a, b = total(lv, '3375', *ev), total(lv, '216000', *ev)
    r = f'{b / a:.2f}' if a > 0.005 else '-'
    print(f'| {name} | {a:.2f} | {b:.2f} | {r} |')
if top:
    big = c['L2', '216000']
    small = c['L2', '3375']
    def miss(d, k):
        return d.get(k, {}).get('DLmr', 0) + d.get(k, {}).get('DLmw', 0)
    print()
    print('| source line | lines from beyond the L2, N = 3375 | 216000 |')
    print('|---|---|---|')
    for k in sorted(big, key=lambda k: -miss(big, k))[:top]:
        print(f'| {k[0]}:{k[1]} | {miss(small, k):.2f} | {miss(big, k):.2f} |')
EOF
