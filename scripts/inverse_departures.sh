#!/usr/bin/env bash
# The uncalibrated estimator, one departure from the ideal device at a time (docs/inverse.md,
# "Limits"): for each family, a copy of studies/inverse/device_vb10_real.toml whose [inverse]
# prior keeps only that departure (the estimator is told which to expect: its own prior, no
# bank) is given to tests/inverse/inverse_harness, which simulates records of it as a
# calibration does and prints the exact-count rate, the count's RMSE, the median-k error and
# the sd(ln k) RMSE by n bin, with the CPU time per record. Families: ideal, loads (load CV
# 0.2-0.6), onset (U(0, 20 us)), tolerance (+-5 %), noise (white + 1/f^alpha, offset), all.
#   scripts/inverse_departures.sh [records per family] [seed]     (default 20, 4242; ~15 min)
# Output: results/inverse/departures/<family>.log and the summary table on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
records=${1:-20}
seed=${2:-4242}
harness=./build/tests/inverse_harness
[[ -x $harness ]] || { echo "inverse_departures: build first (bash scripts/build.sh): no $harness" >&2; exit 1; }
out=results/inverse/departures
mkdir -p "$out"
base=studies/inverse/device_vb10_real.toml

# family KEY=VALUE...: the broadened device with only the departures given left in its prior.
family() {
  local name=$1; shift
  local ideal=(load_cv='[0, 0]' onset_s='[0, 0]' parameter_tolerance=0 noise='"white"' offset=false)
  local script=()
  for setting in "${ideal[@]}" "$@"; do
    script+=(-e "s|^${setting%%=*} = .*|${setting%%=*} = ${setting#*=}|")
  done
  sed "${script[@]}" "$base" > "$out/$name.toml"
}
family ideal
family loads load_cv='[0.2, 0.6]'
family onset onset_s='[0, 20e-6]'
family tolerance parameter_tolerance=0.05
family noise noise='"coloured"' offset=true
family all load_cv='[0.2, 0.6]' onset_s='[0, 20e-6]' parameter_tolerance=0.05 noise='"coloured"' offset=true

printf '| family | records | n exact | n RMSE | median-k error (median) | sd(ln k) RMSE | CPU per record |\n|---|---|---|---|---|---|---|\n'
for name in ideal loads onset tolerance noise all; do
  OMP_NUM_THREADS=1 "$harness" "$out/$name.toml" "$records" "$seed" > "$out/$name.log" 2>&1
  # The harness's `all` row: "all N n RMSE x exact y % median-k |rel err| median z sd(ln k) RMSE w T ms".
  awk -v family="$name" '$1 == "all" {
    printf "| %s | %s | %s %% | %s | %s | %s | %.2f s |\n", family, $2, $7, $5, $13, $17, $18 / 1000 }' "$out/$name.log"
done
