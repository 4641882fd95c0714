#!/bin/bash
# The discs' rotational inertia alone (docs/reproduction.md, "Luding et
# al., Fig. 7: where do the 2.9 deg go?"): paired runs of biaxial2d-paper
# at 500 N/m from the same prepared packings, once with a sphere's moment
# of inertia (0.4 m a^2, the example's) and once with a disc's (0.5 m a^2),
# the mass a sphere's in both (the packing file's mass column with
# particles.mass_model = "disc" gives I = 0.5 m a^2, formats/particles_csv.c).
# Frictionless preparation, so the inertia plays no part before loading.
#
# usage: scripts/peak-inertia.sh OUTDIR     (DEMBOX: another binary)
# About 50 CPU minutes here; finished runs are skipped when run again.
# Prints phi_peak per seed and the paired difference disc - sphere.
set -eu
OUT=${1:?usage: scripts/peak-inertia.sh OUTDIR}
B=${DEMBOX:-$(cd "$(dirname "$0")/.." && pwd)/build/dembox}
case $B in /*) ;; *) B=$(pwd)/$B ;; esac
mkdir -p "$OUT"
cd "$OUT"
"$B" example biaxial2d-paper > paper.cfg
# the preparation alone: the example's first stage
python3 - <<'EOF'
s = open('paper.cfg').read()
a = s.index('stages = (')
b = s.index(');', a) + 2
stage0 = s[a:s.index('},', a) + 1]
open('prep.cfg', 'w').write(s[:a] + stage0 + '\n);' + s[b:])
EOF
for s in 1 2 3 4; do
    [ -f prep$s/particles_final.csv ] ||
        "$B" run prep.cfg --set seed=$s --threads 1 --quiet -o prep$s
    # the packing inside a box at its extent (+1e-9), from the origin
    python3 - "$s" <<'EOF'
import csv, sys
s = sys.argv[1]
rows = list(csv.DictReader(open('prep%s/particles_final.csv' % s)))
lo, L = [], []
for c in 'xy':
    a = min(float(r[c]) - float(r['radius']) for r in rows)
    b = max(float(r[c]) + float(r['radius']) for r in rows)
    L.append((b - a) * (1 + 1e-9))
    lo.append(a - (L[-1] - (b - a)) / 2)
with open('start%s.csv' % s, 'w', newline='') as f:
    w = csv.writer(f)
    w.writerow(rows[0].keys())
    for r in rows:
        r['x'] = repr(float(r['x']) - lo[0])
        r['y'] = repr(float(r['y']) - lo[1])
        w.writerow(r.values())
open('box%s' % s, 'w').write('%r %r\n' % tuple(L))
EOF
    read -r Lx Ly < box$s
    for mm in sphere disc; do
        [ -f $mm$s/summary.json ] && continue
        "$B" run paper.cfg --set particles.placement=file \
            --set particles.file=start$s.csv --set "box.size=[$Lx,$Ly,0.0]" \
            --set particles.mass_model=$mm --set stages.1.strain=0.1 \
            --set stages.1.duration=0.2 --threads 1 --quiet -o $mm$s
    done
done
python3 - <<'EOF'
import json, statistics as st
phi = {(m, s): json.load(open('%s%d/summary.json' % (m, s)))['peak']['phi_deg']
       for m in ('sphere', 'disc') for s in (1, 2, 3, 4)}
for s in (1, 2, 3, 4):
    print('seed %d: phi_peak sphere inertia %.2f, disc inertia %.2f deg'
          % (s, phi[('sphere', s)], phi[('disc', s)]))
d = [phi[('disc', s)] - phi[('sphere', s)] for s in (1, 2, 3, 4)]
print('disc - sphere: %.2f +- %.2f deg (mean +- standard error)'
      % (st.mean(d), st.stdev(d) / len(d) ** 0.5))
EOF
