#!/bin/sh
# SPDX-License-Identifier: MIT
# The sweep under MPI (docs/sweep.md): mpirun -np 3 gives the summary of a
# single-process run of the same slices, and a rank killed with SIGKILL
# mid-run loses nothing and counts nothing twice after --resume.
#   sweep_mpi.sh NOISEPIPE HAVE_MPI WORKDIR same|kill_resume
# Exit 77 (CTest SKIP_RETURN_CODE) when noisepipe has no MPI or mpirun is missing.
set -u
np=$1 have=$2 work=$3 case=$4
case "$have" in ON|1|TRUE|YES) ;; *) echo "noisepipe built without MPI: skipped"; exit 77 ;; esac
command -v mpirun >/dev/null 2>&1 || { echo "no mpirun on PATH: skipped"; exit 77; }
# OpenMPI refuses to run as root unless told (CI containers run as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi="mpirun --oversubscribe -np 3"
rm -rf "$work" && mkdir -p "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# The summary without the lines that depend on the run (time, processes, resumed count).
stable() { grep -v -e '^wall time' -e '^processes' -e '^x cells' "$1"; }

case "$case" in
same)
    $np sweep --z 0:6 --x-cells 0:2 > "$work/one.txt" || fail "single process: exit $?"
    $mpi $np sweep --z 0:6 --x-cells 0:2 > "$work/mpi.txt" || fail "mpirun: exit $?"
    cat "$work/mpi.txt"
    grep -q '^processes *3 (MPI on)' "$work/mpi.txt" || fail "the run did not use 3 MPI ranks"
    stable "$work/one.txt" > "$work/a" && stable "$work/mpi.txt" > "$work/b"
    diff "$work/a" "$work/b" || fail "mpirun -np 3 and one process differ"
    # A cheap configuration fails under MPI too (the check can fail): exit 1, one verdict.
    $mpi $np sweep --z 0:3 --x-cells 0:1 --config s_frac=4,lerp_frac=6 > "$work/cheap.txt"
    rc=$?
    [ $rc -eq 1 ] || fail "cheap configuration under mpirun: exit $rc, expected 1"
    [ "$(grep -c '^verdict: FAIL' "$work/cheap.txt")" -eq 1 ] || fail "expected one FAIL verdict"
    ;;
kill_resume)
    args="sweep --z 0:6 --x-cells 0:4"
    $mpi $np $args --journal "$work/j" > "$work/killed.txt" 2>&1 &
    mp=$!
    # Wait for two journalled blocks, then SIGKILL one rank (a child of mpirun).
    n=0 tries=0
    while [ "$n" -lt 2 ] && [ $tries -lt 600 ]; do
        sleep 0.05
        n=$(cat "$work"/j/*.journal 2>/dev/null | grep -c '^block ')
        tries=$((tries + 1))
    done
    victim=$(ps -o pid= --ppid $mp | head -n 1 | tr -d ' ')
    [ -n "$victim" ] || fail "no rank to kill"
    kill -9 "$victim" || fail "cannot kill rank $victim"
    wait $mp
    rc=$?
    [ $rc -ne 0 ] || fail "mpirun exited 0 although a rank was killed"
    done_blocks=$(cat "$work"/j/*.journal | grep -c '^block ')
    echo "killed rank $victim after $n journalled blocks; mpirun exit $rc; $done_blocks of 24 blocks journalled"
    [ "$done_blocks" -lt 24 ] || fail "the kill came after the run had finished"
    $mpi $np $args --journal "$work/j" --resume > "$work/resumed.txt" || fail "resume: exit $?"
    cat "$work/resumed.txt"
    resumed=$(sed -n 's/^x cells.* \([0-9][0-9]*\) resumed from the journal$/\1/p' "$work/resumed.txt")
    [ "${resumed:-0}" -gt 0 ] || fail "the resumed run took no block from the journals"
    [ "$(cat "$work"/j/*.journal | grep -c '^block ')" -eq 24 ] || fail "after the resume the journals should hold 24 blocks"
    $np $args > "$work/one.txt" || fail "single process: exit $?"
    stable "$work/one.txt" > "$work/a" && stable "$work/resumed.txt" > "$work/b"
    diff "$work/a" "$work/b" || fail "killed-and-resumed and uninterrupted summaries differ"
    ;;
*) fail "unknown case $case" ;;
esac
rm -rf "$work"
echo "ok"
