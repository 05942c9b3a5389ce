#!/usr/bin/env bash
# The tracking examples (docs/tracking.md): studies/monitoring/record_unexcited.toml and
# record_excited.toml (1 ms, four asperities that arrive, step, wear and leave) simulated, then
# tracked with their known devices, with figures. The unexcited one is tracked well; the
# excited one shows what the first version does not do yet. Results go to
# results/tracking_demo/ (or $STENGMC_RESULTS_DIR); a few seconds each.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/tracking_demo}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
for regime in unexcited excited; do
  "$stengmc" run "studies/monitoring/record_$regime.toml" -o "$out/record_$regime.h5" > /dev/null
  "$stengmc" track "$out/record_$regime.h5" --known "studies/monitoring/device_$regime.toml" \
    -o "$out/record_${regime}_track.h5" --figures
done
echo "(truth: onsets 0, 150, 300, 550 us; k 60 -> 66 N/m at 400 us; the 95 N/m asperity released at 700 us;"
echo " the 130 N/m one wearing 20 %/ms; the 42 N/m one from 550 us: studies/monitoring/record_*.toml)"
echo
echo "Tracking demo (HDF5): $(realpath "$out")/*.h5"
echo "Tracking demo figures: $(realpath "$out")/*_track.png"
