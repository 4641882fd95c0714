#!/bin/sh
# Reproduce the figures of both seeds with the scaled built-in examples
# (docs/reproduction.md records the results). Long: about 25 CPU-minutes
# on this project's reference machine; JOBS runs in parallel (default: all
# cores). Each sweep restarts where it stopped when run again.
# Usage: scripts/reproduce.sh [OUTDIR]
set -eu
cd "$(dirname "$0")/.."
OUT=${1:-reproduce}
JOBS=${JOBS:-$(nproc)}
B=./build/dembox
[ -x "$B" ] || ./scripts/setup.sh build
sweep() { name=$1; shift; echo "== $name"; "$B" sweep "$@" -o "$OUT/$name" --jobs "$JOBS" --quiet; }

# seed 001 Figs. 6-8: frictional powder (mu = 0.5) at three side pressures;
# Mohr circles at peak and the flow function (Fig. 7), void ratio (Fig. 8)
sweep pressure biaxial2d --param stages.0.pressure,stages.1.pressure=250,500,1000

# seed 001 Figs. 4-5: frictionless, cohesive powder; flow function per
# cohesion (Fig. 5 top) and macroscopic cohesion versus kc/k2 (Fig. 5 bottom)
sweep cohesion biaxial2d-cohesive --param contact.kc=1.0e4,5.0e4,1.0e5 \
    --param stages.0.pressure,stages.1.pressure=250,500,1000

# seed 000 Fig. 3 left: macroscopic friction at peak and in the critical
# state versus contact friction, for two initial conditions: dense
# (frictionless preparation) and looser (prepared with the contact friction)
sweep friction-dense biaxial2d --param contact.mu=0.1,0.3,0.5,1.0
sweep friction-loose biaxial2d --param contact.mu,stages.0.mu=0.1,0.3,0.5,1.0

# seed 000 Figs. 2 right and 3 right: cyclic loading, strain accumulation
# per cycle for several contact frictions (ratcheting or shakedown)
sweep cyclic cyclic3d --param contact.mu=0.1,0.3,0.5

echo "results in $OUT/*/sweep.json and $OUT/*/plots/"
