#!/usr/bin/env bash
# Ensemble throughput over MPI ranks and threads on this machine (issue 13; README
# "Ensembles"): the quick identifiability sweep (studies/ensembles/identifiability_quick.toml,
# 12 grid points x 20 realisations, ~6 ms each) and 40 realisations of the shipped GW
# surface (~10 ms each, 200 of them) run as
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

# Prints the table of the three layouts for study $1 of $2 realisations.
throughput() {
  local study=$1 realisations=$2
  rm -f "$SCRATCH/reference.h5"
  echo "== throughput: $study ($realisations realisations), median of $REPEATS"
  t11=$(time_runs p1t1 "$BUILD/src/stengmc" run "$study" -j 1)
  t21=$(time_runs p2t1 "${MPIRUN[@]}" -np 2 "$BUILD/src/stengmc" run "$study" -j 1)
  t12=$(time_runs p1t2 "$BUILD/src/stengmc" run "$study" -j 2)
  printf '  %-22s %8s %14s %10s\n' layout "wall [s]" "realisations/s" "speed-up"
  for row in "1 rank x 1 thread:$t11" "2 ranks x 1 thread:$t21" "1 rank x 2 threads:$t12"; do
    t=${row##*:}
    printf '  %-22s %8.2f %14.1f %10.2f\n' "${row%%:*}" "$t" "$(echo "$realisations / $t" | bc -l)" \
      "$(echo "$t11 / $t" | bc -l)"
  done
  echo "  (every output identical to the 1 x 1 file: golden_digest.py same)"
}

throughput "$STUDY" "$REALISATIONS"
# Fewer, costlier records: the shipped GW surface (~24 asperities, 50 us).
cat > "$SCRATCH/gw.toml" <<TOML
seed = 3
duration_s = 50e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
[surface]
file = "$PWD/surfaces/pet_on_steel_gw.toml"
[domain]
policy = "flag"
[spectrum]
window = "hann"
start_s = 5e-6
prominence_over_floor = 10
min_frequency_hz = 100e3
high_resolution = false
[ensemble]
realisations = 200
trace_realisations = []
TOML
echo
throughput "$SCRATCH/gw.toml" 200
echo
launch=$(for ((i = 0; i < REPEATS; ++i)); do
  start=$(date +%s.%N); "${MPIRUN[@]}" -np 2 "$BUILD/src/stengmc" --version > /dev/null; end=$(date +%s.%N)
  echo "$end - $start" | bc -l
done | median)
printf '== mpirun -np 2 launch and MPI start-up alone (stengmc --version): %.2f s (in every 2-rank time above)\n' "$launch"
echo
echo "== bench_distribution"
(cd "$SCRATCH" && "$BUILD/bench/bench_distribution")
