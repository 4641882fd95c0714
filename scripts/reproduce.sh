#!/bin/bash
# Reproduce the figures of both papers (docs/reproduction.md records the
# results). Every part is a `dembox sweep` into OUTDIR/NAME; running the
# same command again resumes: finished runs are skipped, unfinished ones
# continue from their checkpoints.
#
# usage: scripts/reproduce.sh [--quick | --paper] [--jobs N] [--only NAMES]
#                             [--numbers DIR] [--smoke] [--any-build]
#                             [--list] [OUTDIR]
#
#   --quick       the scaled built-in examples, one sample per point
#                 (default; about 25 CPU minutes)
#   --paper       the papers' sizes and parameters with 3 seeds per point
#                 (about 53 CPU hours, --list gives each part's: run it
#                 over several sessions)
#   --jobs N      runs at once (default: the number of cores)
#   --only NAMES  only these parts (comma-separated; see --list)
#   --numbers DIR after each part, copy its sweep.json, its pictures
#                 (plots/: .png with the .dat and .gp that draw them) and
#                 every run's summary.json, config.cfg, timing.txt (the
#                 build that ran it) and run.log (its warnings) to
#                 DIR/NAME/ (the numbers behind docs/reproduction.md; the
#                 runs there replaced by the part's, so that none of an
#                 earlier command stays beside them), and what a part's
#                 own command reads from its runs (oc-contacts:
#                 scripts/contact-adhesion.py, from the contacts)
#   --smoke       every run stops after 300 steps (checks the command, not
#                 the physics; used by CTest)
#   --any-build   resume unfinished runs from checkpoints another build of
#                 dembox wrote (a rebuild between sessions), not bit for
#                 bit either build's and noted in their timing.txt; else
#                 such runs start again
#   --list        print the parts with their CPU time and exit
#   OUTDIR        default: reproduce-quick or reproduce-paper
#
# OUTDIR/reproduce.id records the mode and the parts; a folder made by
# another mode, another set of parts or another dembox version (its number;
# a rebuild of the same version goes on) is refused (a resumed sweep must
# continue the same runs). OUTDIR/reproduce.builds lists the builds
# (`dembox --version`) that ran in it: a resume by another one warns that
# the parts' ensembles then mix engines (finished runs are not run
# again), which numbers to publish should not. A part whose runs fail is
# reported and the others go on; the exit status is then 1.
set -u
HERE=$(pwd)
cd "$(dirname "$0")/.."

MODE=quick JOBS= ONLY= NUMBERS= SMOKE= ANY= LIST= OUT=
die() { echo "reproduce.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case $1 in
    --quick) MODE=quick; shift ;;
    --paper) MODE=paper; shift ;;
    --jobs) JOBS=${2:-}; shift 2 || die "--jobs needs a number" ;;
    --only) ONLY=${2:-}; shift 2 || die "--only needs part names" ;;
    --numbers) NUMBERS=${2:-}; shift 2 || die "--numbers needs a folder" ;;
    --smoke) SMOKE=1; shift ;;
    --any-build) ANY=1; shift ;;
    --list) LIST=1; shift ;;
    -h | --help) sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$OUT" ] || die "one OUTDIR only (got $OUT and $1)"; OUT=$1; shift ;;
    esac
done
JOBS=${JOBS:-$(nproc)}
[[ $JOBS =~ ^[1-9][0-9]*$ ]] || die "--jobs must be a positive integer (got $JOBS)"
OUT=${OUT:-reproduce-$MODE}
# paths given by the caller are relative to where it was called from
case $OUT in /*) ;; *) OUT=$HERE/$OUT ;; esac
case $NUMBERS in /* | "") ;; *) NUMBERS=$HERE/$NUMBERS ;; esac
case ${DEMBOX:-} in /* | "") ;; *) DEMBOX=$HERE/$DEMBOX ;; esac
B=${DEMBOX:-./build/dembox} # DEMBOX: another dembox binary (tests)

# The parts: NAME|CPU minutes|figures|sweep arguments[|numbers], the
# last an optional command that --numbers runs after the part with its
# folder and its numbers folder (its output kept there as table.md). CPU minutes on
# this project's machine (docs/reproduction.md gives the measured ones;
# parts not yet run there are estimated from the runs' size, about 10
# CPU seconds per simulated second of 3375 spheres at dt = 2e-5 s and
# about 5 CPU minutes per 0.5 s of 1950 discs at dt = 2e-7 s).
quick_parts() {
    cat <<'EOF'
pressure|4|Luding et al. Figs. 6, 7, 8, §3.3|biaxial2d --param stages.0.pressure,stages.1.pressure=250,500,1000
cohesion|8|Luding et al. Figs. 4, 5, §3.1|biaxial2d-cohesive --param contact.kc=1.0e4,5.0e4,1.0e5 --param stages.0.pressure,stages.1.pressure=250,500,1000
friction-dense|5|David et al. Fig. 3 left (dense), Fig. 2 left|biaxial2d --param contact.mu=0.1,0.3,0.5,1.0
friction-loose|5|David et al. Fig. 3 left (loose)|biaxial2d --param contact.mu,stages.0.mu=0.1,0.3,0.5,1.0
cyclic|5|David et al. Figs. 2 right, 3 right|cyclic3d --param contact.mu=0.1,0.3,1.0
EOF
}
paper_parts() {
    cat <<'EOF'
cyclic-period|30|David et al.: the period does not matter (t0 = 1, 2, 5 s)|cyclic3d-paper --set contact.mu=0.1 --set stages.1.cycles=10 --param stages.1.period=1,2,5 --param seed=1,2
cyclic-mu|140|David et al. Figs. 2 right, 3 right (50 cycles, t0 = 1 s)|cyclic3d-paper --set stages.1.period=1 --set stages.1.cycles=50 --param contact.mu=0.01,0.1,0.3,0.5,1.0 --param seed=1,2,3
cyclic-threshold|60|David et al. Fig. 3 right: the threshold friction (mu = 0.02, 0.05)|cyclic3d-paper --set stages.1.period=1 --set stages.1.cycles=50 --param contact.mu=0.02,0.05 --param seed=1,2,3
cyclic-threshold-seeds|45|David et al. Fig. 3 right: the threshold friction, seeds 4-6 (mu = 0.02, 0.05)|cyclic3d-paper --set stages.1.period=1 --set stages.1.cycles=50 --param contact.mu=0.02,0.05 --param seed=4,5,6
cyclic-floor-gb0|30|David et al. Fig. 3 right: the creep floor at mu = 1 without background damping|cyclic3d-paper --set stages.1.period=1 --set stages.1.cycles=50 --set contact.mu=1.0 --set damping.gamma_b=0.0 --param seed=1,2,3
cyclic-floor-t2|60|David et al. Fig. 3 right: the creep floor at mu = 1 with twice the period|cyclic3d-paper --set stages.1.period=2 --set stages.1.cycles=50 --set contact.mu=1.0 --param seed=1,2,3
biaxial-pressure|90|Luding et al. Figs. 6, 7, 8, §3.3 (40 % strain)|biaxial2d-paper --set stages.1.strain=0.4 --set stages.1.duration=0.8 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3
biaxial-pressure-fixed|230|Luding et al. Figs. 6, 7, 8, §3.3 (40 % strain) again after the re-ordering fix, seeds 1-4 (overlaps up to 0.5 of a radius at 1000 N/m)|biaxial2d-paper --set stages.1.strain=0.4 --set stages.1.duration=0.8 --set checks.max_overlap=0.6 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3,4
cyclic-t10|65|David et al. Figs. 2 right, 3 right at the paper's period t0 = 10 s (mu = 0.5, 50 cycles, seed 1; against cyclic-mu's t0 = 1 s)|cyclic3d-paper --set stages.1.cycles=50 --param seed=1
cyclic-t10-first|30|David et al. Figs. 2 right, 3 right: the first cycles at t0 = 10 s, mu = 0.5, seeds 2 and 3 (10 cycles; against cyclic-mu's t0 = 1 s)|cyclic3d-paper --set stages.1.cycles=10 --param seed=2,3
cyclic-t10-paired|45|David et al. Figs. 2 right, 3 right: t0 = 10 s against cyclic-mu's t0 = 1 s on the same samples (mu = 0.5, seeds 1-3, 10 cycles; the preparation is the same when the engine is)|cyclic3d-paper --set stages.1.cycles=10 --param seed=1,2,3
cyclic-t10-full|200|David et al. Figs. 2 right, 3 right: the example cyclic3d-paper in full (t0 = 10 s, 100 cycles, mu = 0.5, seed 1; one run with 2 threads; the engine since session 60 (commit 141a4ee) makes the sample recorded as cyclic-t10-full-4)|cyclic3d-paper --param seed=1 --threads 2
cyclic-t10-full-3|210|David et al. Figs. 2 right, 3 right: the example cyclic3d-paper in full, a third sample (seed 2; one run with 2 threads)|cyclic3d-paper --param seed=2 --threads 2
critical-20|45|Luding et al. Fig. 8 bottom: the critical state read as the paper did, over the last quarter of 20 % strain, seeds 1-3 (does a single sample show the critical friction falling with p?)|biaxial2d-paper --set checks.max_overlap=0.6 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3
critical-stiffness|60|Luding et al. Fig. 8: the critical friction against p/k2 (p = 100 N/m with a tenth of the stiffness: the overlaps of 1000 N/m)|biaxial2d-paper --set stages.1.strain=0.4 --set stages.1.duration=0.8 --set stages.0.pressure=100 --set stages.1.pressure=100 --set contact.k1=5.0e3 --set contact.k2=1.0e4 --set contact.kt=2.0e3 --set contact.gamma_n=0.0316 --set contact.gamma_t=0.00632 --set checks.max_overlap=0.6 --param seed=1,2,3,4
peak-reference|8|Luding et al. Fig. 7 gap: reference (p = 500, 10 % strain)|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --param seed=1,2,3,4
peak-kt|8|Luding et al. Fig. 7 gap: k_t = k2 instead of 0.2 k2|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set contact.kt=1.0e5 --param seed=1,2,3,4
peak-prep|7|Luding et al. Fig. 7 gap: prepared with mu = 0.5 (looser)|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set stages.0.mu=0.5 --param seed=1,2,3,4
peak-rate|12|Luding et al. Fig. 7 gap: half the strain rate|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.4 --param seed=1,2,3,4
peak-damping|7|Luding et al. Fig. 7 gap: no background damping|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set damping.gamma_b=0.0 --param seed=1,2,3,4
peak-size|37|Luding et al. Fig. 7 gap: twice the particles (N = 3900)|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set particles.count=3900 --param seed=1,2,3,4
peak-gammat|20|Luding et al. Fig. 7 gap: no tangential viscosity|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set contact.gamma_t=0.0 --param seed=1,2,3,4
peak-kt-damping|32|Luding et al. Fig. 7 gap: k_t = k2 and no background damping|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set contact.kt=1.0e5 --set damping.gamma_b=0.0 --param seed=1,2,3,4
peak-kt2|30|Luding et al. Fig. 7 gap: k_t = 2 k2 and no background damping|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set contact.kt=2.0e5 --set damping.gamma_b=0.0 --param seed=1,2,3,4
peak-wall-heavy|8|Luding et al. Fig. 7 gap: walls ten times heavier (m_w = 0.1 kg, relaxation 50 ms)|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set walls.mass=0.1 --param seed=1,2,3,4
peak-wall-viscous|8|Luding et al. Fig. 7 gap: walls ten times more viscous (gamma_w = 20 kg/s, relaxation 0.5 ms)|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set walls.gamma=20.0 --param seed=1,2,3,4
peak-wall-heavy-kt-damping|10|Luding et al. Fig. 7 gap: heavy walls (m_w = 0.1 kg), k_t = k2 and no background damping together|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set walls.mass=0.1 --set contact.kt=1.0e5 --set damping.gamma_b=0.0 --param seed=1,2,3,4
friction-dense|120|David et al. Fig. 2 left, Fig. 3 left (dense)|biaxial2d-paper --set stages.0.pressure=200 --set stages.1.pressure=200 --set stages.1.strain=0.4 --set stages.1.duration=0.8 --param contact.mu=0.0,0.1,0.2,0.4,0.6,1.0 --param seed=1,2,3
friction-loose|130|David et al. Fig. 3 left (loose: prepared with mu)|biaxial2d-paper --set stages.0.pressure=200 --set stages.1.pressure=200 --set stages.1.strain=0.4 --set stages.1.duration=0.8 --param contact.mu,stages.0.mu=0.0,0.1,0.2,0.4,0.6,1.0 --param seed=1,2,3
biaxial-cohesion|240|Luding et al. Figs. 4, 5, §3.1|biaxial2d-paper --set contact.mu=0.0 --param contact.kc=0.0,2.5e4,5.0e4,1.0e5 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3
oc-cohesion|157|Luding et al. Fig. 5 bottom: over-consolidated at 1000 N/m, k_c = k2|biaxial2d-paper --set contact.mu=0.0 --set contact.kc=1.0e5 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --param stages.1.pressure,stages.2.pressure=100,250,500,1000 --param seed=1,2,3
oc-kc|300|Luding et al. Fig. 5 bottom: over-consolidated at 1000 N/m, k_c/k2 = 0.25, 0.5|biaxial2d-paper --set contact.mu=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --param contact.kc=2.5e4,5.0e4 --param stages.1.pressure,stages.2.pressure=100,250,500,1000 --param seed=1,2,3
oc-kc-seeds|150|Luding et al. Fig. 5 bottom: over-consolidated at 1000 N/m, k_c/k2 = 0.25, seeds 4-6 (the shape of c against k_c)|biaxial2d-paper --set contact.mu=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --set contact.kc=2.5e4 --param stages.1.pressure,stages.2.pressure=100,250,500,1000 --param seed=4,5,6
oc-reference|90|Luding et al. Fig. 5 bottom: over-consolidated at 1000 N/m, k_c = 0 (p = 1000: biaxial-cohesion)|biaxial2d-paper --set contact.mu=0.0 --set contact.kc=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --param stages.1.pressure,stages.2.pressure=100,250,500 --param seed=1,2,3
oc-kc-half-seeds|49|Luding et al. Fig. 5 bottom at fixed pressure: over-consolidated at 1000 N/m, k_c/k2 = 0.5, seeds 4-6 at p = 100, 250|biaxial2d-paper --set contact.mu=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --set contact.kc=5.0e4 --param stages.1.pressure,stages.2.pressure=100,250 --param seed=4,5,6
oc-kc-075|34|Luding et al. Fig. 5 bottom at fixed pressure: over-consolidated at 1000 N/m, k_c/k2 = 0.75, seeds 1-3 at p = 100, 250|biaxial2d-paper --set contact.mu=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --set contact.kc=7.5e4 --param stages.1.pressure,stages.2.pressure=100,250 --param seed=1,2,3
oc-contacts|60|Luding et al. Fig. 5 bottom: what the contacts hold (k_c/k2 = 0 to 1, seeds 1-2, over-consolidated at 1000 N/m and sheared at 100 N/m, the contacts every 5 ms; numbers by scripts/contact-adhesion.py)|biaxial2d-paper --set contact.mu=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --set stages.1.pressure=100 --set stages.2.pressure=100 --set output.dump_interval=0.005 --param contact.kc=0.0,2.5e4,5.0e4,7.5e4,1.0e5 --param seed=1,2|python3 scripts/contact-adhesion.py
oc-reference-1000|16|Luding et al. Fig. 5 bottom at fixed pressure: over-consolidated at 1000 N/m, k_c = 0 tested at 1000 N/m (seeds 1-3)|biaxial2d-paper --set contact.mu=0.0 --set stages=({type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;mu=0.0;},{type="isotropic";pressure=1000.0;tolerance=1.0e-4;max_time=0.1;},{type="compress";axis="y";strain=0.2;duration=0.4;profile="cosine";pressure=1000.0;}) --set contact.kc=0.0 --param seed=1,2,3
peak-best-flow|40|Luding et al. Fig. 7 gap: the flow function at peak of the closest variant (heavy walls, k_t = k2, no background damping) at the four pressures|biaxial2d-paper --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set walls.mass=0.1 --set contact.kt=1.0e5 --set damping.gamma_b=0.0 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3,4
peak-best-cell|76|Luding et al. Fig. 7 gap: the same closest variant in a periodic cell (no walls)|biaxial2d-paper --set box.boundary=periodic --set stages.1.strain=0.1 --set stages.1.duration=0.2 --set walls.mass=0.1 --set contact.kt=1.0e5 --set damping.gamma_b=0.0 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3
peak-cell|76|Luding et al. Fig. 7 gap: the flow function at peak in a periodic cell (no walls)|biaxial2d-paper --set box.boundary=periodic --set stages.1.strain=0.1 --set stages.1.duration=0.2 --param stages.0.pressure,stages.1.pressure=100,250,500,1000 --param seed=1,2,3
mu0-cell|35|Luding et al. Fig. 5 top gap: frictionless at p = 500 in a periodic cell (against biaxial-cohesion, k_c = 0)|biaxial2d-paper --set contact.mu=0.0 --set box.boundary=periodic --param seed=1,2,3
mu0-damping|30|Luding et al. Fig. 5 top gap: frictionless at p = 500 without background damping (against biaxial-cohesion, k_c = 0)|biaxial2d-paper --set contact.mu=0.0 --set damping.gamma_b=0.0 --param seed=1,2,3
mu0-size|70|Luding et al. Fig. 5 top gap: frictionless at p = 500 with twice the particles, N = 3900 (against biaxial-cohesion, k_c = 0)|biaxial2d-paper --set contact.mu=0.0 --set particles.count=3900 --param seed=1,2,3
EOF
}
parts() { if [ "$MODE" = paper ]; then paper_parts; else quick_parts; fi; }

# the parts chosen
ALL=$(parts | cut -d'|' -f1 | tr '\n' ' ')
if [ -n "$ONLY" ]; then
    for n in ${ONLY//,/ }; do
        case " $ALL " in *" $n "*) ;; *) die "--only: no part '$n' in --$MODE (parts: $ALL)" ;; esac
    done
    CHOSEN=" ${ONLY//,/ } "
else
    CHOSEN=" $ALL "
fi
selected() { parts | while IFS='|' read -r n m f a x; do case "$CHOSEN" in *" $n "*) echo "$n|$m|$f|$a|$x" ;; esac; done; }

# Wall minutes of a part of M CPU minutes and sweep arguments A with
# --jobs JOBS: its runs (the product of the --param value counts) go
# min(runs, JOBS) at once, each with its --threads (default 1).
part_wall() {
    local m=$1 runs=1 threads=1 prev="" w
    shift
    for w in "$@"; do
        case $prev in
            --param) local c=${w#*=}
                     c=${c//[^,]/}; runs=$((runs * (${#c} + 1))) ;;
            --threads) threads=$w ;;
        esac
        prev=$w
    done
    local at=$(( runs < JOBS ? runs : JOBS ))
    echo $(( (m + at * threads - 1) / (at * threads) ))
}

total=0 wall=0
printf '%-18s %8s  %s\n' part CPU-min figures
while IFS='|' read -r n m f a x; do
    printf '%-18s %8s  %s\n' "$n" "$m" "$f"
    total=$((total + m))
    # shellcheck disable=SC2086 # the arguments are split on purpose
    wall=$((wall + $(part_wall "$m" $a)))
done < <(selected)
echo "mode --$MODE: about $total CPU minutes in all, $wall minutes with $JOBS jobs" \
     "(finished runs are skipped)"
[ -z "$LIST" ] || exit 0

[ -x "$B" ] || ./scripts/setup.sh build dembox >/dev/null || die "build failed"
[ -x "$B" ] || die "$B: not executable"
VERSION=$("$B" --version 2>/dev/null | head -1 | cut -d' ' -f1-2)
ID="mode=$MODE smoke=${SMOKE:-0} version=$VERSION parts=$(echo $CHOSEN)"
mkdir -p "$OUT" || die "$OUT: cannot create"
if [ -f "$OUT/reproduce.id" ]; then
    old=$(cat "$OUT/reproduce.id")
    [ "$old" = "$ID" ] || die "$OUT was made by another command ($old); use another OUTDIR"
elif [ -n "$(ls -A "$OUT")" ]; then
    die "$OUT is not empty and was not made by reproduce.sh; use another OUTDIR"
fi
echo "$ID" > "$OUT/reproduce.id"
BUILD=$("$B" --version 2>/dev/null | head -1)
if [ -f "$OUT/reproduce.builds" ] && ! grep -qxF "$BUILD" "$OUT/reproduce.builds"; then
    echo "reproduce.sh: warning: $OUT holds runs of another build" \
         "($(tail -1 "$OUT/reproduce.builds")); this one ($BUILD) runs only" \
         "what is not finished, so a part's ensemble may mix engines:" \
         "for numbers to publish, use a new OUTDIR" >&2
fi
grep -qxF "$BUILD" "$OUT/reproduce.builds" 2>/dev/null ||
    echo "$BUILD" >> "$OUT/reproduce.builds"

failed=""
while IFS='|' read -r n m f a x; do
    echo "== $n ($f; about $m CPU minutes) $(date -u +%H:%M:%S)"
    # shellcheck disable=SC2086 # the arguments are split on purpose
    if ! "$B" sweep $a -o "$OUT/$n" --jobs "$JOBS" \
        --set output.checkpoint_interval=120 ${SMOKE:+--max-steps 300} \
        ${ANY:+--any-build}; then
        failed="$failed $n"
    fi
    if [ -n "$NUMBERS" ] && [ -f "$OUT/$n/sweep.json" ]; then
        mkdir -p "$NUMBERS/$n"
        cp "$OUT/$n/sweep.json" "$NUMBERS/$n/"
        rm -rf "$NUMBERS/$n/runs" # (the part's runs now, no older ones)
        for r in "$OUT/$n"/runs/*/; do
            [ -f "$r/summary.json" ] || continue
            d="$NUMBERS/$n/runs/$(basename "$r")"
            mkdir -p "$d"
            cp "$r/summary.json" "$r/config.cfg" "$d/"
            for k in timing.txt run.log; do
                [ ! -f "$r/$k" ] || cp "$r/$k" "$d/"
            done
        done
        if [ -n "$x" ] && [ -z "$SMOKE" ]; then # the part's own numbers
            # shellcheck disable=SC2086 # the command is split on purpose
            $x "$OUT/$n" "$NUMBERS/$n" > "$NUMBERS/$n/table.md" ||
                failed="$failed $n"
        fi
        if [ -d "$OUT/$n/plots" ]; then
            mkdir -p "$NUMBERS/$n/plots"
            cp "$OUT/$n"/plots/*.png "$OUT/$n"/plots/*.dat "$OUT/$n"/plots/*.gp \
                "$NUMBERS/$n/plots/" 2>/dev/null
        fi
    fi
done < <(selected)
if [ -n "$failed" ]; then
    echo "reproduce.sh: runs failed in:$failed (see OUTDIR/PART/runs/*/run.log); run the same command again to retry them" >&2
    exit 1
fi
echo "results in $OUT/*/sweep.json and $OUT/*/plots/"
