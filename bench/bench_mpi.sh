#!/usr/bin/env bash
# Ensemble throughput over MPI ranks and threads on this machine (issue 13; README
# "Ensembles"): the quick identifiability sweep (studies/ensembles/identifiability_quick.toml,
# 12 grid points x 20 realisations) run as
#   1 rank  x 1 thread    (no mpirun: the reference)
#   2 ranks x 1 thread    (mpirun -np 2 ... -j 1)
#   1 rank  x 2 threads   (-j 2)
# each REPEATS times (default 3); prints the median wall time, realisations per second and
# the speed-up over the reference, and checks that every output is the reference's file
# (scripts/golden_digest.py same). Then runs bench_distribution (the cost of distributing
# and the scaling model).
#
#   bash bench/bench_mpi.sh [BUILD_DIR]     # default build; needs -DSTENGMC_BUILD_BENCHMARKS=ON
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
REPEATS=${REPEATS:-3}
STUDY=studies/ensembles/identifiability_quick.toml
REALISATIONS=240
MPIRUN=(mpirun --allow-run-as-root --oversubscribe --bind-to none)
SCRATCH=$(mktemp -d -p "$PWD" bench-mpi.XXXXXX)
trap 'rm -rf "$SCRATCH"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

# Prints the median wall time [s] of REPEATS runs of "$@" -o <file>; checks each file.
time_runs() {
  local name=$1; shift
  for ((i = 0; i < REPEATS; ++i)); do
    local out="$SCRATCH/$name.$i.h5"
    local start end
    start=$(date +%s.%N)
    "$@" -o "$out" > "$SCRATCH/$name.log" 2>&1 || { cat "$SCRATCH/$name.log"; exit 1; }
    end=$(date +%s.%N)
    echo "$end - $start" | bc -l
    if [[ -f "$SCRATCH/reference.h5" ]]; then
      /usr/bin/python3 scripts/golden_digest.py same "$SCRATCH/reference.h5" "$out" > /dev/null ||
        { echo "$name: the output differs from the one-process file" >&2; exit 1; }
    else
      cp "$out" "$SCRATCH/reference.h5"
    fi
  done | median
}

echo "== throughput: $STUDY ($REALISATIONS realisations), median of $REPEATS"
t11=$(time_runs p1t1 "$BUILD/src/stengmc" run "$STUDY" -j 1)
t21=$(time_runs p2t1 "${MPIRUN[@]}" -np 2 "$BUILD/src/stengmc" run "$STUDY" -j 1)
t12=$(time_runs p1t2 "$BUILD/src/stengmc" run "$STUDY" -j 2)
printf '  %-22s %8s %14s %10s\n' layout "wall [s]" "realisations/s" "speed-up"
for row in "1 rank x 1 thread:$t11" "2 ranks x 1 thread:$t21" "1 rank x 2 threads:$t12"; do
  t=${row##*:}
  printf '  %-22s %8.2f %14.1f %10.2f\n' "${row%%:*}" "$t" "$(echo "$REALISATIONS / $t" | bc -l)" \
    "$(echo "$t11 / $t" | bc -l)"
done
echo "  (every output identical to the 1 x 1 file: golden_digest.py same)"
echo
echo "== bench_distribution"
(cd "$SCRATCH" && "$BUILD/bench/bench_distribution")
