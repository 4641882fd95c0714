#!/bin/sh
# A sample split over 1, 2 and 4 MPI ranks (4 oversubscribe two cores)
# follows the undivided sample, in 3D and 2D (tests/mpi_decomp.c).
# Status 77 (skipped): no mpirun, or it cannot start two ranks here.
set -eu
PROG=${1:?usage: test_decomp_mpi.sh MPI_DECOMP}
. "$(dirname "$0")/mpi_env.sh"
for dim in 3 2; do
    for np in 1 2 4; do
        "$MPIRUN" -np "$np" $(mpi_opts "$np") "$PROG" "$dim"
    done
done
# the passes that keep the own particles' records from one chained step
# to the next, filling only the ghosts' (3D, two ranks)
for pass in records ring; do
    "$MPIRUN" -np 2 $(mpi_opts 2) "$PROG" 3 "$pass"
done
