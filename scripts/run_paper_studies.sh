#!/usr/bin/env bash
# Runs every study in studies/paper/ with figures; results go to results/paper/.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p results/paper
failed=()
for study in studies/paper/*.toml; do
  name=$(basename "$study" .toml)
  echo "=== $name"
  if ! ./build/src/stengmc run "$study" --out "results/paper/$name.h5" --figures; then
    failed+=("$name")
  fi
done
bash scripts/paper_comparisons.sh
echo
echo "Results (HDF5): $(pwd)/results/paper/*.h5"
echo "Figures (PNG):  $(pwd)/results/paper/*.png"
if ((${#failed[@]})); then
  echo "FAILED studies: ${failed[*]}" >&2
  exit 1
fi
