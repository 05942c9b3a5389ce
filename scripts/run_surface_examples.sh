#!/usr/bin/env bash
# Examines every random surface in surfaces/ (200 realisations, seed 1) and runs every
# study in studies/surfaces/, with figures; results go to results/surfaces/
# (or $STENGMC_RESULTS_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/surfaces}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
failed=()
for surface in surfaces/*.toml; do
  grep -q '^kind = "random"' "$surface" || continue
  name=$(basename "$surface" .toml)
  echo "=== surface $name"
  if ! "$stengmc" surface "$surface" --realisations 200 --seed 1 --out "$out/${name}_surface.h5" --figures; then
    failed+=("$name")
  fi
done
for study in studies/surfaces/*.toml; do
  name=$(basename "$study" .toml)
  echo "=== study $name"
  if ! "$stengmc" run "$study" --out "$out/$name.h5" --figures; then
    failed+=("$name")
  fi
done
echo
echo "Surface results (HDF5): $(realpath "$out")/*.h5"
echo "Surface figures (PNG):  $(realpath "$out")/*.png"
if ((${#failed[@]})); then
  echo "FAILED: ${failed[*]}" >&2
  exit 1
fi
