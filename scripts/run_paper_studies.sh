#!/usr/bin/env bash
# Runs every study in studies/paper/ with figures; results go to results/paper/
# (or $STENGMC_RESULTS_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/paper}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
failed=()
for study in studies/paper/*.toml; do
  name=$(basename "$study" .toml)
  echo "=== $name"
  if ! "$stengmc" run "$study" --out "$out/$name.h5" --figures; then
    failed+=("$name")
  fi
done
bash scripts/paper_comparisons.sh "$out"
echo
echo "Results (HDF5): $(realpath "$out")/*.h5"
echo "Figures (PNG):  $(realpath "$out")/*.png"
if ((${#failed[@]})); then
  echo "FAILED studies: ${failed[*]}" >&2
  exit 1
fi
