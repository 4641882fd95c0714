#!/bin/bash
# dembox against LAMMPS and LIGGGHTS on the same packing and workload.
#
# usage: bench/peers.sh [--dim 2|3] [--n N] [--steps S] [--np P]
#                       [--codes "dembox lammps-hh lammps-gr liggghts"]
#                       [--replicate K] [--data DIR] [--dembox PATH]
#                       [--work DIR] [--dembox-ranks]
#
#   --dim, --n      the packing DIR/pack{dim}d_{N}.data (LAMMPS data file,
#                   atom_style sphere); default 3D N = 3375 (2D N = 1950)
#   --steps         timed steps of every code (default 20000)
#   --np            MPI ranks of the peers and OpenMP threads of dembox
#                   (default 1; 1 = plain serial launch, no mpirun)
#   --dembox-ranks  dembox as --np MPI ranks of one thread each (its
#                   domain decomposition, `mpirun -np NP dembox bench`)
#                   instead of --np threads: the same launch as the peers
#   --codes         which codes to run (default: all four)
#                     dembox     dembox bench --data <the same file>
#                     lammps-hh  pair_style gran/hooke/history
#                                (mass-normalised damping, as in the peers'
#                                reference runs)
#                     lammps-gr  pair_style granular hooke + linear_history,
#                                damping velocity (absolute damping: the
#                                exact mapping of dembox's law)
#                     liggghts   model hooke/stiffness, absolute damping
#   --replicate K   tile the periodic packing K times along every axis
#                   (K^3 N particles in 3D, K^2 N in 2D; written to the
#                   work folder as pack{dim}d_{K^dim N}.data, which every
#                   code then reads): large packings with the very local
#                   structure of the small one, for per-particle costs
#   --data          folder of the packings (default $DEMBOX_BENCH_DATA or
#                   ../shared/bench/data next to this repository)
#   --dembox        the dembox binary (default build/dembox of this tree)
#   --work          folder for the inputs and logs (default: a new
#                   temporary folder, kept and printed)
#   --peer-skin S   the peers' neighbour skin in m (default 0.1 mean
#                   diameter, as in ../shared/bench: 0.001 in 3D, 0.0002
#                   in 2D); dembox adapts its own skin (docs/physics.md)
#
# The LAMMPS and LIGGGHTS inputs are written here (they follow the
# workload of ../shared/bench/run{2,3}d.{lmp,lgt} next to this repository,
# see ../shared/bench/README.md): periodic box, fix nve/sphere, fix viscous
# (background damping on translation), fix deform (isochoric compression at
# the strain rate dembox's wall applies). dembox uses walls instead (see
# docs/performance.md). Loop times come from each code's own timer
# ("Loop time of ..."; dembox: its timed loop only), so preparation and
# start-up are excluded everywhere. Prints a Markdown table; a requested code
# that is not installed or fails is a row "not run: why" of the table, and
# the exit status is then 1. Run one case at a time on an otherwise idle
# machine. Never run by CTest.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
DIM=3 N= STEPS=20000 NP=1 REP=1
CODES="dembox lammps-hh lammps-gr liggghts"
DATA=${DEMBOX_BENCH_DATA:-$here/../../shared/bench/data}
DEMBOX=$here/../build/dembox
WORK= DEMBOX_RANKS=0 PEER_SKIN=

die() { echo "peers.sh: $*" >&2; exit 1; }
while [ $# -gt 0 ]; do
  case $1 in
    --dim) DIM=${2:?}; shift 2 ;;
    --n) N=${2:?}; shift 2 ;;
    --steps) STEPS=${2:?}; shift 2 ;;
    --np) NP=${2:?}; shift 2 ;;
    --replicate) REP=${2:?}; shift 2 ;;
    --codes) CODES=${2:?}; shift 2 ;;
    --data) DATA=${2:?}; shift 2 ;;
    --dembox) DEMBOX=${2:?}; shift 2 ;;
    --work) WORK=${2:?}; shift 2 ;;
    --dembox-ranks) DEMBOX_RANKS=1; shift ;;
    --peer-skin) PEER_SKIN=${2:?}; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument $1 (see --help)" ;;
  esac
done
case $DIM in 2|3) ;; *) die "--dim must be 2 or 3" ;; esac
[ -n "$N" ] || { [ "$DIM" = 3 ] && N=3375 || N=1950; }
[[ $N =~ ^[0-9]+$ ]] || die "--n must be a positive integer"
[[ $STEPS =~ ^[1-9][0-9]*$ ]] || die "--steps must be a positive integer"
[[ $NP =~ ^[1-9][0-9]*$ ]] || die "--np must be a positive integer"
[[ $REP =~ ^[1-9][0-9]*$ ]] || die "--replicate must be a positive integer"
[ -z "$PEER_SKIN" ] || [[ $PEER_SKIN =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]] ||
  die "--peer-skin must be a positive number (m)"
PACK=$DATA/pack${DIM}d_${N}.data
[ -f "$PACK" ] || die "$PACK: no such packing (prepare it as in ../shared/bench/README.md)"
PACK=$(cd "$(dirname "$PACK")" && pwd)/$(basename "$PACK")
[ -n "$WORK" ] || WORK=$(mktemp -d "${TMPDIR:-/tmp}/dembox-peers.XXXXXX")
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)

# Tile the periodic packing REP times per axis: copy (a, b, c) is shifted
# by a, b, c box lengths and its ids by the copy's number times N. Image
# flags are dropped (the positions lie in the box).
if [ "$REP" -gt 1 ]; then
  N=$(( N * REP ** DIM ))
  TILED=$WORK/pack${DIM}d_${N}.data
  awk -v K="$REP" -v dim="$DIM" '
    function copies(line, sec,   f, nf, a, b, c, m, o) {
      nf = split(line, f, " ")
      for (c = 0; c < (dim == 3 ? K : 1); c++)
        for (b = 0; b < K; b++)
          for (a = 0; a < K; a++) {
            m = (c * K + b) * K + a
            o = (f[1] + m * n0)
            if (sec == 1)
              printf "%d %s %s %s %.17g %.17g %.17g 0 0 0\n", o, f[2], f[3], f[4],
                     f[5] + a * L[1], f[6] + b * L[2], f[7] + c * L[3]
            else
              printf "%d %s %s %s %s %s %s\n", o, f[2], f[3], f[4], f[5], f[6], f[7]
          }
    }
    / atoms$/ {n0 = $1; printf "%d atoms\n", n0 * K ^ dim; next}
    / xlo xhi$/ {L[1] = $2 - $1; printf "%.17g %.17g xlo xhi\n", $1, $1 + K * L[1]; next}
    / ylo yhi$/ {L[2] = $2 - $1; printf "%.17g %.17g ylo yhi\n", $1, $1 + K * L[2]; next}
    / zlo zhi$/ {L[3] = $2 - $1; c3 = dim == 3 ? K : 1
                 printf "%.17g %.17g zlo zhi\n", $1, $1 + c3 * L[3]; next}
    /^Atoms/ {sec = 1; print; next}
    /^Velocities/ {sec = 2; print; next}
    /^[A-Za-z]/ {sec = 0; print; next}
    sec > 0 && NF >= 7 {copies($0, sec); next}
    {print}' "$PACK" > "$TILED"
  PACK=$TILED
fi
TAG=${DIM}d_${N}_s${STEPS}_np${NP}
LOAD0=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")

# ---------------------------------------------------------------- workload
# One place for the numbers; docs/performance.md has the mapping table.
if [ "$DIM" = 3 ]; then
  DT=2.0e-5 SKIN=0.001 GAMMA_B=0.001
  KN=5000.0 KT=1000.0 MU=0.5
  ETA_N=0.05 ETA_T=0.005            # kg/s, absolute (dembox, granular, LIGGGHTS)
  HH_GN=95.5 HH_GT=9.55             # 1/s, = eta / m_eff(two 5 mm spheres)
  DEFORM="z erate -0.05 x volume y volume remap x"
  DIMLINE="" ENFORCE=""
else
  DT=2.0e-7 SKIN=0.0002 GAMMA_B=0.0004
  KN=1.0e5 KT=2.0e4 MU=0.5
  ETA_N=0.0211 ETA_T=0.00211
  HH_GN=5045.0 HH_GT=504.5          # 1/s, = eta / m_eff(two 1 mm spheres)
  DEFORM="y erate -2.5 x volume remap x"
  DIMLINE="dimension       2" ENFORCE="fix             e2d all enforce2d"
fi
SKIN=${PEER_SKIN:-$SKIN}

if [ "$NP" -gt 1 ]; then
  # more ranks than cores: oversubscribed, unbound, and waiting ranks
  # yield their core (state it with the figures)
  BIND=(--bind-to core)
  [ "$NP" -gt "$(env -u OMP_NUM_THREADS nproc)" ] &&
    BIND=(--oversubscribe --bind-to none --mca mpi_yield_when_idle 1)
  LAUNCH=(mpirun -np "$NP" "${BIND[@]}")
  [ "$(id -u)" = 0 ] && LAUNCH=(mpirun --allow-run-as-root -np "$NP" "${BIND[@]}")
else
  LAUNCH=()
fi

write_lammps() { # $1 = hh | gr
  local pair
  if [ "$1" = hh ]; then
    pair="pair_style      gran/hooke/history $KN $KT $HH_GN $HH_GT $MU 1
pair_coeff      * *"
  else
    pair="pair_style      granular
pair_coeff      * * hooke $KN $ETA_N tangential linear_history $KT 0.1 $MU damping velocity"
  fi
  cat > "$WORK/in.$TAG.lammps-$1" <<EOF
# dembox bench/peers.sh: LAMMPS, $DIM D, N = $N, $STEPS steps, model $1
units           si
$DIMLINE
atom_style      sphere
atom_modify     map array
boundary        p p p
comm_modify     vel yes
read_data       $PACK
neighbor        $SKIN bin
neigh_modify    delay 0 every 1 check yes
$pair
timestep        $DT
fix             integ all nve/sphere
$ENFORCE
fix             bgdamp all viscous $GAMMA_B
fix             d all deform 1 $DEFORM
compute         cn all contact/atom
compute         z all reduce ave c_cn
thermo_style    custom step atoms ke c_z cpu
thermo_modify   norm no
thermo          $(( STEPS / 4 > 0 ? STEPS / 4 : 1 ))
run             $STEPS
EOF
}

write_liggghts() {
  # LIGGGHTS reads "Atoms" without the "# sphere" comment, and in 2D gives
  # a disc the mass pi r^2 rho: rescale the density column so the masses
  # are LAMMPS's sphere masses (the same fix as ../shared/bench/run_bench.sh).
  awk -v dim="$DIM" '
    /^Atoms/ {print "Atoms"; sec=1; next}
    /^Velocities/ {print "Velocities"; sec=0; next}
    sec==1 && NF>=7 && dim==2 {$4 = sprintf("%.10g", $4*2.0/3.0*$3)}
    {print}' "$PACK" > "$WORK/pack.$TAG.lgt.data"
  cat > "$WORK/in.$TAG.liggghts" <<EOF
# dembox bench/peers.sh: LIGGGHTS, $DIM D, N = $N, $STEPS steps
$DIMLINE
atom_style      granular
atom_modify     map array
boundary        p p p
newton          off
communicate     single vel yes
units           si
read_data       $WORK/pack.$TAG.lgt.data
neighbor        $SKIN bin
neigh_modify    delay 0
fix m1 all property/global kn peratomtypepair 1 $KN
fix m2 all property/global kt peratomtypepair 1 $KT
fix m3 all property/global gamman_abs peratomtypepair 1 $ETA_N
fix m4 all property/global gammat_abs peratomtypepair 1 $ETA_T
fix m5 all property/global coefficientFriction peratomtypepair 1 $MU
pair_style      gran model hooke/stiffness tangential history absolute_damping on tangential_damping on
pair_coeff      * *
timestep        $DT
fix             integ all nve/sphere
$ENFORCE
fix             bgdamp all viscous $GAMMA_B
fix             d all deform 1 $DEFORM
compute         cn all contact/atom
compute         z all reduce ave c_cn
thermo_style    custom step atoms ke c_z cpu
thermo_modify   norm no
thermo          $(( STEPS / 4 > 0 ? STEPS / 4 : 1 ))
run             $STEPS
EOF
}

# CPU use of the loop in % per rank/thread: LAMMPS prints it for the loop,
# dembox for its timed loop; LIGGGHTS does not, so its figure is
# /usr/bin/time's for the whole process. Below ~100 % the machine was busy.
cpu_lammps() { awk '/% CPU use/ {sub("%", "", $1); print $1}' "$1" | tail -1; }
cpu_time_v() { awk -F': ' '/Percent of CPU/ {sub("%", "", $2); printf "%.0f (process)", $2 / np}' np="$NP" "$1" 2>/dev/null; }
# Peak RSS in MB from a /usr/bin/time -v file ("-" if none).
peak_mb() { awk -F': ' '/Maximum resident/ {printf "%.0f", $2/1024; f=1} END {if (!f) print "-"}' "$1" 2>/dev/null || echo -; }
TIMEV=()
[ -x /usr/bin/time ] && TIMEV=(/usr/bin/time -v -o)

# run_peer CODE -> prints "seconds" of the loop, or nothing
rows=()
add_row() { rows+=("$*"); }
# a requested code that did not run is a row of its own (and exit status 1),
# so that a table without it never passes for a complete comparison
not_run=()
skip() { # $1 = code, $2 = why
  echo "peers.sh: $1: $2" >&2
  not_run+=("$1|$2")
}

run_lammps() { # $1 = hh | gr
  command -v lmp >/dev/null || { skip "lammps-$1" "lmp not installed"; return; }
  write_lammps "$1"
  local base=$WORK/$TAG.lammps-$1
  local t=()
  [ ${#TIMEV[@]} -gt 0 ] && t=("${TIMEV[@]}" "$base.time")
  (cd "$WORK" && OMP_NUM_THREADS=1 "${t[@]}" "${LAUNCH[@]}" lmp -in "in.$TAG.lammps-$1" -log "$base.log" -screen none) \
    || { skip "lammps-$1" "failed, see $base.log"; return; }
  local secs
  secs=$(awk '/^Loop time of/ {print $4}' "$base.log" | tail -1)
  local model=gran/hooke/history
  [ "$1" = gr ] && model="granular (damping velocity)"
  add_row "lammps|$model|$NP ranks|$secs|$(peak_mb "$base.time")|$(cpu_lammps "$base.log")"
}

run_liggghts() {
  command -v liggghts >/dev/null || { skip liggghts "liggghts not installed"; return; }
  write_liggghts
  local base=$WORK/$TAG.liggghts
  local t=()
  [ ${#TIMEV[@]} -gt 0 ] && t=("${TIMEV[@]}" "$base.time")
  (cd "$WORK" && OMP_NUM_THREADS=1 "${t[@]}" "${LAUNCH[@]}" liggghts -in "in.$TAG.liggghts" -log "$base.log" -screen none) \
    || { skip liggghts "failed, see $base.log"; return; }
  local secs
  secs=$(awk '/^Loop time of/ {print $4}' "$base.log" | tail -1)
  add_row "liggghts|hooke/stiffness (absolute damping)|$NP ranks|$secs|$(peak_mb "$base.time")|$(cpu_time_v "$base.time")"
}

run_dembox() {
  [ -x "$DEMBOX" ] || { skip dembox "$DEMBOX not built"; return; }
  local base=$WORK/$TAG.dembox
  local t=()
  [ ${#TIMEV[@]} -gt 0 ] && t=("${TIMEV[@]}" "$base.time")
  # the packing is prepared once (untimed) and cached; the loop alone is
  # timed (over ranks: rank 0's loop, which waits for the others)
  local threads=$NP what="$NP threads" launch=()
  if [ "$DEMBOX_RANKS" = 1 ] && [ "$NP" -gt 1 ]; then
    threads=1 what="$NP ranks" launch=("${LAUNCH[@]}")
  fi
  OMP_NUM_THREADS=$threads "${t[@]}" "${launch[@]}" "$DEMBOX" bench --dim "$DIM" \
    --n "$N" --steps "$STEPS" --threads "$threads" --data "$PACK" --quiet \
    > "$base.log" 2>&1 \
    || { cat "$base.log" >&2; skip dembox "failed, see $base.log"; return; }
  local secs
  secs=$(awk '/^loop:/ {print $2}' "$base.log")
  add_row "dembox|linear + tangential history (walls)|$what|$secs|$(peak_mb "$base.time")|$(awk '/^cpu:/ {print $4}' "$base.log")"
}

for c in $CODES; do
  case $c in
    dembox) run_dembox ;;
    lammps-hh) run_lammps hh ;;
    lammps-gr) run_lammps gr ;;
    liggghts) run_liggghts ;;
    *) die "unknown code $c" ;;
  esac
done

# ------------------------------------------------------------------ table
echo "# $(date -u +%Y-%m-%dT%H:%MZ)  $(nproc) cores  $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')"
echo "# load average before: $LOAD0, after: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")"
echo "# packing $PACK, logs and inputs in $WORK"
echo
# On a busy machine the wall-clock ratio depends on who got the cores; the
# rate per CPU-second (N * steps / CPU seconds of all ranks or threads) is
# the steadier comparison there. CPU use % is per rank/thread.
echo "| code | model | dim | N | steps | ranks/threads | loop s | particle-steps/s | dembox/code | CPU use % | particle-steps per CPU-s | dembox/code per CPU-s | peak RSS MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
dembox_pss= dembox_cpu=
for r in "${rows[@]}"; do
  IFS='|' read -r code _ _ secs _ cpu <<<"$r"
  if [ "$code" = dembox ]; then
    dembox_pss=$(awk -v n="$N" -v s="$STEPS" -v t="$secs" 'BEGIN {print n*s/t}')
    dembox_cpu=$(awk -v p="$dembox_pss" -v c="${cpu%% *}" -v np="$NP" 'BEGIN {if (c > 0) print p/(c/100*np)}')
  fi
done
for r in "${rows[@]}"; do
  IFS='|' read -r code model par secs rss cpu <<<"$r"
  awk -v code="$code" -v model="$model" -v dim="$DIM" -v n="$N" -v s="$STEPS" \
      -v par="$par" -v t="$secs" -v d="$dembox_pss" -v dc="$dembox_cpu" \
      -v rss="$rss" -v cpu="${cpu:--}" -v np="$NP" 'BEGIN {
    pss = n * s / t
    ratio = d != "" ? sprintf("%.2f", d / pss) : "-"
    split(cpu, c, " ")
    cpus = c[1] / 100 * np   # CPU-seconds per second of the loop, all ranks/threads
    pcpu = c[1] > 0 ? sprintf("%.3g", pss / cpus) : "-"
    rcpu = (c[1] > 0 && dc != "") ? sprintf("%.2f", dc / (pss / cpus)) : "-"
    printf "| %s | %s | %dD | %d | %d | %s | %.2f | %.3g | %s | %s | %s | %s | %s |\n",
           code, model, dim, n, s, par, t, pss, ratio, cpu, pcpu, rcpu, rss }'
done
for r in "${not_run[@]}"; do
  IFS='|' read -r code why <<<"$r"
  echo "| $code | not run: $why | ${DIM}D | $N | $STEPS | | | | | | | | |"
done
[ ${#not_run[@]} -eq 0 ] || exit 1
