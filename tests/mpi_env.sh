# Sourced by the MPI tests: mpirun in $MPIRUN, set up to run as root (CI),
# in containers without a shared-memory single copy, one thread per rank;
# exit 77 (skipped) when there is no mpirun or it cannot start two ranks.
# mpi_opts NP: the options for NP ranks: ranks waiting in MPI yield their
# core only when there are more ranks than cores (2 ranks on 2 cores
# beside another busy process ran 100x slower yielding: docs/parallel.md).
MPIRUN=${MPIEXEC:-mpirun}
command -v "$MPIRUN" > /dev/null || { echo "no $MPIRUN: skipped"; exit 77; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMP_NUM_THREADS=1
"$MPIRUN" -np 2 --oversubscribe true > /dev/null 2>&1 ||
    { echo "mpirun cannot start 2 ranks here: skipped"; exit 77; }
mpi_opts() {
    if [ "$1" -gt "$(nproc)" ]; then
        echo "--oversubscribe --mca mpi_yield_when_idle 1"
    else
        echo "--oversubscribe"
    fi
}
