#!/usr/bin/env bash
# Runs the quick identifiability ensemble (studies/ensembles/identifiability_quick.toml:
# 6 counts x 2 stiffness spreads x 20 realisations, about a minute on two cores) with its
# figures; results go to results/ensembles/ (or $STENGMC_RESULTS_DIR). An interrupted run
# resumes where it stopped when this is run again.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/ensembles}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
"$stengmc" run studies/ensembles/identifiability_quick.toml --out "$out/identifiability_quick.h5" --figures
echo
echo "Ensemble results (HDF5): $(realpath "$out")/*.h5"
echo "Ensemble figures (PNG):  $(realpath "$out")/*.png"
