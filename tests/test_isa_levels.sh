#!/bin/sh
# A build for a CPU level with the force pass compiled for the levels
# above (CMake option DEM_DISPATCH; added to CTest only there): every
# level the CPU runs (DEMBOX_ISA) gives the same outputs bit for bit, in
# 2D and in 3D, with one thread and with two; a level the CPU lacks, or
# an unknown one, is refused with one line. Where qemu-user is installed
# the same run on emulated CPUs without AVX2 (qemu64) and with it but
# without AVX-512 (Haswell) takes the level each has and gives the same
# outputs again. Every level runs the records and ring passes too, with
# the same outputs.
set -eu
BIN=${DEMBOX_BIN:?run through ctest}
T=$(mktemp -d "${TMPDIR:-/tmp}/dembox-test-isa.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$T"

# run NAME CONFIG THREADS [launcher...]: a short run into NAME, its
# force pass's instructions in NAME.simd
run() {
    name=$1 cfg=$2 th=$3
    shift 3
    "$@" "$BIN" run "$cfg" -o "$name" --threads "$th" --quiet \
        --max-steps 400 > /dev/null 2> "$name.err" ||
        fail "$name: $(tail -3 "$name.err")"
    sed -n 's/.*(family [^)]*), \([^:]*\):.*/\1/p' "$name/timing.txt" \
        > "$name.simd"
}
same() { # the outputs of runs A and B, byte for byte
    for f in timeseries.csv particles_final.csv; do
        cmp -s "$1/$f" "$2/$f" || fail "$1/$f and $2/$f differ"
    done
}
levels=build
for l in x86-64-v3 x86-64-v4; do
    if DEMBOX_ISA=$l "$BIN" run biaxial2d -o probe-$l --max-steps 1 \
        --quiet > /dev/null 2> probe-$l.err; then
        levels="$levels $l"
    else
        grep -q "DEMBOX_ISA: this CPU lacks the instructions of $l" \
            probe-$l.err || fail "probe $l: $(cat probe-$l.err)"
        [ "$(grep -c . probe-$l.err)" -eq 1 ] || fail "probe $l: not one line"
    fi
done
echo "levels this CPU runs: $levels"
for cfg in biaxial2d triaxial3d; do
    for th in 1 2; do
        for l in $levels; do
            DEMBOX_ISA=$l run "$cfg-$l-$th" "$cfg" "$th"
            same "$cfg-build-1" "$cfg-$l-$th"
        done
    done
done
grep -q "SSE2\|AVX" biaxial2d-build-1.simd || fail "no instructions named"
case " $levels " in
*" x86-64-v4 "*) grep -q "AVX-512" biaxial2d-x86-64-v4-1.simd ||
    fail "v4 ran $(cat biaxial2d-x86-64-v4-1.simd)" ;;
esac
DEMBOX_ISA=x86-64-v9 "$BIN" run biaxial2d -o bad --max-steps 1 \
    > /dev/null 2> bad.err && fail "an unknown level ran"
grep -q "'x86-64-v9' is not a level of this build" bad.err ||
    fail "unknown level: $(cat bad.err)"
[ ! -e bad/timeseries.csv ] || fail "an unknown level wrote outputs"
# every level has the records and ring passes (GCC's vector extensions,
# contact/pass.c), the baseline's in SSE2: forced, the same outputs
for l in $levels; do
    for p in records ring; do
        DEMBOX_ISA=$l DEMBOX_PASS=$p run "biaxial2d-$l-$p" biaxial2d 2
        same biaxial2d-build-1 "biaxial2d-$l-$p"
    done
done

# (a build for the baseline only: one for a higher level refuses these)
if command -v qemu-x86_64 > /dev/null 2>&1 &&
    grep -q "SSE2" biaxial2d-build-1.simd; then
    for cpu in qemu64 Haswell; do
        run "emu-$cpu" biaxial2d 1 qemu-x86_64 -cpu "$cpu"
        same biaxial2d-build-1 "emu-$cpu"
    done
    # the ring pass on a CPU without AVX
    DEMBOX_PASS=ring run emu-qemu64-ring biaxial2d 1 qemu-x86_64 -cpu qemu64
    same biaxial2d-build-1 emu-qemu64-ring
    grep -q "SSE2" emu-qemu64.simd || fail "qemu64 ran $(cat emu-qemu64.simd)"
    case " $levels " in
    *" x86-64-v3 "*) grep -q "AVX2" emu-Haswell.simd ||
        fail "Haswell ran $(cat emu-Haswell.simd)" ;;
    esac
fi
echo "test_isa_levels: ok"
