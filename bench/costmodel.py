#!/usr/bin/env python3
"""Cost model of a spatial domain decomposition of one dembox run over P
MPI ranks (docs/parallel.md, "Cost model"): time per step from the
measured cost per particle-step and the ghost exchange and reductions a
decomposition needs. Prints strong and weak scaling for 64-1024 ranks.

    python3 bench/costmodel.py [--c NS] [--alpha US] [--beta GBS]

Assumptions (each a flag):
  c      ns per particle-step on one core at large N (measured: 130-170 ns
         for 3D, N = 20000, AMD EPYC Zen 3; docs/performance.md)
  alpha  latency of one MPI message, us (InfiniBand: 1-2 us)
  beta   bandwidth one rank gets, GB/s (a 100 Gb/s NIC shared by 32
         ranks: about 0.4 GB/s each)
Geometry: spheres of diameter d at solid fraction 0.6 (number density
1.15 / d^3), cubic subdomains, interaction range r_c = 1.2 d (largest
diameter plus the neighbour skin). Ghosts: a half shell (the faces
towards +x, +y, +z, LAMMPS's 'newton on'), so every pair is computed
once, positions, velocities and spins go out (9 doubles per ghost) and
forces and torques come back (6 doubles). Six messages out and six back
per step (the staged exchange: 2 per axis). Every step also needs one
global sum of the wall forces and the stress (about 30 doubles): an
allreduce of 2 log2(P) latencies. Packing and unpacking a ghost: 10 ns.
Migration and neighbour rebuilds (every 10-50 steps) are left out: a few
per cent of the ghost traffic.

--shell full models what src/decomp/halo.c does now instead ("newton
off"): ghosts from all around (a full shell, about twice the volume),
9 doubles out and nothing back, a pair across a cut computed by both
ranks (counted as 0.3 c per half-shell ghost: about two pairs each at the
pair loop's share of c), and the ghosts sent to and received from the
neighbours that hold them (26 messages each way at most, all under way at
once; counted as one latency each).
"""
import argparse
import math

p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
p.add_argument("--c", type=float, default=150.0)
p.add_argument("--alpha", type=float, default=1.5)
p.add_argument("--beta", type=float, default=0.4)
p.add_argument("--shell", choices=("half", "full"), default="half")
a = p.parse_args()
c, alpha, beta = a.c * 1e-9, a.alpha * 1e-6, a.beta * 1e9
n_d3, rc = 1.15, 1.2  # particles per d^3, interaction range in d


def step(N, P):
    """Seconds per step and its parts for N particles on P ranks."""
    local = N / P
    comp = c * local
    if P == 1:
        return comp, comp, 0.0, 0.0, 0.0
    L = (local / n_d3) ** (1.0 / 3.0)  # subdomain side, in d
    half = n_d3 * ((L + rc) ** 3 - L ** 3)  # half shell
    if a.shell == "half":
        ghosts = half
        comm = 12 * alpha + ghosts * (9 + 6) * 8 / beta + 2 * 10e-9 * ghosts
    else:
        ghosts = n_d3 * ((L + 2 * rc) ** 3 - L ** 3)
        comm = min(P - 1, 26) * alpha + ghosts * 9 * 8 / beta + 10e-9 * ghosts
        comp += 0.3 * c * half
    red = 2 * alpha * math.log2(P)
    return comp + comm + red, comp, comm, red, ghosts


def row(N, P, ref):
    t, comp, comm, red, g = step(N, P)
    eff = ref / (P * t)
    return ("| %8.2g | %5d | %9.0f | %7.0f | %8.1f | %8.1f | %8.1f | %8.1f | %4.0f %% |"
            % (N, P, N / P, g, comp * 1e6, comm * 1e6, red * 1e6, t * 1e6,
               100 * eff))


head = ("|        N |     P | N/P       | ghosts  | compute  | ghosts   | reduce   | step     | eff.   |\n"
        "|          |       |           | per rank| us       | us       | us       | us       |        |\n"
        "|---|---|---|---|---|---|---|---|---|")
print("c = %.0f ns, alpha = %.1f us, beta = %.2f GB/s per rank, %s shell\n"
      % (a.c, a.alpha, a.beta, a.shell))
print("Strong scaling (parallel efficiency against one rank)\n")
print(head)
for N in (1e6, 1e7):
    ref = step(N, 1)[0]
    for P in (64, 128, 256, 512, 1024):
        print(row(N, P, ref))
print("\nWeak scaling (efficiency against N/P particles on one rank)\n")
print(head)
for local in (1e4, 1e5):
    for P in (64, 128, 256, 512, 1024):
        print(row(local * P, P, step(local, 1)[0] * P))
# where the step's communication equals its computation
for P in (64, 1024):
    lo, hi = 1.0, 1e8
    for _ in range(100):
        mid = math.sqrt(lo * hi)
        t, comp, comm, red, g = step(mid * P, P)
        lo, hi = (mid, hi) if comm + red > comp else (lo, mid)
    print("\nP = %d: communication = computation at N/P = %.0f" % (P, hi))
